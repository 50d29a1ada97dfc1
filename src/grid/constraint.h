/* moraine: prescribed velocities on the grid nodes inside a region.
 *
 * A rigid footing pushed into the soil, a moving plate that covers part of a
 * face: the nodes inside the region (chosen once, when the constraint is made)
 * get the prescribed components of their velocity, each time the grid
 * velocity is computed in a step, after the face conditions. The force the
 * constraint exerts on the material in the last step, sum m (v_set - v~)/dt
 * over its nodes (N, or N/m in 2D), is kept as its reaction: over the nodes
 * whose rows this process books (grid.own_lo, own_hi), every node but in a
 * distributed run. */
#ifndef MRN_GRID_CONSTRAINT_H
#define MRN_GRID_CONSTRAINT_H

#include <stddef.h>

#include "grid/grid.h"

/* Whether point x lies in the constrained region: 1 inside, 0 outside, -1 on
 * error (message set). The grid asks only this of a region (the regions
 * themselves are a particles/ notion, a layer above the grid). */
typedef int (*mrn_point_test)(void *ctx, const double x[3]);

typedef struct mrn_constraint {
  size_t *nodes;
  size_t count;
  unsigned mask;       /* bit d set: component d is prescribed */
  double velocity[3];  /* the prescribed components (m/s) */
  double reaction[3];  /* force on the material in the last step */
} mrn_constraint;

/* Fill c with the nodes of g for which inside(ctx, x) is 1 (domain nodes
 * only). Returns 0, or an error when no node is inside or the test fails. */
int mrn_constraint_init(mrn_constraint *c, const mrn_grid *g, mrn_point_test inside, void *ctx, unsigned mask,
                        const double velocity[3]);
void mrn_constraint_free(mrn_constraint *c);

/* Impose the prescribed components on vel (3 per node). With dt > 0 the
 * reaction is recomputed from the velocities before they were imposed. */
void mrn_constraint_apply(mrn_constraint *c, const mrn_grid *g, double *vel, double floor_mass, double dt);

#endif
