/* moraine: the passes over the particles of the explicit step.
 *
 * Several stages of the step run in one pass over the particles, chunk by
 * chunk while a chunk is in the cache: the velocity gradient of a chunk goes
 * straight to the material update (no particle stores it), its stresses
 * straight to the internal force, its new positions straight to the
 * end-of-step check. The step names the stages each pass chains
 * (mrn_particle_stages), so its source reads in the order of the physics.
 * The transfers work on `tr`, the step's transfer context
 * (mrn_sim_transfer). */
#ifndef MRN_SOLVER_UPDATE_H
#define MRN_SOLVER_UPDATE_H

#include "solver/simulation.h"
#include "transfer/kernels.h"

/* L from the nodal velocity gvel, then F, volume, stress and energies over
 * dt (USF, MUSL, USAVG's halves). 0, or an error naming
 * the first particle whose F would invert (the others are updated). */
int mrn_update_from_grid(mrn_sim *sim, mrn_transfer *tr, const double *gvel, double dt);

/* the same from given gradients L, 9 per particle (the contact step's) */
int mrn_update_from_gradients(mrn_sim *sim, const double *L, double dt);

/* mrn_update_from_grid, then the internal force of the updated stresses
 * scattered to the grid (P2G with force only), the particles unmoved since
 * the last P2G (USF, USAVG's first half). For plain B-splines both happen
 * in one pass (mrn_update_force in transfer/kernels.h). Errors as
 * mrn_update_from_grid. */
int mrn_update_then_force(mrn_sim *sim, mrn_transfer *tr, const double *gvel, double dt);

/* G2P over dt_move (positions and velocities, mrn_g2p_then) with L from
 * the updated grid velocity, and the material update over dt_stress (USL);
 * then each chunk goes to `after` when it is not NULL
 * (*after_bad: what it rejected first, or -1). Errors as
 * mrn_update_from_grid. */
int mrn_update_with_g2p(mrn_sim *sim, mrn_transfer *tr, double dt_move, double dt_stress, const mrn_particle_pass *after,
                        long *after_bad);

/* The stages a pass over the particles chains, in the order they run on each
 * chunk of particles. */
enum {
  MRN_STAGE_MOVE = 1u << 0,     /* G2P: velocities, affine matrices, positions (000, Eqs. 31-41) */
  MRN_STAGE_GRADIENT = 1u << 1, /* velocity gradient L from a nodal velocity (000, Eqs. 44-45) */
  MRN_STAGE_MATERIAL = 1u << 2, /* F, volume, stress and energies from L (material/advance.h) */
  MRN_STAGE_FORCE = 1u << 3,    /* internal force of the updated stress to the grid (002, Fig. 1 step 3) */
  MRN_STAGE_END = 1u << 4       /* the end-of-step wrap, clamp and state check */
};

typedef struct mrn_particle_stages {
  unsigned stages;              /* MRN_STAGE_* bits */
  const double *gvel;           /* GRADIENT: the nodal velocity (after MOVE: grid.vel_new, V~) */
  double move_dt;               /* MOVE: over this step */
  double material_dt;           /* MATERIAL: over this step */
  double *dx;                   /* MOVE: NULL to move the particles, else their increments go here */
  const mrn_particle_pass *end; /* END: the check, run on each chunk (NULL: none in this pass) */
  long end_bad;                 /* END, out: the lowest particle `end` rejected, or -1 */
} mrn_particle_stages;

/* Runs one pass of the chained stages. The chains a pass can make:
 * GRADIENT -> MATERIAL [-> FORCE] (particles unmoved since the last P2G),
 * MOVE [-> END], MOVE -> GRADIENT -> MATERIAL [-> END]. 0, or an error as
 * mrn_update_from_grid (or for a chain no pass makes). */
int mrn_particle_stages_run(mrn_sim *sim, mrn_transfer *tr, mrn_particle_stages *s);

#endif
