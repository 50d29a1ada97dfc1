/* moraine: the grid side of the implicit step: stencils and active nodes,
 * mass matrices, assembly of forces and stiffness, the sparse systems. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/tensor.h"
#include "implicit/implicit_internal.h"
#include "material/principal.h"

static int grow(void **ptr, size_t bytes) {
  void *q = realloc(*ptr, bytes ? bytes : 1);
  if (!q) return mrn_error_code(MRN_ERR, "implicit: out of memory");
  *ptr = q;
  return 0;
}

/* Moving-least-squares functions on the nodes a stencil kept, with the
 * kernel weights N_A and the linear basis p_A = (1, x_A - x_p):
 *   N'_A = N_A p_A . M^-1 e_0,  grad_d N'_A = N_A p_A . M^-1 e_(d+1),
 *   M = sum_A N_A p_A p_A^T,
 * which reproduce constants and linear fields exactly (sum N' = 1,
 * sum N' x_A = x_p, sum grad N' = 0, sum (x_A - x_p) (x) grad N' = I), so
 * linear and angular momentum and the energy identities survive the removal
 * of a node. Returns 1 when the kept nodes cannot carry a linear field. */
static int relinearise(const mrn_grid *g, int dim, const double *xp, mrn_implicit_stencil *s) {
  const int n = dim + 1;
  double M[16] = {0}, pa[MRN_IMPLICIT_STENCIL_MAX][4], y[4][4];
  for (int k = 0; k < s->count; k++) {
    double xa[3];
    mrn_grid_node_position(g, s->node[k], xa);
    pa[k][0] = 1.0;
    for (int d = 0; d < dim; d++) pa[k][d + 1] = (xa[d] - xp[d]) * g->inv_cell; /* in cells, for conditioning */
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) M[n * i + j] += s->N[k] * pa[k][i] * pa[k][j];
  }
  for (int j = 0; j < n; j++) {
    double e[4] = {0};
    e[j] = 1.0;
    if (mrn_pinv_solve(n, M, e, 1e-10, y[j]) < n) return 1;
  }
  for (int k = 0; k < s->count; k++) {
    double w = s->N[k], Nk = 0.0;
    for (int i = 0; i < n; i++) Nk += pa[k][i] * y[0][i];
    for (int d = 0; d < 3; d++) {
      double gd = 0.0;
      if (d < dim)
        for (int i = 0; i < n; i++) gd += pa[k][i] * y[d + 1][i];
      s->dN[k][d] = w * gd * g->inv_cell; /* back from cells to metres */
    }
    s->N[k] = w * Nk;
  }
  return 0;
}

/* the stencils of the points at their start-of-step positions */
static void make_stencils(mrn_implicit *im) {
  const mrn_sim *sim = im->sim;
  const mrn_particles *ps = &sim->particles;
  const mrn_grid *g = &sim->grid;
  mrn_kernel_options kopt = {sim->shape, sim->kernel_boundary, 0, 0};
  for (size_t p = 0; p < im->np; p++) {
    if (im->dim == 2) mrn_implicit_stencil_2d(g, &kopt, ps->x + 3 * p, ps->vol0[p], &im->sten[p]);
    else mrn_implicit_stencil_3d(g, &kopt, ps->x + 3 * p, ps->vol0[p], &im->sten[p]);
  }
}

/* the lumped nodal masses of the stencils (im->gmass) and the heaviest point's mass */
static int node_masses(mrn_implicit *im, double *mmax) {
  const mrn_particles *ps = &im->sim->particles;
  const size_t nn = im->sim->grid.n;
  if (grow((void **)&im->gmass, nn * sizeof(double))) return MRN_ERR;
  memset(im->gmass, 0, nn * sizeof(double));
  *mmax = 0.0;
  for (size_t p = 0; p < im->np; p++) {
    *mmax = fmax(*mmax, ps->mass[p]);
    for (int k = 0; k < im->sten[p].count; k++) im->gmass[im->sten[p].node[k]] += ps->mass[p] * im->sten[p].N[k];
  }
  return 0;
}

/* The kept nodes cannot carry a linear field (all on one line): keep the
 * partition of unity only, N' = N / sum N, grad N' = grad N - N' sum grad N
 * (linear momentum and energy still hold, angular momentum not exactly). */
static int renormalise(const mrn_implicit *im, size_t p, mrn_implicit_stencil *s) {
  double sum = 0.0, gsum[3] = {0, 0, 0};
  for (int k = 0; k < s->count; k++) {
    sum += s->N[k];
    for (int d = 0; d < 3; d++) gsum[d] += s->dN[k][d];
  }
  if (!(sum > 0.0))
    return mrn_error_code(MRN_ERR_STATE, "implicit: particle %zu has no node above the mass floor (min_node_mass %g)",
                          p + 1, im->opt.min_node_mass);
  for (int k = 0; k < s->count; k++) {
    s->N[k] /= sum;
    for (int d = 0; d < 3; d++) s->dN[k][d] -= s->N[k] * gsum[d];
  }
  return 0;
}

/* Nodes that only the fringe of a shape function reaches (tiny mass, tiny
 * gradients) make the Jacobian nearly singular and Newton wander (001 §7.1
 * on integration errors). They are left out, and the points that touched
 * them get moving-least-squares functions on the nodes they keep
 * (relinearise), so momenta and the energy identities still hold. */
static int drop_light_nodes(mrn_implicit *im, double floor_mass) {
  const double *x = im->sim->particles.x;
  for (size_t p = 0; p < im->np; p++) {
    mrn_implicit_stencil *s = &im->sten[p];
    int c = 0, dropped = 0;
    for (int k = 0; k < s->count; k++) {
      if (im->gmass[s->node[k]] <= floor_mass) {
        dropped = 1;
        continue;
      }
      s->node[c] = s->node[k], s->N[c] = s->N[k];
      memcpy(s->dN[c], s->dN[k], sizeof s->dN[c]);
      c++;
    }
    s->count = c;
    if (!dropped || !relinearise(&im->sim->grid, im->dim, x + 3 * p, s)) continue;
    if (renormalise(im, p, s)) return MRN_ERR_STATE;
  }
  return 0;
}

/* room for the per-node arrays of `nact` active nodes */
static int reserve_active(mrn_implicit *im, size_t nact) {
  if (nact <= im->act_cap) return 0;
  size_t c = nact, NR = (size_t)im->NR;
  if (grow((void **)&im->act, c * sizeof(size_t)) || grow((void **)&im->ijk, 3 * c * sizeof(int)) ||
      grow((void **)&im->Kb, c * NR * 9 * sizeof(double)) || grow((void **)&im->Mc, c * NR * sizeof(double)) ||
      grow((void **)&im->touched, c * NR) || grow((void **)&im->ml, c * sizeof(double)) ||
      grow((void **)&im->fdof, 3 * c * sizeof(int)) || grow((void **)&im->vfix, 3 * c * sizeof(double)) ||
      grow((void **)&im->v0, 3 * c * sizeof(double)) ||
      grow((void **)&im->u, 3 * c * sizeof(double)) || grow((void **)&im->fint, 3 * c * sizeof(double)) ||
      grow((void **)&im->fext, 3 * c * sizeof(double)) || grow((void **)&im->p, 3 * c * sizeof(double)) ||
      grow((void **)&im->r, 3 * c * sizeof(double)) || grow((void **)&im->du, 3 * c * sizeof(double)))
    return MRN_ERR;
  im->act_cap = c;
  return 0;
}

/* the nodes some stencil reaches, numbered in grid order (im->dof, im->act, im->ijk) */
static int number_active_nodes(mrn_implicit *im) {
  const mrn_grid *g = &im->sim->grid;
  for (size_t i = 0; i < g->n; i++) im->dof[i] = -1;
  for (size_t p = 0; p < im->np; p++)
    for (int k = 0; k < im->sten[p].count; k++) im->dof[im->sten[p].node[k]] = 0;
  size_t nact = 0;
  for (size_t i = 0; i < g->n; i++)
    if (im->dof[i] == 0) nact++;
  if (reserve_active(im, nact)) return MRN_ERR;
  im->nact = 0;
  for (size_t i = 0; i < g->n; i++)
    if (im->dof[i] == 0) {
      size_t a = im->nact++;
      im->dof[i] = (int)a;
      im->act[a] = i;
      int ijk[3];
      mrn_grid_node_ijk(g, i, ijk);
      memcpy(im->ijk + 3 * a, ijk, sizeof ijk);
    }
  return 0;
}

/* Fixed components: the face conditions on the nodes on and beyond each
 * face (as the explicit step applies them, grid/boundary.h), then the grid
 * constraints (which take precedence, as in the explicit step); the free
 * ones are numbered in order (im->fdof, im->nfree). */
static void fix_components(mrn_implicit *im) {
  const mrn_sim *sim = im->sim;
  const size_t nact = im->nact;
  for (size_t a = 0; a < 3 * nact; a++) im->fdof[a] = 0, im->vfix[a] = 0.0;
  for (size_t a = 0; a < nact; a++)
    for (int axis = 0; axis < im->dim; axis++)
      for (int side = 0; side < 2; side++) {
        const mrn_face_bc *f = &sim->boundary.face[2 * axis + side];
        const int i = im->ijk[3 * a + axis];
        if (side == 0 ? i > 0 : i < sim->grid.ncell[axis]) continue;
        if (f->kind == MRN_BC_SLIP) im->fdof[im->dim * a + axis] = -1;
        if (f->kind == MRN_BC_FIXED || f->kind == MRN_BC_VELOCITY)
          for (int d = 0; d < im->dim; d++) {
            im->fdof[im->dim * a + d] = -1;
            im->vfix[3 * a + d] = f->kind == MRN_BC_VELOCITY ? f->velocity[d] : 0.0;
          }
      }
  for (int c = 0; c < sim->nconstraints; c++) {
    const mrn_constraint *con = &sim->constraints[c];
    for (size_t k = 0; k < con->count; k++) {
      int a = im->dof[con->nodes[k]];
      if (a < 0) continue;
      for (int d = 0; d < im->dim; d++)
        if (con->mask & (1u << d)) im->fdof[im->dim * a + d] = -1, im->vfix[3 * (size_t)a + d] = con->velocity[d];
    }
  }
  im->nfree = 0;
  for (size_t a = 0; a < nact * im->dim; a++)
    if (im->fdof[a] == 0) im->fdof[a] = im->nfree++;
}

/* stencils at the start-of-step positions, active nodes, fixed dofs */
int mrn_implicit_setup_step(mrn_implicit *im) {
  double mmax;
  make_stencils(im);
  if (node_masses(im, &mmax)) return MRN_ERR;
  int rc = drop_light_nodes(im, im->opt.min_node_mass * mmax);
  if (!rc) rc = number_active_nodes(im);
  if (!rc) fix_components(im);
  return rc;
}

/* mass matrices, grid momentum and external forces at mid-step (001 Eqs. 15-19, 26) */
void mrn_implicit_map_to_grid(mrn_implicit *im) {
  const mrn_particles *ps = &im->sim->particles;
  size_t nact = im->nact, NR = (size_t)im->NR;
  memset(im->Mc, 0, nact * NR * sizeof(double));
  memset(im->touched, 0, nact * NR);
  memset(im->ml, 0, nact * sizeof(double));
  memset(im->p, 0, 3 * nact * sizeof(double));
  memset(im->fext, 0, 3 * nact * sizeof(double));
  for (size_t q = 0; q < im->np; q++) {
    const mrn_implicit_stencil *s = &im->sten[q];
    double m = ps->mass[q];
    for (int k = 0; k < s->count; k++) {
      size_t a = (size_t)im->dof[s->node[k]];
      double mN = m * s->N[k];
      im->ml[a] += mN;
      for (int d = 0; d < im->dim; d++) {
        im->p[3 * a + d] += mN * ps->v[3 * q + d];
        im->fext[3 * a + d] += s->N[k] * im->load_factor * im->fpt[3 * q + d] + mN * im->sim->gravity[d];
      }
      for (int l = 0; l < s->count; l++) {
        size_t b = (size_t)im->dof[s->node[l]];
        size_t idx = b * NR + (size_t)mrn_implicit_pair_index(im, a, b);
        im->Mc[idx] += mN * s->N[l];
        im->touched[idx] = 1;
      }
    }
  }
}

/* effective mass entry of pair (b, r), 001 Eq. 18 */
static inline double mass_entry(const mrn_implicit *im, double eps, size_t b, int r) {
  double m = (1.0 - eps) * im->Mc[b * (size_t)im->NR + (size_t)r];
  if (r == im->rc) m += eps * im->ml[b];
  return m;
}

static double lumped_weight(const mrn_implicit *im) {
  return im->opt.mass == MRN_MASS_CONSISTENT ? 0.0 : im->opt.mass == MRN_MASS_LUMPED ? 1.0 : im->opt.eps;
}

/* the free-dof matrix alpha M~ + beta K in compressed columns */
int mrn_implicit_build_matrix(mrn_implicit *im, double alpha, double beta) {
  const double eps = lumped_weight(im);
  const int dim = im->dim;
  if (mrn_csc_reset(&im->A, im->nfree)) return MRN_ERR;
  for (size_t b = 0; b < im->nact; b++)
    for (int k = 0; k < dim; k++) {
      int col = im->fdof[dim * b + k];
      if (col < 0) continue;
      for (int r = 0; r < im->NR; r++) {
        size_t idx = b * (size_t)im->NR + (size_t)r;
        if (!im->touched[idx]) continue;
        size_t a = (size_t)im->dof[(size_t)((long)im->act[b] + im->off[r])];
        double m = alpha * mass_entry(im, eps, b, r);
        for (int i = 0; i < dim; i++) {
          int row = im->fdof[dim * a + i];
          if (row < 0) continue;
          double v = (i == k ? m : 0.0) + (beta != 0.0 ? beta * im->Kb[9 * idx + 3 * i + k] : 0.0);
          if (mrn_csc_push(&im->A, row, v)) return MRN_ERR;
        }
      }
      mrn_csc_end_column(&im->A, col);
    }
  return 0;
}

/* y = M~ x over all active components (x, y: 3 per active node) */
void mrn_implicit_mass_multiply(const mrn_implicit *im, const double *x, double *y) {
  const double eps = lumped_weight(im);
  memset(y, 0, 3 * im->nact * sizeof(double));
  for (size_t b = 0; b < im->nact; b++)
    for (int r = 0; r < im->NR; r++) {
      size_t idx = b * (size_t)im->NR + (size_t)r;
      if (!im->touched[idx]) continue;
      size_t a = (size_t)im->dof[(size_t)((long)im->act[b] + im->off[r])];
      double m = mass_entry(im, eps, b, r);
      for (int d = 0; d < im->dim; d++) y[3 * a + d] += m * x[3 * b + d];
    }
}

/* deformation-gradient increment dF = I + sum_A u_A (x) grad N_A (001 Eq. 25) */
void mrn_implicit_increment(const mrn_implicit *im, const mrn_implicit_stencil *s, double dF[9]) {
  mat_identity(dF);
  for (int k = 0; k < s->count; k++) {
    const double *u = im->u + 3 * (size_t)im->dof[s->node[k]];
    for (int i = 0; i < im->dim; i++)
      for (int j = 0; j < im->dim; j++) dF[3 * i + j] += u[i] * s->dN[k][j];
  }
}

size_t mrn_implicit_point_cell(const mrn_implicit *im, size_t p) {
  const mrn_grid *g = &im->sim->grid;
  const double *x = im->sim->particles.x + 3 * p;
  int c[3] = {0, 0, 0};
  for (int d = 0; d < im->dim; d++) {
    c[d] = (int)floor((x[d] - g->origin[d]) * g->inv_cell);
    c[d] = c[d] < -g->pad ? -g->pad : c[d] > g->ncell[d] + g->pad - 1 ? g->ncell[d] + g->pad - 1 : c[d];
  }
  return mrn_grid_index(g, c[0], c[1], c[2]);
}

int mrn_implicit_cell_volumes(mrn_implicit *im) {
  if (!(im->opt.ghost > 0) && !im->opt.bbar) return 0;
  const mrn_grid *g = &im->sim->grid;
  const mrn_particles *ps = &im->sim->particles;
  if (grow((void **)&im->cellvol, g->n * sizeof(double))) return MRN_ERR;
  memset(im->cellvol, 0, g->n * sizeof(double));
  /* V_0 det F: the step keeps the particles' F = F_t */
  for (size_t p = 0; p < ps->n; p++) im->cellvol[mrn_implicit_point_cell(im, p)] += mrn_particle_volume(ps, p);
  return 0;
}

/* internal forces (001 Eq. 44) and stiffness (001 Eq. A.10) at the current u */
void mrn_implicit_assemble(mrn_implicit *im) {
  const mrn_particles *ps = &im->sim->particles;
  const int dim = im->dim;
  const size_t NR = (size_t)im->NR;
  memset(im->fint, 0, 3 * im->nact * sizeof(double));
  memset(im->Kb, 0, im->nact * NR * 9 * sizeof(double));
  mrn_implicit_bbar_theta(im);
  for (size_t q = 0; q < im->np; q++) {
    const mrn_implicit_stencil *s = &im->sten[q];
    double dF[9], P[9], D[81];
    mrn_implicit_point_increment(im, q, dF);
    mrn_emc_tangent(&im->mat[ps->material[q]], &im->st[q], dF, dim, P, D, &im->res[q]);
    if (im->opt.bbar) mrn_implicit_bbar_point(im, q, P, D);
    const double V0 = ps->vol0[q];
    for (int k = 0; k < s->count; k++) {
      size_t a = (size_t)im->dof[s->node[k]];
      for (int i = 0; i < dim; i++)
        for (int j = 0; j < dim; j++) im->fint[3 * a + i] += V0 * P[3 * i + j] * s->dN[k][j];
    }
    /* K_(a i),(b k) = V0 dP_ij/d(dF_kl) dN_a,j dN_b,l */
    for (int lb = 0; lb < s->count; lb++) {
      size_t b = (size_t)im->dof[s->node[lb]];
      double Q[3][3][3] = {{{0}}}; /* Q[i][j][k] = sum_l D(kl, ij) dN_b,l */
      for (int i = 0; i < dim; i++)
        for (int j = 0; j < dim; j++)
          for (int kk = 0; kk < dim; kk++) {
            double sum = 0.0;
            for (int l = 0; l < dim; l++) sum += D[9 * (3 * kk + l) + 3 * i + j] * s->dN[lb][l];
            Q[i][j][kk] = V0 * sum;
          }
      for (int la = 0; la < s->count; la++) {
        size_t a = (size_t)im->dof[s->node[la]];
        double *Kab = im->Kb + 9 * (b * NR + (size_t)mrn_implicit_pair_index(im, a, b));
        for (int i = 0; i < dim; i++)
          for (int kk = 0; kk < dim; kk++) {
            double sum = 0.0;
            for (int j = 0; j < dim; j++) sum += Q[i][j][kk] * s->dN[la][j];
            Kab[3 * i + kk] += sum;
          }
      }
    }
  }
  mrn_implicit_bbar_cells(im);
  mrn_implicit_ghost_apply(im);
}

/* Solve M~ v = p on the free components. The consistent mass matrix is
 * singular when the points in a cell cannot tell its nodes apart (a single
 * row of points near the edge of a body), yet p = sum m N v_p always lies in
 * its range, and any solution keeps the FLIP energy identity (001 Eq. 38) --
 * but only as far as M~ v = p holds: the error (M~ v - p) . dv is an error
 * of the step's kinetic energy. So M~ (symmetric, positive semi-definite) is
 * solved by conjugate gradients preconditioned with the factorised
 * M~ + delta M_lumped (delta = 1e-10): the preconditioned operator has its
 * eigenvalues lambda / (lambda + delta) in (0, 1], clustered at 1 but for
 * the few nearly singular directions, which conjugate gradients resolve in a
 * few iterations (a plain iterative refinement with the same factor
 * contracts them only by delta / (lambda + delta) per pass). The loop stops
 * at max |M~ v - p| <= 1e-15 max |p|, after 100 iterations, or on a
 * direction M~ does not see. */
int mrn_implicit_project_velocity(mrn_implicit *im, const double *p, double *v) {
  const int n = im->nfree;
  const double delta = 1e-10;
  int rc = mrn_implicit_build_matrix(im, 1.0, 0.0);
  if (rc) return rc;
  mrn_csc M = im->A; /* borrow the arrays, then build the regularised copy */
  im->A = (mrn_csc){0};
  if ((rc = mrn_implicit_build_matrix(im, 1.0, 0.0))) goto out;
  for (size_t b = 0; b < im->nact; b++)
    for (int d = 0; d < im->dim; d++) {
      int c = im->fdof[im->dim * b + d];
      if (c < 0) continue;
      for (int k = im->A.colptr[c]; k < im->A.colptr[c + 1]; k++)
        if (im->A.rowind[k] == c) im->A.val[k] += delta * im->ml[b];
    }
  mrn_lu lu;
  if ((rc = mrn_lu_factor(&lu, &im->A))) goto out;
  size_t nn = n > 0 ? (size_t)n : 1;
  double *res = malloc(nn * sizeof(double)), *z = malloc(nn * sizeof(double)), *dir = malloc(nn * sizeof(double)),
         *Md = malloc(nn * sizeof(double));
  if (!res || !z || !dir || !Md) rc = mrn_error_code(MRN_ERR, "implicit: out of memory");
  double pn = 0.0, rz = 0.0;
  if (!rc) {
    for (int i = 0; i < n; i++) v[i] = 0.0, res[i] = p[i], pn = fmax(pn, fabs(p[i]));
    rc = mrn_lu_solve(&lu, &im->A, res, z);
    for (int i = 0; i < n && !rc; i++) dir[i] = z[i], rz += res[i] * z[i];
  }
  for (int it = 0; it < 100 && !rc && pn > 0.0; it++) {
    mrn_csc_multiply(&M, dir, Md);
    double dMd = 0.0;
    for (int i = 0; i < n; i++) dMd += dir[i] * Md[i];
    /* a direction M~ does not see: what is left of the residual lies where
     * the nearly singular M~ cannot take it (1e-12 to 1e-10 of max |p| in a
     * few steps of the Taylor bar, doc/implicit.md); stop there */
    if (!(dMd > 0.0)) break;
    const double alpha = rz / dMd;
    double rmax = 0.0;
    for (int i = 0; i < n; i++) {
      v[i] += alpha * dir[i];
      res[i] -= alpha * Md[i];
      rmax = fmax(rmax, fabs(res[i]));
    }
    if (rmax <= 1e-15 * pn) break;
    if ((rc = mrn_lu_solve(&lu, &im->A, res, z))) break;
    double rz_new = 0.0;
    for (int i = 0; i < n; i++) rz_new += res[i] * z[i];
    const double beta = rz_new / rz;
    rz = rz_new;
    for (int i = 0; i < n; i++) dir[i] = z[i] + beta * dir[i];
  }
  free(res), free(z), free(dir), free(Md);
  mrn_lu_free(&lu);
out:
  mrn_csc_free(&im->A);
  im->A = M;
  return rc;
}
