/* moraine: volumetric averaging of the implicit step's displacement
 * gradient over the cells (the option `bbar`): a B-bar form of the step
 * increment against volumetric locking.
 *
 * With several material points per cell every point's own increment
 * dF_p = I + H_p, H_p = sum_A u_A (x) grad N_A(x_p) (001 Eq. 25), has to
 * keep its own volume under nearly isochoric plastic flow: far more
 * volumetric constraints than the grid can meet, so the body locks (the
 * Taylor bar's mushroom stays small, doc/implicit.md). The option replaces
 * the divergence of each point's increment by the volume-weighted average
 * over the points in its start-of-step cell c:
 *   H~_p = H_p + (theta_c - tr H_p) / d I_d,
 *   theta_c = sum_(q in c) w_q tr H_q = sum_A u_A . g_A,
 *   g_A = sum_(q in c) w_q grad N_A(x_q),  w_q = V_q / sum_(q in c) V_q,
 * (d the dimension, I_d the in-plane identity, V_q the start-of-step volume)
 * and evaluates the algorithmic stress at dF~ = I + H~ (B-bar, applied to
 * the increment of the step). H~ is linear in u, so the internal force is
 * f = sum_p V_0 P(dF~_p) : dH~_p/du and u . f = sum_p V_0 P : H~_p: the
 * energy identity of 001 Eq. 56 holds as before (energy conservation and
 * the dissipation bookkeeping are unchanged). Every affine displacement
 * gives H~ = H, so constant fields and linear momentum are exact; angular
 * momentum is not exact any more (the averaged divergence of a point's
 * mid-point rotation is not its own).
 *
 * Force and stiffness. With c_A = g_A - grad N_A(x_p) the derivative of
 * H~_p along u_(A k) is e_k (x) grad N_A + c_(A k) / d I_d, so
 *   f_(A k) += V_0 tr_d(P) / d (g_(A k) - dN_A/dx_k),
 * and K = V_0 dH~/du : D : dH~/du (D = dP/d(dF), emc_stress.h) adds to the
 * point's own term (grid_system.c)
 *   V_0 [ -a_(A i) dN_B/dx_k / d - dN_A/dx_i b_(B k) / d + s dN_A/dx_i dN_B/dx_k / d^2 ]
 * on the point's stencil and, summed over the cell,
 *   (A_(A i) - Nn_(A i) / d) g_(B k) / d + g_(A i) (B_(B k) - Nn_(B k) / d) / d + S g_(A i) g_(B k) / d^2
 * on the union of its points' stencils, where
 *   a_(A i) = sum_j DV_ij dN_A/dx_j,  DV_ij = sum_(l<d) dP_ij/d(dF_ll),
 *   b_(B k) = sum_l DT_kl dN_B/dx_l,  DT_kl = sum_(m<d) dP_mm/d(dF_kl),
 *   s = sum_(l<d) DT_ll,
 *   A = sum_q V_0 a, B = sum_q V_0 b, Nn = sum_q V_0 s grad N, S = sum_q V_0 s.
 * Splitting the terms this way keeps the cost of a point at that of its
 * own stencil; the cell terms cost one product over the union per cell. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "implicit/implicit_internal.h"

static int grow(void **ptr, size_t bytes) {
  void *q = realloc(*ptr, bytes ? bytes : 1);
  if (!q) return mrn_error_code(MRN_ERR, "implicit: out of memory (bbar)");
  *ptr = q;
  return 0;
}

/* slot of active node a in cell c's union, appended when new; -1 when full */
static int union_slot(mrn_bbar_cell *c, int a) {
  for (int k = 0; k < c->count; k++)
    if (c->node[k] == a) return k;
  if (c->count == MRN_IMPLICIT_STENCIL_MAX) return -1;
  c->node[c->count] = a;
  memset(c->g[c->count], 0, sizeof c->g[0]);
  return c->count++;
}

int mrn_implicit_bbar_setup(mrn_implicit *im) {
  if (!im->opt.bbar) return 0;
  const mrn_grid *g = &im->sim->grid;
  const size_t np = im->np;
  if (grow((void **)&im->bb_of, (np ? np : 1) * sizeof(int)) ||
      grow((void **)&im->bb_slot, (np ? np : 1) * sizeof *im->bb_slot) ||
      grow((void **)&im->bb_index, g->n * sizeof(int)))
    return MRN_ERR;
  for (size_t i = 0; i < g->n; i++) im->bb_index[i] = -1;
  /* cells holding points, in order of first appearance */
  size_t ncell = 0;
  for (size_t p = 0; p < np; p++) {
    size_t key = mrn_implicit_point_cell(im, p);
    if (im->bb_index[key] < 0) {
      if (ncell >= im->bb_cap) {
        size_t cap = im->bb_cap ? 2 * im->bb_cap : 64;
        if (grow((void **)&im->bb, cap * sizeof *im->bb)) return MRN_ERR;
        im->bb_cap = cap;
      }
      im->bb[ncell].count = 0;
      im->bb[ncell].cell = key;
      im->bb_index[key] = (int)ncell++;
    }
    im->bb_of[p] = im->bb_index[key];
  }
  im->bb_n = ncell;
  /* union of the stencils and the averaged gradients g_A */
  for (size_t p = 0; p < np; p++) {
    mrn_bbar_cell *c = &im->bb[im->bb_of[p]];
    const mrn_implicit_stencil *s = &im->sten[p];
    const double w = mrn_particle_volume(&im->sim->particles, p) / im->cellvol[c->cell];
    for (int k = 0; k < s->count; k++) {
      int slot = union_slot(c, im->dof[s->node[k]]);
      if (slot < 0)
        return mrn_error_code(MRN_ERR, "implicit: bbar: the points of one cell reach more than %d nodes",
                              MRN_IMPLICIT_STENCIL_MAX);
      im->bb_slot[p][k] = (unsigned char)slot;
      for (int d = 0; d < 3; d++) c->g[slot][d] += w * s->dN[k][d];
    }
  }
  /* the union's node pairs enter the matrix */
  for (size_t ci = 0; ci < ncell; ci++) {
    const mrn_bbar_cell *c = &im->bb[ci];
    for (int ka = 0; ka < c->count; ka++)
      for (int kb = 0; kb < c->count; kb++) {
        size_t a = (size_t)c->node[ka], b = (size_t)c->node[kb];
        im->touched[b * (size_t)im->NR + (size_t)mrn_implicit_pair_index(im, a, b)] = 1;
      }
  }
  return 0;
}

void mrn_implicit_bbar_theta(mrn_implicit *im) {
  if (!im->opt.bbar) return;
  for (size_t ci = 0; ci < im->bb_n; ci++) {
    mrn_bbar_cell *c = &im->bb[ci];
    double th = 0.0;
    for (int k = 0; k < c->count; k++)
      for (int d = 0; d < im->dim; d++) th += c->g[k][d] * im->u[3 * (size_t)c->node[k] + d];
    c->theta = th;
    /* the assembly's sums start afresh */
    c->trP = 0.0, c->S = 0.0;
    memset(c->A, 0, (size_t)c->count * sizeof c->A[0]);
    memset(c->B, 0, (size_t)c->count * sizeof c->B[0]);
    memset(c->Nn, 0, (size_t)c->count * sizeof c->Nn[0]);
  }
}

void mrn_implicit_point_increment(const mrn_implicit *im, size_t p, double dF[9]) {
  mrn_implicit_increment(im, &im->sten[p], dF);
  if (!im->opt.bbar) return;
  const int d = im->dim;
  double tr = 0.0;
  for (int i = 0; i < d; i++) tr += dF[4 * i] - 1.0;
  const double shift = (im->bb[im->bb_of[p]].theta - tr) / d;
  for (int i = 0; i < d; i++) dF[4 * i] += shift;
}

void mrn_implicit_bbar_point(mrn_implicit *im, size_t p, const double P[9], const double D[81]) {
  const mrn_implicit_stencil *s = &im->sten[p];
  mrn_bbar_cell *c = &im->bb[im->bb_of[p]];
  const int dim = im->dim;
  const double V0 = im->sim->particles.vol0[p], inv_d = 1.0 / dim;
  const size_t NR = (size_t)im->NR;
  double DV[3][3] = {{0}}, DT[3][3] = {{0}}, s_vol = 0.0, trP = 0.0;
  for (int i = 0; i < dim; i++) {
    trP += P[4 * i];
    for (int j = 0; j < dim; j++)
      for (int l = 0; l < dim; l++) {
        DV[i][j] += D[9 * (4 * l) + 3 * i + j];
        DT[i][j] += D[9 * (3 * i + j) + 4 * l];
      }
  }
  for (int l = 0; l < dim; l++) s_vol += DT[l][l];
  double a[MRN_IMPLICIT_STENCIL_MAX][3], b[MRN_IMPLICIT_STENCIL_MAX][3];
  for (int k = 0; k < s->count; k++) {
    const int slot = im->bb_slot[p][k];
    const size_t node = (size_t)im->dof[s->node[k]];
    for (int i = 0; i < dim; i++) {
      a[k][i] = b[k][i] = 0.0;
      for (int j = 0; j < dim; j++) {
        a[k][i] += DV[i][j] * s->dN[k][j];
        b[k][i] += DT[i][j] * s->dN[k][j];
      }
      /* the point's part of the force: -V_0 tr(P) / d dN_A/dx_i */
      im->fint[3 * node + i] -= V0 * trP * inv_d * s->dN[k][i];
      c->A[slot][i] += V0 * a[k][i];
      c->B[slot][i] += V0 * b[k][i];
      c->Nn[slot][i] += V0 * s_vol * s->dN[k][i];
    }
  }
  c->trP += V0 * trP * inv_d;
  c->S += V0 * s_vol;
  /* the point's part of the stiffness, on its own stencil */
  for (int lb = 0; lb < s->count; lb++) {
    size_t nb = (size_t)im->dof[s->node[lb]];
    for (int la = 0; la < s->count; la++) {
      size_t na = (size_t)im->dof[s->node[la]];
      double *K = im->Kb + 9 * (nb * NR + (size_t)mrn_implicit_pair_index(im, na, nb));
      for (int i = 0; i < dim; i++)
        for (int k = 0; k < dim; k++)
          K[3 * i + k] += V0 * (-(a[la][i] * s->dN[lb][k] + s->dN[la][i] * b[lb][k]) * inv_d +
                                s_vol * s->dN[la][i] * s->dN[lb][k] * inv_d * inv_d);
    }
  }
}

void mrn_implicit_bbar_cells(mrn_implicit *im) {
  if (!im->opt.bbar) return;
  const int dim = im->dim;
  const double inv_d = 1.0 / dim;
  const size_t NR = (size_t)im->NR;
  for (size_t ci = 0; ci < im->bb_n; ci++) {
    const mrn_bbar_cell *c = &im->bb[ci];
    double left[MRN_IMPLICIT_STENCIL_MAX][3], right[MRN_IMPLICIT_STENCIL_MAX][3];
    for (int k = 0; k < c->count; k++) {
      const size_t node = (size_t)c->node[k];
      for (int i = 0; i < dim; i++) {
        im->fint[3 * node + i] += c->trP * c->g[k][i];
        left[k][i] = (c->A[k][i] - c->Nn[k][i] * inv_d) * inv_d;
        right[k][i] = (c->B[k][i] - c->Nn[k][i] * inv_d) * inv_d;
      }
    }
    const double S = c->S * inv_d * inv_d;
    for (int kb = 0; kb < c->count; kb++) {
      size_t nb = (size_t)c->node[kb];
      for (int ka = 0; ka < c->count; ka++) {
        size_t na = (size_t)c->node[ka];
        double *K = im->Kb + 9 * (nb * NR + (size_t)mrn_implicit_pair_index(im, na, nb));
        for (int i = 0; i < dim; i++)
          for (int k = 0; k < dim; k++)
            K[3 * i + k] += left[ka][i] * c->g[kb][k] + c->g[ka][i] * right[kb][k] + S * c->g[ka][i] * c->g[kb][k];
      }
    }
  }
}
