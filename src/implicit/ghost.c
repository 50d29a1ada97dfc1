/* moraine: ghost stabilisation of the implicit step (001 §7.4, which uses
 * it for the Taylor bar; the penalty of its ref. [50], W. M. Coombs, "Ghost
 * stabilisation of the material point method for stable quasi-static and
 * dynamic analysis of large deformation problems", arXiv:2209.10955).
 *
 * The grid displacement of the step, u(x) = sum_A N^h_A(x) u_A with the grid's
 * linear (hat) basis N^h (the basis under the linear and uGIMP shape
 * functions), has a normal gradient that jumps across cell faces. The
 * penalty adds to the residual the derivative of
 *   G(u) = 1/2 sum_F gamma E h^(2p-1) int_F [[grad u . n]] . [[grad u . n]] dA,  p = 1,
 * over the faces F shared by two active cells at least one of which is only
 * partly filled, i.e. f_ghost = K_g u with
 *   K_g(A i),(B k) = delta_ik gamma E h int_F [[dN_A/dn]] [[dN_B/dn]] dA
 * (gamma: the `ghost` option; E: the largest Young's modulus of the
 * materials; h: the cell size). For the hat basis across the face
 * x_d = x_f between cells [x_f - h, x_f] and [x_f, x_f + h] the jump
 * [[dN/dn]] = dN/dx_d(+) - dN/dx_d(-) is (1, -2, 1) / h times the face's
 * bilinear (3D) or linear (2D) tangential factor on the nodes at
 * x_f - h, x_f, x_f + h, so
 *   K_g = gamma E h (c_A c_B / h^2) M_F(A, B),  c = (1, -2, 1),
 *   M_F = (h / 6)^(dim - 1) prod_t m(a_t, b_t),  m = 2 on the same node, 1 otherwise,
 * the face mass matrix of the tangential factors. K_g is symmetric and
 * positive semi-definite, and every affine field (rigid translations and
 * rotations included) lies in its kernel, so linear and angular momentum are
 * untouched. It depends on the start-of-step cells only, so it is constant
 * during the Newton loop.
 *
 * Energy: u is the displacement of the step, so the penalty is not a stored
 * energy that carries over from step to step; with the mid-point rule the
 * grid kinetic energy changes by -(f_int + K_g u - f_ext) . u, i.e. the
 * ghost force removes u^T K_g u >= 0 per step. It is accumulated as
 * `ghost` in mrn_implicit_energy (doc/implicit.md).
 *
 * Cells: a cell is active when all its corner nodes are active in the step;
 * it is partly filled (cut by the body boundary) when the current volumes of
 * the material points whose centres lie in it add up to less than
 * MRN_GHOST_FULL of the cell volume. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "implicit/implicit_internal.h"

/* a cell with less than this fraction of its volume in material points is cut */
#define MRN_GHOST_FULL 0.999

/* 1 when the cell with lower corner ijk (domain numbering) has every corner active */
static int cell_active(const mrn_implicit *im, const int ijk[3]) {
  const mrn_grid *g = &im->sim->grid;
  for (int d = 0; d < im->dim; d++)
    if (ijk[d] < -g->pad || ijk[d] + 1 > g->ncell[d] + g->pad) return 0;
  for (int c = 0; c < (1 << im->dim); c++) {
    int n[3] = {ijk[0] + (c & 1), ijk[1] + ((c >> 1) & 1), ijk[2] + ((c >> 2) & 1)};
    if (im->dof[mrn_grid_index(g, n[0], n[1], n[2])] < 0) return 0;
  }
  return 1;
}

int mrn_implicit_ghost_build(mrn_implicit *im) {
  if (!(im->opt.ghost > 0)) return 0;
  const mrn_sim *sim = im->sim;
  const mrn_grid *g = &sim->grid;
  const int dim = im->dim;
  const size_t NR = (size_t)im->NR;
  const double h = g->cell;
  void *gq = realloc(im->Gb, im->act_cap * NR * sizeof(double));
  if (!gq) return mrn_error_code(MRN_ERR, "implicit: out of memory for the ghost penalty");
  im->Gb = gq;
  memset(im->Gb, 0, im->nact * NR * sizeof(double));
  /* im->cellvol: the points' volume in each cell (mrn_implicit_cell_volumes) */
  const double full = MRN_GHOST_FULL * pow(h, dim);
  const double coef = im->opt.ghost * im->ghost_modulus / h * pow(h / 6.0, dim - 1); /* gamma E h / h^2 (h/6)^(dim-1) */
  static const double cn[3] = {1.0, -2.0, 1.0};
  for (size_t a0 = 0; a0 < im->nact; a0++) {
    const int *lo = im->ijk + 3 * a0; /* lower corner of the cell below the face */
    if (!cell_active(im, lo)) continue;
    int cut_lo = im->cellvol[im->act[a0]] < full;
    for (int d = 0; d < dim; d++) {
      int up[3] = {lo[0], lo[1], lo[2]};
      up[d]++;
      if (!cell_active(im, up)) continue;
      if (!cut_lo && !(im->cellvol[mrn_grid_index(g, up[0], up[1], up[2])] < full)) continue;
      /* the 3 x 2^(dim-1) nodes of the jump: normal offset 0..2, tangential offsets 0..1 */
      const int t1 = (d + 1) % dim, t2 = dim == 3 ? (d + 2) % 3 : -1;
      const int nt = 1 << (dim - 1);
      size_t node[12];
      double c[12];
      int tang[12][2];
      int m = 0;
      for (int s = 0; s < 3; s++)
        for (int t = 0; t < nt; t++) {
          int n[3] = {lo[0], lo[1], lo[2]};
          n[d] += s;
          n[t1] += t & 1;
          if (t2 >= 0) n[t2] += (t >> 1) & 1;
          node[m] = (size_t)im->dof[mrn_grid_index(g, n[0], n[1], n[2])];
          c[m] = cn[s];
          tang[m][0] = t & 1, tang[m][1] = (t >> 1) & 1;
          m++;
        }
      for (int ia = 0; ia < m; ia++)
        for (int ib = 0; ib < m; ib++) {
          double mf = (tang[ia][0] == tang[ib][0] ? 2.0 : 1.0) * (dim == 3 ? (tang[ia][1] == tang[ib][1] ? 2.0 : 1.0) : 1.0);
          size_t idx = node[ib] * NR + (size_t)mrn_implicit_pair_index(im, node[ia], node[ib]);
          im->Gb[idx] += coef * c[ia] * c[ib] * mf;
          im->touched[idx] = 1;
        }
    }
  }
  return 0;
}

void mrn_implicit_ghost_apply(mrn_implicit *im) {
  if (!(im->opt.ghost > 0)) return;
  const size_t NR = (size_t)im->NR;
  for (size_t b = 0; b < im->nact; b++)
    for (int r = 0; r < im->NR; r++) {
      size_t idx = b * NR + (size_t)r;
      double k = im->Gb[idx];
      if (k == 0.0) continue;
      size_t a = (size_t)im->dof[(size_t)((long)im->act[b] + im->off[r])];
      for (int i = 0; i < im->dim; i++) {
        im->fint[3 * a + i] += k * im->u[3 * b + i];
        im->Kb[9 * idx + 4 * i] += k;
      }
    }
}

double mrn_implicit_ghost_work(const mrn_implicit *im) {
  if (!(im->opt.ghost > 0)) return 0.0;
  const size_t NR = (size_t)im->NR;
  double w = 0.0;
  for (size_t b = 0; b < im->nact; b++)
    for (int r = 0; r < im->NR; r++) {
      double k = im->Gb[b * NR + (size_t)r];
      if (k == 0.0) continue;
      size_t a = (size_t)im->dof[(size_t)((long)im->act[b] + im->off[r])];
      for (int i = 0; i < im->dim; i++) w += im->u[3 * a + i] * k * im->u[3 * b + i];
    }
  return w;
}
