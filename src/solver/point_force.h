/* moraine: point forces on material points in the explicit step.
 *
 * A point force f_p (N; N/m in 2D) rides with its material point and is
 * spread to the grid with the point's own shape functions, f_ext,I =
 * lambda sum_p N_I(x_p) f_p (000, Eq. 27's external force term), where
 * lambda is the simulation's load factor (default 1): a load history
 * without reselecting the loaded points. The forces are held in the
 * particle field "point_force" (3 values per point), registered on first
 * use, so that they follow their points through sorting and deletion, are
 * written to the .vtp and kept in checkpoints.
 *
 * Their work W_ext = sum_I f_ext,I . V~_I dt (V~ after the boundary
 * conditions) is booked in sim->work_external and enters the energy balance
 * W_MPM (000, Eq. 68) beside the friction and damping work. With the usual
 * position update x += dt sum_I N_I V~_I it is exactly sum_p f_p . dx_p. */
#ifndef MRN_SOLVER_POINT_FORCE_H
#define MRN_SOLVER_POINT_FORCE_H

#include <stddef.h>

struct mrn_sim;

#define MRN_POINT_FORCE_FIELD "point_force"

/* Register the field "point_force" unless it is: a distributed run does
 * it on every process alike, whether it holds a loaded particle or not
 * (their particles' records must agree). 0, or MRN_ERR (out of memory, or
 * the field name is taken by another field; message set). */
int mrn_sim_add_point_forces(struct mrn_sim *sim);
/* Set the force on particle p (replaces its earlier one), registering the
 * field on first use. 0, or MRN_ERR as mrn_sim_add_point_forces. */
int mrn_sim_set_point_force(struct mrn_sim *sim, size_t p, const double f[3]);
/* every point force to zero */
void mrn_sim_clear_point_forces(struct mrn_sim *sim);
/* multiply every point force by factor from the next step (finite; default 1) */
void mrn_sim_set_load_factor(struct mrn_sim *sim, double factor);

/* Step internals: add lambda sum_p N_I f_p to the nodal forces (grid.force),
 * before their halo sum in a distributed run (solver/dist.h); after the
 * velocity update, the work of those forces over the step (this process's
 * points': a book summed over the processes, mrn_books). */
void mrn_point_forces_to_grid(struct mrn_sim *sim);
double mrn_point_forces_work(const struct mrn_sim *sim, double dt);

#endif
