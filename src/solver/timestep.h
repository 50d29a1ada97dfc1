/* moraine: time-step policies, asked for a new dt before every step.
 *   fixed     dt = value
 *   a_tau     dt = a_tau * l_cell * min over materials sqrt(rho / E) (000, Eq. 29)
 *   cfl       dt = C min(h / max_p (c_p + |v_p|), h^2 / nu_max) (002, Eqs. 34-37),
 *             c_p the P-wave speed of the particle's material, nu = mu / rho for
 *             materials with a viscosity; with CPDI and CPDI2 each particle's
 *             c_p + |v_p| is multiplied by max(1, h g_p / sqrt(dim)), g_p its
 *             largest |grad S_ip| (transfer/cpdi.h)
 *   grid_cfl  dt = C h min_A sqrt(m_A / (V_A M_A)), nodal averages of mass,
 *             volume and P-wave modulus (001, Eqs. 58-61)
 *   callback  dt = a user function of the simulation (a Lua function in decks)
 * Every policy is clamped to [min, max] when those are set (> 0); a policy
 * that asks for a step below `min` stops the run with an error. */
#ifndef MRN_SOLVER_TIMESTEP_H
#define MRN_SOLVER_TIMESTEP_H

struct mrn_sim;

typedef enum { MRN_DT_FIXED = 0, MRN_DT_A_TAU, MRN_DT_CFL, MRN_DT_GRID_CFL, MRN_DT_CALLBACK } mrn_dt_kind;

/* returns 0 and sets *dt, or an error code (message set) */
typedef int (*mrn_dt_callback)(void *ctx, struct mrn_sim *sim, double *dt);

typedef struct mrn_dt_policy {
  mrn_dt_kind kind;
  double value;   /* dt for fixed, a_tau for a_tau, the Courant number C for the CFL policies */
  double min, max; /* 0 = no bound */
  mrn_dt_callback callback;
  void *ctx;
  void (*release)(void *ctx);
} mrn_dt_policy;

void mrn_dt_policy_fixed(mrn_dt_policy *p, double dt);
void mrn_dt_policy_a_tau(mrn_dt_policy *p, double a_tau);
void mrn_dt_policy_cfl(mrn_dt_policy *p, mrn_dt_kind kind, double courant);
/* the particle (002) and grid-averaged (001) critical steps, without the
 * Courant number; HUGE_VAL when nothing limits the step */
double mrn_dt_particle_critical(const struct mrn_sim *sim);
double mrn_dt_grid_critical(struct mrn_sim *sim);
/* the particle critical step, and the particle with the largest |v| (its
 * index, -1 when there is none) and that speed (m/s) */
double mrn_dt_particle_critical_at(const struct mrn_sim *sim, long *fastest_particle, double *top_speed);
void mrn_dt_policy_release(mrn_dt_policy *p);
const char *mrn_dt_kind_name(mrn_dt_kind k);

/* evaluate the policy for the current state; 0 or error */
int mrn_dt_compute(struct mrn_sim *sim, double *dt);

#endif
