/* moraine: the physical-sanity watchdog of a run.
 *
 * The state check after each step (solver/simulation.h) stops a run on a
 * non-finite value, an inverted particle or a particle outside the grid. An
 * instability against walls can stay clear of all three: the wall clamp keeps
 * the particles inside and the values finite while the energy grows without
 * bound. The watchdog looks at the physics instead, every `every` steps of
 * mrn_run (and after the first):
 *   energy  W_MPM > energy * E_scale: the discretisation created more energy
 *           than the problem holds (000, Eq. 68; E_scale below);
 *   dt      an explicit step dt > dt * h / max_p(c_p + |v_p|), the particle
 *           CFL estimate (002, Eqs. 34-37);
 *   speed   a particle moved more than `speed` cells in an explicit step
 *           (|v| dt > speed * h): the transfers assume it crosses at most one.
 * E_scale = E_k + E_el when run{} started + M |g| L (the potential energy of
 * all the mass falling across the grid, L the grid's extent along g) + the
 * magnitudes of the booked work W_pl, W_friction, W_damping, W_external,
 * of the energy in- and outflow E_inflow, W_inflow, E_outflow,
 * and at least 1e-6 * M (h / dt)^2 / 2 (all the mass moving a thousandth of
 * a cell per step), so that a problem with no energy at all has a scale.
 * A velocity face or constraint with a non-zero velocity does work that the
 * balance does not book: the energy test is then off (the others stay).
 * A bound of 0 turns its test off. */
#ifndef MRN_SOLVER_WATCHDOG_H
#define MRN_SOLVER_WATCHDOG_H

struct mrn_sim;

typedef struct mrn_watchdog {
  double energy; /* bound on W_MPM / E_scale (default 1) */
  double dt;     /* bound on dt / particle CFL estimate, explicit steps (default 4) */
  double speed;  /* bound on cells crossed per explicit step (default 1) */
  long every;    /* steps between checks (default 10) */
} mrn_watchdog;

/* what a run's checks saw, for sim:watchdog() and the tests */
typedef struct mrn_watchdog_state {
  double e_start;  /* E_k + E_el when the run started (J) */
  double peak_energy, peak_dt, peak_speed; /* the largest ratios seen */
  long checks;
  long last_step;  /* the step of the last check */
} mrn_watchdog_state;

void mrn_watchdog_default(mrn_watchdog *w);
/* at the start of a run: take E_k + E_el, keep the peaks */
void mrn_watchdog_start(mrn_watchdog_state *s, const struct mrn_sim *sim);
/* after a step: 0, or MRN_ERR_STATE with a diagnosis when a bound is passed.
 * Checks when `every` steps have passed since the last check, or `force`. */
int mrn_watchdog_check(mrn_watchdog_state *s, const struct mrn_sim *sim, int force);

#endif
