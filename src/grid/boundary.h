/* moraine: boundary conditions on the six (2D: four) faces of the grid.
 *
 * A face condition acts on every node on the face and on the ghost nodes
 * beyond it. Kinds:
 *   free      nothing imposed
 *   fixed     no-slip: every velocity component is zero
 *   slip      the normal component is zero, tangential motion is free
 *   friction  a unilateral contact with Coulomb friction: the normal velocity
 *             is removed while the material moves into the face, and
 *             friction with coefficient mu bounds the tangential impulse by
 *             mu times the normal one (never reversing the tangential
 *             motion); material moving away is left free. The face node and
 *             the ghost nodes beyond it form one contact, whose state is kept
 *             from step to step (grid.contact). The frictional work
 *             (000, Eq. 66) is accumulated.
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
  int gap_check;      /* MRN_BC_FRICTION: release a column where the material over it stands clear */
  double velocity[3]; /* prescribed velocity for MRN_BC_VELOCITY (m/s) */
} mrn_face_bc;

struct mrn_walls;

typedef struct mrn_boundary {
  mrn_face_bc face[MRN_FACE_COUNT];
  /* rigid walls of any shape (grid/wall.h), applied after the faces; NULL:
   * none. Owned by the simulation. */
  struct mrn_walls *walls;
  /* the part of the holds in V that reaches the particles (mrn_hold_share
   * of the scheme, solver/step.c, set by the simulation each step): that
   * part of the normal momentum the holds remove counts in the friction
   * bound of V~ (mrn_contact_bound) */
  double hold_share;
  /* the weight with which the holds on a field other than the grid's V
   * reach the particles (XPIC's smoothed passes, set by the solver around
   * each): booked with the holds of V, and counted with them in the
   * friction bound; 0: neither */
  double pass_weight;
} mrn_boundary;

/* A contact between the material and a rigid obstacle (a friction face or a
 * wall) at one point of it: `count` nodes that stand for that point and share
 * one contact, nodes[0 .. count-1], or first, first + step, ... when nodes is
 * NULL. */
typedef struct mrn_contact_column {
  size_t first;
  long step;
  int count;
  const size_t *nodes;
  int axis;    /* the normal's axis when it is one (a face), else -1 */
  int shared;  /* 1: the nodes may lie on several processes (a wall's column, solver/dist.h): the sums of
                * mrn_contact_push and _slide_sums take this process's rows (mrn_grid_owns) only */
  double n[3]; /* unit normal pointing into the obstacle */
  double w[3]; /* the obstacle's velocity there (m/s) */
} mrn_contact_column;

/* The unilateral Coulomb contact of one column on `vel` (see boundary.c):
 * held (normal velocity relative to the obstacle removed) only when
 * `touching` and moving into the obstacle, or, without friction, when in
 * contact at the end of the last step (bit `bit` of *state, which the call
 * with friction updates). With friction, the tangential impulse is bounded by
 * mu times the normal one of the step (mrn_contact_bound), with `held` (may
 * be NULL): the column's memory of the step's holds, to which a call
 * without friction adds its hold times `weight` and which the call with
 * friction reads. The impulse on the material is added to J (may be NULL);
 * returns the frictional work sum m dV . (V - w), <= 0 (both of the nodes
 * on this process's rows, mrn_grid_owns). */
double mrn_contact_apply(const mrn_contact_column *c, mrn_grid *g, double mass_floor, double *vel, double mu,
                         int with_friction, int touching, unsigned char *state, unsigned char bit, double J[3],
                         double *held, double weight, double hold_share);

/* The steps of mrn_contact_apply, for a caller that sums a shared column's
 * N and M, P over the processes between them (grid/wall.c): N, the normal
 * momentum into the obstacle (push); whether the column is held (held:
 * with friction it sets or clears `bit` of *state); the normal velocity
 * removed (hold); M and P, the column's mass and momentum relative to the
 * obstacle (slide_sums); friction from the summed N, M, P (slide: returns
 * its work). The impulse added to J and the work are those of the nodes
 * on this process's rows (mrn_grid_owns): summed over the processes, each
 * node counts once. */
double mrn_contact_push(const mrn_contact_column *c, const mrn_grid *g, double mass_floor, const double *vel);
int mrn_contact_held(double N, int with_friction, int touching, unsigned char *state, unsigned char bit);
/* the normal impulse bounding friction: N of V~ plus hold_share times the
 * normal momentum `held` that the step's holds removed, at least 0 */
double mrn_contact_bound(double N, double held, double hold_share);
void mrn_contact_hold(const mrn_contact_column *c, const mrn_grid *g, double mass_floor, double *vel, double J[3]);
void mrn_contact_slide_sums(const mrn_contact_column *c, const mrn_grid *g, double mass_floor, const double *vel,
                            double MP[4]);
double mrn_contact_slide(const mrn_contact_column *c, const mrn_grid *g, double mass_floor, double *vel, double mu,
                         double N, const double MP[4], double J[3]);

/* 1 when a particle at surface coordinate x, of half side r, lies over the
 * patch of a face or wall centred at c (one cell wide): a column is touched
 * only by the material over it (see "Rolling" in doc/numerics.md) */
int mrn_contact_over_patch(double x, double c, double r, double cell);

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

/* Impose the conditions on `vel` (3n). When `with_friction` is set (the
 * updated velocity V~ of a step), friction faces apply Coulomb friction,
 * decide their contacts and keep them in g->contact, and the frictional work
 * (J, or J/m in 2D, negative while dissipating) is returned; otherwise (the
 * velocity V of P2G, or XPIC's smoothed fields) they hold the columns moving
 * into the face or in contact at the end of the last step, without friction.
 * Friction faces take the nodes above `mass_floor` (the simulation's; lighter
 * nodes are empty). `dt` only enters the work through F * V * dt = m dV . V.
 * The walls of bc->walls follow the faces (grid/wall.h, mrn_walls_apply). */
double mrn_boundary_apply(const mrn_boundary *bc, mrn_grid *g, double mass_floor, double *vel, int with_friction);
/* Given the outcome so far, combines `narrays` arrays of one byte per node
 * (g->n each, one after another at `marks`) with those of the other
 * processes that hold particles near the same nodes, and returns the
 * outcome every process agreed (solver/dist.h, mrn_dist_or_marks) */
typedef int (*mrn_marks_share)(void *ctx, unsigned char *marks, int narrays, int rc);

/* Mark in g->touch the face nodes of friction faces where the material
 * touches the face: for each particle (positions x, initial volumes vol0, 3
 * and 1 values per particle) whose initial half side reaches a friction
 * face, the face nodes within `reach` cells of it along the face (the reach
 * of its shape functions, where its momentum lands) whose cell-sized patch
 * of the face its extent covers (mrn_contact_over_patch). A column not
 * in contact is touched only by material on the face; one in contact stays
 * touched while material is within a slack of it (see boundary.c). With
 * gap_check, a column whose patch material above the face lies over, and
 * none on the face, is released; those marks are first combined by `share`
 * (NULL on one process) with the other processes' (ctx is passed to it).
 * 0 or an error code (out of memory, or another process's error). */
int mrn_boundary_touch(const mrn_boundary *bc, mrn_grid *g, double reach, const double *x, const double *vol0, size_t n,
                       mrn_marks_share share, void *ctx);

#endif
