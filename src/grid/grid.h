/* moraine: the Cartesian background grid.
 *
 * Nodes sit at origin + i*cell for i = 0..ncell along each axis, plus `pad`
 * ghost layers beyond every face so that wide kernels (quadratic and cubic
 * B-splines) keep the partition of unity for particles next to the boundary.
 * Face boundary conditions act on the face nodes and on the ghost nodes
 * beyond them. Nodal vectors always have 3 components (z = 0 in 2D). */
#ifndef MRN_GRID_GRID_H
#define MRN_GRID_GRID_H

#include <stddef.h>

#define MRN_GRID_PAD 2
/* the bit of grid.contact above the six face bits (grid/boundary.h) */
#define MRN_GRID_BODIES_HELD (1u << 6)

typedef struct mrn_grid {
  int dim;
  double origin[3];
  double size[3];   /* extent of the domain (ncell * cell) */
  double cell;      /* cell size h, the same along every axis */
  double inv_cell;
  int ncell[3];     /* cells per axis; 0 along unused axes */
  int pad;          /* ghost node layers beyond each face */
  int nnode[3];     /* nodes per axis including ghosts; 1 along unused axes */
  long stride[3];   /* x fastest */
  size_t n;         /* total number of nodes */

  double *mass;     /* n */
  double *mom;      /* 3n momentum from P2G */
  double *vel;      /* 3n velocity V^i (after boundary conditions) */
  double *vel_new;  /* 3n updated velocity V~^i (000, Eq. 28) */
  double *force;    /* 3n total nodal force */
  double *vel_star; /* 3n XPIC(m) smoothed velocity V* (see transfer/xpic.c) */
  double *work;     /* 3n scratch for the XPIC iterations */
  /* n: at the face node of each column of a friction face, bit 1 << face set
   * when the column ended the last step in contact (grid/boundary.c); at a
   * node two bodies share, MRN_GRID_BODIES_HELD when they approached there in
   * the last step's V~ (solver/contact.c); kept from step to step, saved in
   * checkpoints */
  unsigned char *contact;
  /* n: at the face nodes of friction faces, bit 1 << face set when the
   * material touches the face there (mrn_boundary_touch, each step) */
  unsigned char *touch;
  /* n, allocated with the first friction face (mrn_boundary_touch): at the
   * face node of each column of a friction face, the normal momentum into
   * the face that the step's holds removed (signed), each with its weight in
   * what reaches the particles, for the friction bound of V~
   * (grid/boundary.c, mrn_contact_bound); NULL without friction faces */
  double *held;

  /* the rows of nodes, along the last axis (y in 2D, z in 3D; domain
   * numbering), whose work (damping, friction) this process books: in a
   * distributed run (solver/dist.h) the nodes next to another process's
   * part of the grid are updated by both, and booked once; every row
   * otherwise */
  int own_lo, own_hi;

  /* the node spans that can be nonzero (grid/active.h): outside them every
   * array above except vel_star and work is zero */
  struct mrn_grid_active *active;
} mrn_grid;

/* size[d] is rounded to a whole number of cells (error if the rounding is off
 * by more than 1e-6 of a cell). Returns 0 or an error code with message. */
int mrn_grid_init(mrn_grid *g, int dim, const double origin[3], const double size[3], double cell);
void mrn_grid_free(mrn_grid *g);
void mrn_grid_clear(mrn_grid *g);

/* linear index of node (i, j, k), each counted from the domain's first node
 * (ghost nodes have negative indices or indices above ncell) */
static inline size_t mrn_grid_index(const mrn_grid *g, int i, int j, int k) {
  return (size_t)((i + g->pad) * g->stride[0] + (j + g->pad) * g->stride[1] +
                  (g->dim == 3 ? (k + g->pad) * g->stride[2] : 0));
}

/* 1 when this process books the work done at node idx (see own_lo) */
static inline int mrn_grid_owns(const mrn_grid *g, long idx) {
  const long s = idx / g->stride[g->dim - 1] - g->pad;
  return s >= g->own_lo && s < g->own_hi;
}

/* node coordinates of a linear index */
void mrn_grid_node_position(const mrn_grid *g, size_t idx, double x[3]);
/* integer node indices (domain numbering) of a linear index */
void mrn_grid_node_ijk(const mrn_grid *g, size_t idx, int ijk[3]);
/* the index box [lo, hi] (domain numbering, ghost nodes included; zero
 * extent along unused axes) of the nodes strictly within `reach` cells of x
 * along every axis: those a kernel of that reach around x touches */
void mrn_grid_reach_box(const mrn_grid *g, const double *x, double reach, int lo[3], int hi[3]);
/* 1 when the point lies inside the domain [origin, origin + size] (inline:
 * the end-of-step state check asks it of every particle) */
static inline int mrn_grid_contains(const mrn_grid *g, const double x[3]) {
  for (int d = 0; d < g->dim; d++)
    if (!(x[d] >= g->origin[d] && x[d] <= g->origin[d] + g->size[d])) return 0;
  return 1;
}

#endif
