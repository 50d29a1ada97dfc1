/* moraine: a simulation — grid, particles, materials, numerics and clock.
 *
 * This is the engine's public face: a C program builds a simulation with
 * mrn_sim_new(), adds materials and particles, and calls mrn_sim_step() or
 * mrn_sim_run(); the Lua layer is a checked skin over the same calls. */
#ifndef MRN_SOLVER_SIMULATION_H
#define MRN_SOLVER_SIMULATION_H

#include <stddef.h>
#include <stdio.h>

#include "grid/boundary.h"
#include "grid/constraint.h"
#include "grid/grid.h"
#include "material/material.h"
#include "particles/particles.h"
#include "particles/seed.h"
#include "shape/shape.h"
#include "solver/diagnostics.h"
#include "solver/sim_scalars.h"
#include "solver/source.h"
#include "solver/timestep.h"
#include "solver/watchdog.h"
#include "transfer/context.h"
#include "transfer/scheme.h"

#define MRN_MAX_MATERIALS 64

/* What happens to a particle that leaves the grid through a free face (or
 * is carried past any face): the run stops with a diagnosis and a final
 * checkpoint (the default), or the particle is deleted and its mass and
 * energy are booked as outflow. */
typedef enum { MRN_LEAVE_STOP = 0, MRN_LEAVE_DELETE } mrn_leave_policy;
/* "stop", "delete", NULL */
const char *const *mrn_leave_policy_names(void);

/* Another time integrator for mrn_run: step() advances the simulation by one
 * step that ends at or before t_end (s; HUGE_VAL: no end), moving sim->time,
 * sim->step and sim->dt, and returns 0, MRN_STEP_NONE when what is left
 * before t_end is a round-off sliver (nothing done), or an error code with the
 * message set. mrn_sim_free calls release(ctx) so that the integrator forgets
 * the simulation. */
#define MRN_STEP_NONE (-2) /* negative: not an error code (core/error.h), not MRN_STOP (-1) */
typedef struct mrn_integrator {
  int (*step)(void *ctx, struct mrn_sim *sim, double t_end);
  void (*release)(void *ctx);
  void *ctx;
} mrn_integrator;

typedef struct mrn_sim {
  /* dimension, kernel, clock, gravity, damping, energy book, outflow: the
   * persistent scalars, declared and described in solver/sim_scalars.h */
  MRN_SIM_SCALARS(MRN_SIM_MEMBER)

  mrn_grid grid;
  mrn_particles particles;
  mrn_scheme scheme;
  mrn_boundary boundary;
  mrn_constraint *constraints; /* prescribed nodal velocities in regions */
  int nconstraints;
  mrn_dt_policy dt_policy;

  mrn_material *materials[MRN_MAX_MATERIALS];
  int nmaterials;

  /* an integrator that takes the place of the explicit step in mrn_run
   * (the implicit one attaches itself: implicit/implicit.h); step == NULL:
   * the explicit step */
  mrn_integrator integrator;

  /* inflow sources (solver/source.h), and the states a loaded checkpoint
   * kept for sources not added again yet */
  mrn_source *sources;
  int nsources;
  mrn_source_state *source_states;
  int nsource_states;

  /* the processes of a distributed run (solver/dist.h); NULL: one process,
   * or not spread yet; and when its slabs are re-cut: every
   * rebalance_every steps (0: never) when the largest particle count
   * exceeds the mean by the factor rebalance_imbalance */
  struct mrn_dist *dist;
  long rebalance_every;
  double rebalance_imbalance;

  /* the bodies and their contact pairs (solver/contact.h); NULL: one body */
  struct mrn_contact *contact;

  mrn_watchdog watchdog;        /* the bounds of the physical-sanity checks of mrn_run */
  mrn_watchdog_state watch;     /* what those checks saw */

  /* the particles binned by block for the transfers (transfer/blocks.h), and
   * the sort policy: reorder the particles by block at the first P2G of
   * every step that is a multiple of sort_every (> 0; 0: never). Off unless
   * asked for: the Lua API documents particle indices in order of creation. */
  mrn_blocks *blocks;
  long sorted_step; /* the step of the last reordering, -1 before any */

  /* scratch, sized to the particle count */
  double *scratch;
  size_t scratch_cap;
  /* CPDI, cpGIMP: the particles' domains as the step froze them (transfer/cpdi.h, cpgimp.h) */
  double *domain;
  size_t domain_cap;
  /* scheme volumetric = "fbar": the gradients and the averaging's scratch
   * (solver/update.c) */
  double *fbar;
  size_t fbar_cap;
} mrn_sim;

typedef struct mrn_sim_config {
  int dim;
  double origin[3], size[3], cell;
  mrn_shape_kind shape;
  mrn_kernel_boundary kernel_boundary;
  double gravity[3];
} mrn_sim_config;

/* NULL with a message on failure */
mrn_sim *mrn_sim_new(const mrn_sim_config *cfg);
void mrn_sim_free(mrn_sim *sim);

/* Register a material (takes a reference); returns its index or -1 (message set).
 * Registering the same material twice returns the existing index. */
int mrn_sim_add_material(mrn_sim *sim, mrn_material *m);

/* Seed particles of material `material_index` (from mrn_sim_add_material)
 * from a region; mass = density * volume. On success the new particles are
 * first .. first + count - 1; on failure none is added (message set).
 * Before it starts, a seeding whose particles would need more than
 * MRN_SEED_REPORT_BYTES is estimated (mrn_sim_seed_estimate): refused when
 * the particles, with those already there, would not fit in the machine's
 * memory, else the estimate is printed (mrn_info) and the room reserved. */
int mrn_sim_seed(mrn_sim *sim, const mrn_region *region, int material_index, int per_axis,
                 mrn_seed_placement placement, size_t *first, long *count);
#define MRN_SEED_REPORT_BYTES 1e9

/* the memory a seeding would take */
typedef struct mrn_seed_estimate {
  double count; /* particles it adds: exact, or an upper bound when not `exact` */
  int exact;
  double bytes; /* the particles' memory, those already there included */
} mrn_seed_estimate;
/* The bound is the candidate points of the region's bounding box
 * (mrn_seed_candidates); when its particles would need more than
 * MRN_SEED_REPORT_BYTES and there are at most MRN_SEED_MAX_CANDIDATES of
 * them, the region is tested at each of them, as the seeding will, for the
 * exact count (a sphere fills half its box, a slanted cylinder far less). */
int mrn_sim_seed_estimate(const mrn_sim *sim, const mrn_region *region, int per_axis, mrn_seed_placement placement,
                          mrn_seed_estimate *e);
/* bytes per particle: its arrays and what a step sets aside for it */
size_t mrn_sim_particle_bytes(const mrn_sim *sim);
/* call after particles were added or removed by other means */
void mrn_sim_particles_changed(mrn_sim *sim);

/* Prescribe velocity components (bits of mask) on the nodes inside region;
 * returns the constraint's index or -1 (message set). */
int mrn_sim_add_constraint(mrn_sim *sim, const mrn_region *region, unsigned mask, const double velocity[3]);

/* One explicit step with the dt the policy gives. 0, or an error code with a
 * message naming what went wrong (particle, position, step). */
int mrn_sim_step(mrn_sim *sim);

/* One explicit step with a given dt (the policy is not asked) */
int mrn_sim_step_dt(mrn_sim *sim, double dt);

/* The transfer context of the current step (transfer/context.h): the
 * simulation's grid, particles, scheme, kernel and blocks, with sort_now set
 * when the sort policy asks for a reordering at this step and none was done
 * yet. Hand it back to mrn_sim_transfer_end after the transfers. */
mrn_transfer mrn_sim_transfer(mrn_sim *sim);
/* notes the reordering the transfers of tr did (if any) */
void mrn_sim_transfer_end(mrn_sim *sim, const mrn_transfer *tr);
/* reorder the particles by block every `every` steps (<= 0: never) */
void mrn_sim_set_sort_every(mrn_sim *sim, long every);

/* Initialise the Taylor grad v (and APIC C, to the same value) of particles
 * given initial velocities by repeating 000 Eqs. 19-22 until grad v
 * converges (000 §3.2, last paragraph). Returns the iterations used. */
int mrn_sim_init_affine(mrn_sim *sim);

/* the kernel as the transfers use it: shape, face treatment, MLS gradient, periodic axes */
mrn_kernel_options mrn_sim_kernel_options(const mrn_sim *sim);

/* Energies, momenta and centre of mass of the current state */
void mrn_sim_diagnostics(const mrn_sim *sim, mrn_diagnostics *d);
/* The same without the angular momentum about the centroid (L_centroid
 * stays 0): one pass over the particles instead of three */
void mrn_sim_energies(const mrn_sim *sim, mrn_diagnostics *d);

/* Start the energy balance W_MPM (000, Eq. 68) from the current state;
 * mrn_run() does it before the first step of a simulation */
void mrn_sim_energy_balance_start(mrn_sim *sim);

/* Check particle state after a step: finite position, velocity and stress,
 * inside the grid. Returns 0, or an error (message set) naming the first bad
 * particle (the lowest index, for any thread count). */
int mrn_sim_check_state(const mrn_sim *sim);

/* The tests of mrn_sim_check_state for particle p (1: fine): finite values,
 * and those inside the grid. Quiet, so that a parallel pass can ask them of
 * every particle. */
static inline int mrn_sim_particle_finite(const mrn_sim *sim, size_t p) {
  const mrn_particles *ps = &sim->particles;
  const double *x = ps->x + 3 * p, *v = ps->v + 3 * p, *s = ps->stress + 6 * p;
  /* a * 0 is (+-)0 for every finite a and NaN for an infinite or NaN one, so
   * the sum below is 0 exactly when all twelve values are finite. Summed as
   * a tree: one chain of twelve dependent additions cost more than the rest
   * of the end-of-step pass. */
  const double a = (x[0] * 0.0 + x[1] * 0.0) + (x[2] * 0.0 + v[0] * 0.0);
  const double b = (v[1] * 0.0 + v[2] * 0.0) + (s[0] * 0.0 + s[1] * 0.0);
  const double c = (s[2] * 0.0 + s[3] * 0.0) + (s[4] * 0.0 + s[5] * 0.0);
  return (a + b) + c == 0.0;
}

static inline int mrn_sim_particle_ok(const mrn_sim *sim, size_t p) {
  /* the finite test first: a NaN position is reported as such */
  return mrn_sim_particle_finite(sim, p) && mrn_grid_contains(&sim->grid, sim->particles.x + 3 * p);
}

/* A particle's kinetic energy 1/2 m |v|^2 (000, Eq. 47) and gravitational
 * energy -m g . x, zero at the origin's height (000, Eq. 48): the terms the
 * diagnostics sum, and what a deleted particle carries out of the balance.
 * The kinetic energy is that of the inertial mass, mass_scaling m: the one
 * the scaled equations of motion conserve with E_g and E_el. */
static inline double mrn_sim_particle_kinetic(const mrn_sim *sim, size_t p) {
  const double *v = sim->particles.v + 3 * p;
  return 0.5 * sim->particles.mass[p] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * sim->mass_scaling;
}
static inline double mrn_sim_particle_gravity(const mrn_sim *sim, size_t p) {
  const double *x = sim->particles.x + 3 * p, *g = sim->gravity;
  return -sim->particles.mass[p] * (g[0] * x[0] + g[1] * x[1] + g[2] * x[2]);
}

/* The error of mrn_sim_check_state for a particle that failed the test */
int mrn_sim_particle_error(const mrn_sim *sim, size_t p);

/* The energy particles added to a simulation bring in, E_k + E_g + E_el,
 * booked as inflow with their mass and count (W_MPM then does not jump).
 * For particles first .. first + count - 1 (this process's, in a
 * distributed run: the books are summed over the processes). */
void mrn_sim_book_inflow(mrn_sim *sim, size_t first, size_t count);

/* smallest sqrt(rho/E) over the materials in use, for the a_tau step; with
 * mass scaling that of the inertial density, mass_scaling rho */
double mrn_sim_slowness(const mrn_sim *sim);

#endif
