/* moraine: the material-point update of the explicit step — velocity
 * gradient, kinematics and constitutive update in one pass over the
 * particles (the gradient of a chunk of particles goes straight to the
 * material update; no particle stores it). The transfers work on `tr`, the
 * step's transfer context (mrn_sim_transfer). */
#ifndef MRN_SOLVER_UPDATE_H
#define MRN_SOLVER_UPDATE_H

#include "solver/simulation.h"
#include "transfer/kernels.h"

/* L from the nodal velocity gvel, then F, volume, stress and energies over
 * dt (USF, MUSL, both halves of USAVG's first part). 0, or an error naming
 * the first particle whose F would invert (the others are updated). */
int mrn_update_from_grid(mrn_sim *sim, mrn_transfer *tr, const double *gvel, double dt);

/* mrn_update_from_grid, then the internal force of the updated stresses
 * scattered to the grid (P2G with force only), the particles unmoved since
 * the last P2G (USF, USAVG's first half). For plain B-splines both happen
 * in one pass (mrn_update_force in transfer/kernels.h). Errors as
 * mrn_update_from_grid. */
int mrn_update_then_force(mrn_sim *sim, mrn_transfer *tr, const double *gvel, double dt);

/* G2P over dt_move (positions and velocities, mrn_g2p_then) with L from
 * the updated grid velocity, and the material update over dt_stress (USL,
 * USAVG's second half); then each chunk goes to `after` when it is not NULL
 * (*after_bad: what it rejected first, or -1). Errors as
 * mrn_update_from_grid. */
int mrn_update_with_g2p(mrn_sim *sim, mrn_transfer *tr, double dt_move, double dt_stress, const mrn_particle_pass *after,
                        long *after_bad);

#endif
