/* moraine: the transfer kernels in reference form.
 *
 * The three loops of an explicit MPM step as a textbook writes them, for
 * either dimension, every shape function and face treatment, and every
 * choice of the motion-integration scheme (000 §3, Table 1):
 *   P2G          particle by particle, node by node of its stencil;
 *   grid update  node by node;
 *   G2P          particle by particle, one rule for every velocity and
 *                position update.
 * The fast kernels (kernels.h) compute the same quantities, specialised by
 * dimension, shape and scheme, vectorised and blocked for threads;
 * tests/unit/test_kernels_reference.c holds them to this form. Nothing here
 * is meant to be fast: it says what the kernels compute.
 *
 * The transfer's `kernel` options choose the shape, the face treatment, the
 * MLS gradient and the periodic axes, as for the fast kernels. */
#ifndef MRN_TRANSFER_REFERENCE_H
#define MRN_TRANSFER_REFERENCE_H

#include <stddef.h>

#include "shape/shape.h"
#include "transfer/context.h"

/* room for the widest kernel (MRN_SHAPE_MAX_SUPPORT^3), CPDI's 2^d corners x
 * 2^d nodes, and a cpGIMP box reaching 6 nodes along every axis, half-widths
 * up to 2 cells (transfer/cpgimp.h) */
#define MRN_REF_STENCIL_MAX 216

/* The nodes particle p talks to: node indices, values N_i(x_p), gradients
 * grad N_i(x_p) and branch vectors x_i - x_p (000, Eq. 21); dN and off hold
 * `dim` values per node. */
typedef struct mrn_ref_stencil {
  int count;
  size_t node[MRN_REF_STENCIL_MAX];
  double N[MRN_REF_STENCIL_MAX];
  double dN[3 * MRN_REF_STENCIL_MAX];
  double off[3 * MRN_REF_STENCIL_MAX];
} mrn_ref_stencil;

void mrn_ref_stencil_build(const mrn_transfer *t, size_t p, mrn_ref_stencil *s);

/* particle p's stencil as the tensor product of 1D rows along each axis d:
 * n[d] nodes, their weights w and derivatives dw (per unit of grid
 * coordinate), node numbers `node` and grid coordinates `at` (from which
 * the branch vectors x_i - x_p are taken), row d at offset d * stride of
 * each array; n[2] = 1 in 2D. Nodes with x fastest. */
void mrn_ref_tensor_stencil(const mrn_transfer *t, size_t p, const int n[3], int stride, const double *w,
                            const double *dw, const int *node, const int *at, mrn_ref_stencil *s);

/* P2G: nodal mass, and momentum with the scheme's affine or Taylor term,
 * when `momentum`; internal force when `force`. Clears what it writes, on
 * the whole grid. */
void mrn_ref_p2g(const mrn_transfer *t, int momentum, int force);
/* particle p's share of it, s its stencil; adds to what t->grid holds */
void mrn_ref_p2g_add(const mrn_transfer *t, size_t p, const mrn_ref_stencil *s, int momentum, int force);

/* The grid update: V = p / m and V~ = V + dt (f / m + g), with the face
 * conditions of t->boundary on each (no damping, constraints or point
 * forces: solver/step.c adds those). */
void mrn_ref_grid_update(const mrn_transfer *t, double dt, const double gravity[3]);

/* G2P from V (grid.vel), V~ (grid.vel_new) and, for XPIC, V* (grid.vel_star):
 * new velocities, affine or Taylor matrices and position increments. When
 * `dx` is NULL the particles move, otherwise the increments go there (3 per
 * particle). When `L` is not NULL each particle's velocity gradient from V~
 * goes there (row-major 3 x 3, zero beyond dim). */
void mrn_ref_g2p(const mrn_transfer *t, double dt, double *dx, double *L);
/* the same for particle p alone (L, dx: the whole arrays, indexed by p) */
void mrn_ref_g2p_one(const mrn_transfer *t, size_t p, double dt, double *dx, double *L);

/* the velocity gradient L = sum_i gvel_i (x) grad N_i of the stencil s
 * (row-major 3 x 3, zero beyond dim; 000, Eqs. 44-45) */
void mrn_ref_gradient(const mrn_transfer *t, const mrn_ref_stencil *s, const double *gvel, double L[9]);

#endif
