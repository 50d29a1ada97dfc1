/* moraine: boundary conditions on the six (2D: four) faces of the grid.
 *
 * A face condition acts on every node on the face and on the ghost nodes
 * beyond it. Kinds:
 *   free      nothing imposed
 *   fixed     no-slip: every velocity component is zero
 *   slip      the normal component is zero, tangential motion is free
 *   friction  the normal component is zero; while the material presses on the
 *             face, Coulomb friction with coefficient mu reduces the
 *             tangential speed by mu times the removed normal speed (never
 *             reversing it). The frictional work (000, Eq. 66) is accumulated.
 *   velocity  every velocity component is prescribed (a moving plate)
 *   periodic  the face is glued to the opposite one (both faces of the axis
 *             must be periodic): kernels wrap around and particles leaving
 *             through one face re-enter through the other
 */
#ifndef MRN_GRID_BOUNDARY_H
#define MRN_GRID_BOUNDARY_H

#include "grid/grid.h"

typedef enum {
  MRN_BC_FREE = 0,
  MRN_BC_FIXED,
  MRN_BC_SLIP,
  MRN_BC_FRICTION,
  MRN_BC_VELOCITY,
  MRN_BC_PERIODIC,
  MRN_BC_KIND_COUNT
} mrn_bc_kind;

enum { MRN_FACE_XMIN = 0, MRN_FACE_XMAX, MRN_FACE_YMIN, MRN_FACE_YMAX, MRN_FACE_ZMIN, MRN_FACE_ZMAX, MRN_FACE_COUNT };

typedef struct mrn_face_bc {
  mrn_bc_kind kind;
  double mu;          /* friction coefficient for MRN_BC_FRICTION */
  double velocity[3]; /* prescribed velocity for MRN_BC_VELOCITY (m/s) */
} mrn_face_bc;

typedef struct mrn_boundary {
  mrn_face_bc face[MRN_FACE_COUNT];
} mrn_boundary;

const char *mrn_bc_kind_name(mrn_bc_kind k);
/* NULL-terminated list of kind names, in enum order */
const char *const *mrn_bc_kind_names(void);
int mrn_bc_kind_from_name(const char *name, mrn_bc_kind *out);
const char *mrn_face_name(int face);
/* 1 when both faces of the axis are periodic */
static inline int mrn_boundary_periodic(const mrn_boundary *bc, int axis) {
  return bc->face[2 * axis].kind == MRN_BC_PERIODIC && bc->face[2 * axis + 1].kind == MRN_BC_PERIODIC;
}
/* 0, or an error when a periodic face is paired with a non-periodic one */
int mrn_boundary_validate(const mrn_boundary *bc, int dim);

/* Impose the conditions on `vel` (3n). When `with_friction` is set, friction
 * faces apply Coulomb friction and the frictional work (J, or J/m in 2D,
 * negative while dissipating) is returned; otherwise they act as slip faces.
 * `dt` only enters the work through F * V * dt = m dV . V. */
double mrn_boundary_apply(const mrn_boundary *bc, const mrn_grid *g, double *vel, int with_friction);

#endif
