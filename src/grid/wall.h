/* moraine: rigid walls of any shape on the grid.
 *
 * A wall is a rigid obstacle given by its signed distance: negative inside
 * the wall, positive in the material's space, with the outward normal its
 * gradient. Shapes (mrn_wall_shape; a new shape is one case in
 * wall_distance_body, wall.c):
 *   plane     the half-space behind a plane at any angle (2D and 3D)
 *   box       an axis-aligned box (in the wall's reference placement)
 *   cylinder  a disk (2D) or an infinite cylinder along `axis` (3D)
 *   polygon   a closed polygon (2D), vertices in either orientation
 *   mesh      a closed triangle mesh (3D, grid/trimesh.h), e.g. from an STL file
 * With `inside` set the material is inside the shape and the wall outside
 * it (a drum, a container). Kinds:
 *   slip      a unilateral contact without friction
 *   friction  a unilateral contact with Coulomb friction, coefficient mu
 *   fixed     the material it touches moves with the wall (no-slip, bilateral)
 * A wall moves rigidly with a prescribed velocity and angular velocity about
 * its reference point (both set between steps, e.g. from a function of
 * time). Each step the nodes the material touches inside the wall (signed
 * distance <= 0, within the reach of a particle that touches the wall) get
 * the contact of grid/boundary.h (mrn_contact_apply) with the wall's normal
 * and velocity there; the wall keeps the reaction (force and moment about its
 * reference point) and the work it does. doc/numerics.md, "Rigid walls". */
#ifndef MRN_GRID_WALL_H
#define MRN_GRID_WALL_H

#include <stddef.h>

#include "core/comm.h"
#include "grid/grid.h"

typedef enum { MRN_WALL_PLANE = 0, MRN_WALL_BOX, MRN_WALL_CYLINDER, MRN_WALL_POLYGON, MRN_WALL_MESH, MRN_WALL_SHAPE_COUNT } mrn_wall_shape;
typedef enum { MRN_WALL_SLIP = 0, MRN_WALL_FRICTION, MRN_WALL_FIXED, MRN_WALL_KIND_COUNT } mrn_wall_kind;

/* NULL-terminated names, in enum order */
const char *const *mrn_wall_shape_names(void);
const char *const *mrn_wall_kind_names(void);

#define MRN_WALL_NAME_MAX 64
#define MRN_WALL_MAX_VERTICES 1024
#define MRN_WALL_MAX_TRIANGLES 4000000

/* what a wall is made of: shape and placement at creation (the reference
 * placement), kind, and its motion */
typedef struct mrn_wall_spec {
  char name[MRN_WALL_NAME_MAX];
  mrn_wall_shape shape;
  int inside;       /* 1: the material is inside the shape */
  double point[3];  /* plane: a point of it; box: its centre; cylinder: a point of its axis;
                     * mesh: the origin of its facets' surface coordinates */
  double normal[3]; /* plane: the normal out of the wall (any length > 0); cylinder (3D): the axis */
  double half[3];   /* box: half its sides */
  double radius;    /* cylinder */
  double *vertex;   /* polygon: nvertex (x, y) pairs; copied */
  int nvertex;
  double *triangle;   /* mesh: ntriangle triangles, 9 numbers each (corners a, b, c); copied */
  int ntriangle;
  const char *source; /* mesh: where the triangles came from, for messages; not kept */
  mrn_wall_kind kind;
  double mu;          /* friction */
  int gap_check;      /* release a column where the material over it stands clear (doc/numerics.md, "Rolling") */
  double velocity[3]; /* m/s */
  double omega[3];    /* rad/s, about `center` (2D: only z) */
  double center[3];   /* the reference point: rotation, moment */
  /* a rigid body (doc/numerics.md, "Rigid bodies"): the wall moves under
   * gravity, the material's reaction and an external load instead of as set;
   * velocity and omega are its initial ones, and mrn_walls_add makes its
   * centre of mass its `center` */
  int body;
  double density;                 /* kg/m^3, or 0 when the mass is given */
  double mass;                    /* kg (kg/m in 2D), or 0 when the density is given */
  unsigned fix;                   /* bit k: degree of freedom k (mrn_body_dof_names) keeps its velocity */
  double load[3], load_moment[3]; /* external force (N) and moment about the centre of mass (N m) */
} mrn_wall_spec;

/* A motion given as a function of time: fills the velocity and angular
 * velocity at time t; 0 or an error code (message set) */
typedef int (*mrn_wall_motion_fn)(void *ctx, double t, double velocity[3], double omega[3]);

typedef struct mrn_wall {
  mrn_wall_spec spec; /* as made: placement, kind, mu, motion as set last */
  struct mrn_trimesh *mesh; /* mesh: its triangles, searchable */
  double ref[3];      /* where the reference point is now */
  double rot[9];      /* rotation from the reference placement, row-major */
  double period;      /* the length of a closed surface coordinate u (cylinder, polygon), else 0 */
  /* the last step: impulse on the material and its moment about ref (in
   * V~), and the reaction on the wall, -impulse / dt (N, N m; per metre in 2D) */
  double impulse[3], angular[3];
  /* the same of the holds in V, before the forces (the first V of the step
   * only): they reach the particles' momentum under PIC-like updates */
  double hold_impulse[3], hold_angular[3], hold_work;
  int v_done; /* V~ reached: later holds (a re-map) are not the step's */
  double force[3], moment[3];
  double total_impulse[3]; /* accumulated impulse of the material on the wall (N s) */
  double work_friction; /* accumulated frictional work, <= 0 (J) */
  double work;          /* accumulated work the wall did on the material (J) */
  /* a body's mass (kg; kg/m in 2D) and inertia about its centre of mass
   * in the reference placement (kg m^2, row-major; 2D: only [8], about z),
   * and the accumulated work of gravity, its load and its fixings (J) */
  double mass, inertia[9];
  double body_work;
  double spin[3]; /* within the step's end: the angular momentum the body turns to */
  double step_work;     /* that of the current step */
  double step_friction; /* the frictional work of the current step */
  long contacts;        /* nodes held with friction in the last step */
  /* the motion as a function of time (NULL: spec.velocity and spec.omega
   * as set), asked at the middle of each step; release(ctx) on free */
  mrn_wall_motion_fn motion;
  void *motion_ctx;
  void (*motion_release)(void *ctx);
  /* per node of the grid: bit 0 touched this step, bit 1 in contact at the
   * end of the last step, bit 2 found outside the wall this step, bits 3
   * and 4 MRN_WALL_OVER and MRN_WALL_CLEAR (only bit 1 outlives the step) */
  unsigned char *state;
  /* the nodes found outside this step (their bit 2 is cleared next step) */
  size_t *outside;
  size_t nout, capout;
  /* the nodes touched this step, with the wall's normal (out of the wall),
   * velocity and the surface patch of the nearest point there */
  size_t *node;
  double *n, *w;
  long long *key;
  size_t count, cap;
  /* those nodes in columns, one per surface patch: column c holds
   * col_node[col_start[c] .. col_start[c + 1] - 1], its normal into the wall
   * col_n and the wall's velocity col_w (3 each), its contact bit col_state
   * (MRN_WALL_CONTACT) and its first node col_first, where its impulse acts.
   * In a distributed run the columns are those of every process, in the
   * order of their patches; a process holds the nodes of some (solver/dist.h) */
  size_t *col_node, *col_start, *col_first;
  double *col_n, *col_w;
  unsigned char *col_state;
  size_t ncol, col_cap;
  double *sums; /* per column, the sums a step exchanges (ncol x 7) */

} mrn_wall;

/* How the walls reach over the processes of a distributed run, which all
 * hold the whole grid but only their slab's particles (solver/dist.h): a
 * wall's columns may have nodes on several processes, so the touched nodes
 * of the bands are shared with the neighbours, the columns are those of
 * every process, and their sums (N, M, P of grid/boundary.h, the normal and
 * velocity, the reaction) are summed over the processes, each node counted
 * by the process that owns its row. NULL in mrn_walls on one process. */
typedef struct mrn_walls_share {
  void *ctx;
  /* the outcome rc of this process, agreed by every process (solver/dist.h) */
  int (*agree)(void *ctx, int rc);
  /* v[0 .. n) combined over the processes */
  void (*reduce)(void *ctx, double *v, size_t n, mrn_comm_op op);
  /* the `mask` bits of the node bytes `bits` OR-ed with the neighbours' on
   * the bands; fresh(arg, node) for each node that gains one; 0 or an error */
  int (*band_or)(void *ctx, unsigned char *bits, unsigned char mask, int (*fresh)(void *arg, size_t node), void *arg);
  /* the sorted union over the processes of n sorted keys (3 each): a malloc'ed
   * array of *total keys, or NULL (message set) */
  long long *(*union_keys)(void *ctx, const long long *keys, size_t n, size_t *total);
} mrn_walls_share;

typedef struct mrn_walls {
  mrn_wall *wall;
  int count;
  int dim;
  double cundall;      /* D of Cundall's damping, for the bodies (set by the solver) */
  double damping_work; /* the work of that damping on the bodies in the last step */
  const mrn_walls_share *share; /* a distributed run's, or NULL */
} mrn_walls;

#define MRN_WALL_TOUCH 1u
#define MRN_WALL_CONTACT 2u
#define MRN_WALL_OUTSIDE 4u
/* in the touch of a step: material on the wall lies over the node's patch
 * (OVER), material above the wall does (CLEAR) */
#define MRN_WALL_OVER 8u
#define MRN_WALL_CLEAR 16u

/* Check a spec against the grid (shape, normal, radius, vertices, mu, a wall
 * that reaches the grid) and append the wall; *ws is created on first use.
 * Returns 0 or an error (message names the key at fault). */
int mrn_walls_add(mrn_walls **ws, const mrn_grid *g, const mrn_wall_spec *spec);
void mrn_walls_free(mrn_walls *ws);
/* the wall of that name, or NULL */
mrn_wall *mrn_walls_find(mrn_walls *ws, const char *name);

/* The signed distance of x from the wall's surface in its current placement
 * (positive outside the wall) and the outward unit normal there */
double mrn_wall_distance(const mrn_wall *w, int dim, const double x[3], double n[3]);
/* the wall's velocity at x */
void mrn_wall_velocity_at(const mrn_wall *w, int dim, const double x[3], double v[3]);

/* Forget the wall's contacts and take those of the nodes contact[0 .. n)
 * (a distributed run's re-cut: every process's); 0 or an error */
int mrn_wall_reset_contacts(mrn_wall *w, const size_t *contact, size_t n);

/* A wall as a checkpoint left it: its placement, accumulators and the
 * nodes in contact at the end of the last step (which also stand for the
 * nodes it touched then, so the next step forgets the same contacts) */
int mrn_wall_restore(mrn_wall *w, const size_t *contact, size_t n);

/* The degrees of freedom of a body, bit k of spec.fix: x y z rx ry rz
 * (NULL-terminated); a 2D body has x, y and rz */
const char *const *mrn_body_dof_names(void);
/* A body's mass and inertia from its shape and density (or mass), its
 * centre of mass made its reference point; 0 or an error naming the key */
int mrn_body_setup(mrn_wall *w, int dim);
/* a body's inertia in its current placement, R I R^T (kg m^2, row-major) */
void mrn_body_inertia(const mrn_wall *w, double I[9]);
/* a body's kinetic energy (J; J/m in 2D) */
double mrn_body_kinetic(const mrn_wall *w, int dim);
/* End of a step of dt for a body whose reaction is set: its velocity and
 * angular velocity from the reaction, gravity, its load and Cundall's
 * damping D of its net force (Newton-Euler, semi-implicit Euler: the wall
 * then moves with the new ones). Returns the damping's work. */
double mrn_body_advance(mrn_wall *w, int dim, double dt, const double gravity[3], double D);
/* after the body has turned: its angular velocity from its angular
 * momentum in the new placement (3D; nothing to do in 2D) */
void mrn_body_respin(mrn_wall *w, int dim);
/* 1 when a wall is a rigid body; 1 when a body's contact touches the node
 * this step (its velocity is the body's: no Cundall damping there) */
int mrn_walls_have_bodies(const mrn_walls *ws);
int mrn_walls_body_holds(const mrn_walls *ws, size_t node);
/* the bodies' kinetic energy and the work done on them, summed */
void mrn_walls_body_energy(const mrn_walls *ws, double *kinetic, double *work);

/* Start of a step at t_mid, its middle: the walls' motions for the step,
 * the nodes each wall's material touches (positions x, initial volumes vol0
 * of n particles, `reach` cells the shape functions reach), and the step's
 * reaction cleared. 0 or an error (a motion function's). */
int mrn_walls_touch(mrn_walls *ws, const mrn_grid *g, double t_mid, double reach, const double *x, const double *vol0,
                    size_t n);
/* Impose the walls on vel, as mrn_boundary_apply (which calls it), with its
 * hold_share and pass_weight (grid/boundary.h); returns the frictional work
 * (with_friction only) */
double mrn_walls_apply(mrn_walls *ws, mrn_grid *g, double mass_floor, double *vel, int with_friction,
                       double hold_share, double pass_weight);
/* End of a step of dt: the reactions (summed over the processes of a
 * distributed run), the bodies' velocities under gravity, and the walls
 * moved on. `hold_share` is the part of the holds in V that reaches the
 * particles' momentum (1 for PIC-like velocity updates and XPIC, 0 for FLIP,
 * 1 - X for blends). *work: the work the walls of prescribed motion did on
 * the material in the step (a body's is inside the system). 0 or an error. */
int mrn_walls_step_end(mrn_walls *ws, double dt, double hold_share, const double gravity[3], double *work);

#endif
