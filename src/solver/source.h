/* moraine: inflow sources — material entering the grid through a face.
 *
 * A source is an axis-aligned inlet box with one of its faces the inflow
 * plane. Behind the plane lies a virtual reservoir of material on the
 * regular seeding lattice (per_axis points per cell along each axis, at the
 * centres of the sub-cells, as add_particles{placement = "regular"}) that
 * moves into the box with the inflow velocity v(t), normal to the plane.
 * The source keeps how far that material has advanced, the progress
 * s = integral of v dt, and makes a lattice layer real when its centre
 * crosses the plane: layer k (k = 0, 1, ...), which stands for the slab
 * [(k) Delta, (k + 1) Delta] behind the plane, enters when s >= (k + 1/2)
 * Delta, at s - (k + 1/2) Delta in front of the plane. The mass brought in
 * up to s is then rho A s within half a layer, whatever the steps.
 *
 * The grid nodes of the box, and those up to two cells upstream of the plane
 * (ghost nodes included), are held at v(t) every step, like a velocity
 * constraint: the material in the inlet moves with the lattice, so a layer
 * never lands on the one before it. The work those nodes do on the material,
 * sum m (v - V~) . v, is booked as the inlet's work.
 *
 * A source's progress and what it brought in are its state, kept by a
 * checkpoint under its name; the geometry and the velocity come from the
 * caller again when a checkpoint is continued (mrn_sim_add_source finds the
 * state a loaded simulation kept under the same name). */
#ifndef MRN_SOLVER_SOURCE_H
#define MRN_SOLVER_SOURCE_H

#include <stddef.h>

#include "grid/constraint.h"

struct mrn_sim;

#define MRN_SOURCE_NAME 32
#define MRN_MAX_SOURCES 16

/* the velocity of the inflow at time t (m/s, 3 components): 0, or an error
 * code with the message set */
typedef int (*mrn_source_velocity_fn)(void *ctx, const struct mrn_sim *sim, double t, double v[3]);

/* what a checkpoint keeps of a source */
typedef struct mrn_source_state {
  char name[MRN_SOURCE_NAME];
  double progress; /* s, how far the inflowing material has advanced through the plane (m) */
  long layers;     /* lattice layers made real */
  long particles;  /* particles made */
  double mass;     /* their mass (kg; kg/m in 2D) */
  double energy;   /* their E_k + E_g + E_el when made (J; J/m in 2D) */
  double work;     /* the inlet nodes' work on the material (J; J/m in 2D) */
} mrn_source_state;

typedef struct mrn_source_config {
  const char *name;    /* copied; NULL: "source" */
  double lo[3], hi[3]; /* the inlet box (z ignored in 2D) */
  int axis, side;      /* the inflow plane: the box's face along `axis`, its lower (0) or upper (1) side */
  int material;        /* index from mrn_sim_add_material */
  int per_axis;        /* lattice points per cell along each axis */
  double velocity[3];  /* the inflow velocity when fn is NULL */
  mrn_source_velocity_fn fn;
  void *ctx;
  void (*release)(void *ctx); /* called on ctx when the source goes */
  double stress[6];           /* the new particles' stress (Pa) */
} mrn_source_config;

typedef struct mrn_source {
  mrn_source_config cfg;
  char name[MRN_SOURCE_NAME];
  mrn_source_state st;
  double *points; /* the lattice points on the plane, 3 values each */
  size_t npoints;
  double spacing; /* Delta = cell / per_axis */
  double volume;  /* of one particle: Delta^dim */
  double area;    /* of the inflow: npoints Delta^(dim - 1) (m^2; m in 2D) */
  double v[3];    /* the inflow velocity of the current step */
  double work_step; /* the inlet's work in the current step, on this process's rows, until booked */
  mrn_constraint inlet;
} mrn_source;

/* Add a source; its index, or -1 with the message set (a box outside the
 * grid, one that overlaps another source's, no lattice point on the plane, a
 * constant velocity that is zero, points out of the box or is not normal to
 * the plane). A loaded simulation's state of the same name is taken up. */
int mrn_sim_add_source(struct mrn_sim *sim, const mrn_source_config *cfg);
void mrn_sim_free_sources(struct mrn_sim *sim);

/* The step's part (solver/step.c): the velocity of each source for a step
 * of dt from sim->time (at its middle); the inlet nodes held at it, with
 * `share` of the hold's work booked (1 in V~; in the step's first V the
 * part of V that reaches the particles' momentum; 0 for a hold already
 * booked); the layers that crossed the plane made real once the step has
 * ended. 0 or an error code with the message set. */
int mrn_sources_begin_step(struct mrn_sim *sim, double dt);
void mrn_sources_apply(struct mrn_sim *sim, double *vel, double dt, double share);
int mrn_sources_emit(struct mrn_sim *sim, double dt);

/* The sources of `from` (a deck's simulation) move to `to` (the one loaded
 * from its checkpoint), each taking up the state `to` kept under its name. */
void mrn_sim_move_sources(struct mrn_sim *to, struct mrn_sim *from);

/* The state saved under each source's name, for a simulation loaded from
 * a checkpoint until its sources are added again; 0 or MRN_ERR (memory). */
int mrn_sim_keep_source_states(struct mrn_sim *sim, const mrn_source_state *states, int count);

#endif
