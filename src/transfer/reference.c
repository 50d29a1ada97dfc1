/* moraine: the transfer kernels in reference form (see reference.h).
 *
 * Written for reading: one particle at a time, in index order, over the
 * nodes of its stencil, in any dimension. Each product is formed in the
 * order of the general form of the fast kernels (kernels_impl.h,
 * stencil_build), so that both give the same bits where they visit the
 * same terms in the same order, unless the compiler fuses a multiply-add in
 * one and not in the other (-ffp-contract). */
#include "transfer/reference.h"

#include <math.h>
#include <string.h>

#include "core/tensor.h"
#include "transfer/affine_fit.h"

/* ---- P2G ------------------------------------------------------------------------ */

/* m_i = sum_p N_ip m_p                                   (000, Eq. 6)
 * p_i = sum_p N_ip m_p (v_p + A_p (x_i - x_p))           (000, Eqs. 16, 19-20, 23-24)
 *       A_p the affine matrix C_p (APIC) or grad v_p (TPIC), 0 for plain
 * f_i = -sum_p V_p sigma_p grad N_ip                     (002, Fig. 1 step 3) */
void mrn_ref_p2g_add(const mrn_transfer *t, size_t p, const mrn_ref_stencil *s, int momentum, int force) {
  mrn_grid *g = t->grid;
  const mrn_particles *ps = t->particles;
  const int dim = t->dim, affine = t->scheme->grid_velocity != MRN_VGRID_PLAIN;
  const double m = ps->mass[p], vol = mrn_particle_volume_dim(ps, p, dim);
  const double *v = ps->v + 3 * p, *A = ps->affine + (size_t)(dim * dim) * p, *sig = ps->stress + 6 * p;
  for (int c = 0; c < s->count; c++) {
    const size_t i = s->node[c];
    const double *off = s->off + dim * c, *dN = s->dN + dim * c;
    if (momentum) {
      const double Nm = s->N[c] * m;
      g->mass[i] += Nm;
      for (int a = 0; a < dim; a++) {
        double va = v[a];
        if (affine)
          for (int b = 0; b < dim; b++) va += A[dim * a + b] * off[b];
        g->mom[3 * i + a] += Nm * va;
      }
    }
    if (force)
      for (int a = 0; a < dim; a++) {
        double sg = 0.0; /* (sigma grad N)_a */
        for (int b = 0; b < dim; b++) sg += sig[sym_index(a, b)] * dN[b];
        g->force[3 * i + a] -= vol * sg;
      }
  }
}

void mrn_ref_p2g(const mrn_transfer *t, int momentum, int force) {
  mrn_grid *g = t->grid;
  if (momentum) memset(g->mass, 0, g->n * sizeof(double));
  if (momentum) memset(g->mom, 0, 3 * g->n * sizeof(double));
  if (force) memset(g->force, 0, 3 * g->n * sizeof(double));
  mrn_ref_stencil s;
  for (size_t p = 0; p < t->particles->n; p++) {
    mrn_ref_stencil_build(t, p, &s);
    mrn_ref_p2g_add(t, p, &s, momentum, force);
  }
}

/* ---- grid update ----------------------------------------------------------------- */

/* V_i = p_i / m_i (000, Eq. 17), then the face conditions;
 * V~_i = V_i + dt (f_i / m_i + g) (000, Eq. 28), then the face conditions
 * with friction. Nodes at or below the mass floor are empty: V = V~ = 0. */
void mrn_ref_grid_update(const mrn_transfer *t, double dt, const double gravity[3]) {
  mrn_grid *g = t->grid;
  const double floor_mass = t->mass_floor;
  for (size_t i = 0; i < g->n; i++)
    for (int d = 0; d < 3; d++) g->vel[3 * i + d] = g->mass[i] > floor_mass ? g->mom[3 * i + d] / g->mass[i] : 0.0;
  mrn_boundary_apply(t->boundary, g, floor_mass, g->vel, 0);
  for (size_t i = 0; i < g->n; i++) {
    const double m = g->mass[i];
    for (int d = 0; d < 3; d++) {
      const double f = g->force[3 * i + d] + m * gravity[d];
      g->vel_new[3 * i + d] = m > floor_mass ? g->vel[3 * i + d] + dt * f / m : 0.0;
    }
  }
  mrn_boundary_apply(t->boundary, g, floor_mass, g->vel_new, 1);
}

/* ---- G2P ------------------------------------------------------------------------- */

/* What G2P interpolates to a particle from its stencil (000, Eqs. 11, 26, 44-45) */
typedef struct gathered {
  double v_pic[3];  /* sum N V~                    the PIC velocity (000, Eq. 31) */
  double v_old[3];  /* sum N V                     so that v_pic - v_old = a_p dt */
  double v_star[3]; /* sum N V*                    XPIC's smoothed velocity (000, Eq. 40) */
  double B[3][3];   /* sum N V~ (x) (x_i - x_p)    (000, Eq. 26) */
  double D[3][3];   /* sum N (x_i - x_p) (x) (x_i - x_p)  (000, Eq. 27) */
  double L[3][3];   /* sum V~ (x) grad N           grad v (000, Eqs. 44-45) */
} gathered;

static void gather(const mrn_transfer *t, const mrn_ref_stencil *s, gathered *q) {
  const mrn_grid *g = t->grid;
  const int dim = t->dim, xpic = t->scheme->velocity_update == MRN_VUPDATE_XPIC;
  memset(q, 0, sizeof *q);
  for (int c = 0; c < s->count; c++) {
    const double N = s->N[c], *V = g->vel_new + 3 * s->node[c];
    const double *off = s->off + dim * c, *dN = s->dN + dim * c;
    for (int a = 0; a < dim; a++) {
      q->v_pic[a] += N * V[a];
      q->v_old[a] += N * g->vel[3 * s->node[c] + a];
      if (xpic) q->v_star[a] += N * g->vel_star[3 * s->node[c] + a];
      for (int b = 0; b < dim; b++) {
        q->B[a][b] += N * V[a] * off[b];
        q->D[a][b] += N * off[a] * off[b];
        q->L[a][b] += V[a] * dN[b];
      }
    }
  }
}

/* APIC's C = B D^-1 (000, Eq. 25) or TPIC's grad v = L (000, Eq. 22) into
 * the particle's affine matrix (dim x dim stored); with the multilinear
 * kernel, whose D vanishes on grid lines, either is the mass-weighted fit of
 * transfer/affine_fit.h. */
static void affine_matrix(const mrn_transfer *t, const gathered *q, const double *x, double *A) {
  const int dim = t->dim;
  if (t->kernel.shape == MRN_SHAPE_LINEAR) {
    mrn_affine_fit(t->grid, &t->kernel, dim, t->mass_floor, x, A);
    return;
  }
  if (t->scheme->grid_velocity == MRN_VGRID_TAYLOR) {
    for (int a = 0; a < dim; a++)
      for (int b = 0; b < dim; b++) A[dim * a + b] = q->L[a][b];
    return;
  }
  double D[9] = {0, 0, 0, 0, 0, 0, 0, 0, 1}, Di[9]; /* plane strain: D_zz = 1 */
  for (int a = 0; a < dim; a++)
    for (int b = 0; b < dim; b++) D[3 * a + b] = q->D[a][b];
  if (mat_inverse(D, Di))
    for (int e = 0; e < 9; e++) Di[e] = NAN;
  for (int a = 0; a < dim; a++)
    for (int b = 0; b < dim; b++) {
      double C = 0.0;
      for (int e = 0; e < dim; e++) C += q->B[a][e] * Di[3 * e + b];
      A[dim * a + b] = C;
    }
}

/* One rule for every velocity and position update (000 Table 1), component
 * by component, with dv = v_pic - v_old = a_p dt:
 *   v_new = X (v + dv) + (1 - X) v_pic   PIC X = 0 (Eq. 31), FLIP X = 1 (Eq. 33), blend (Eq. 37)
 *   v_new = v_star + dv                  XPIC(m) (Eq. 40)
 *   dx    = v_pic dt                     with the grid velocity (Eq. 32)
 *   dx    = v_new dt                     with the particle velocity (Eqs. 36, 38)
 *   dx    = (v_pic - dv / 2 - (v - v_star) / 2) dt   XPIC(m) (Eq. 41) */
static void update_rule(const mrn_scheme *sc, double dt, double v_pic, double v_old, double v_star, double *v,
                        double *dx) {
  const mrn_velocity_update_kind vu = sc->velocity_update;
  const double X = vu == MRN_VUPDATE_FLIP ? 1.0 : vu == MRN_VUPDATE_BLEND ? sc->flip_fraction : 0.0;
  const double dv = v_pic - v_old;
  const double v_new = vu == MRN_VUPDATE_XPIC ? v_star + dv : X * (*v + dv) + (1.0 - X) * v_pic;
  switch (sc->position_update) {
  case MRN_XUPDATE_GRID: *dx = v_pic * dt; break;
  case MRN_XUPDATE_PARTICLE: *dx = v_new * dt; break;
  case MRN_XUPDATE_XPIC: *dx = dt * (v_pic - 0.5 * dv - 0.5 * (*v - v_star)); break;
  }
  *v = v_new;
}

void mrn_ref_g2p_one(const mrn_transfer *t, size_t p, double dt, double *dx, double *L) {
  mrn_particles *ps = t->particles;
  const int dim = t->dim;
  mrn_ref_stencil s;
  gathered q;
  mrn_ref_stencil_build(t, p, &s);
  gather(t, &s, &q);
  if (t->scheme->grid_velocity != MRN_VGRID_PLAIN) affine_matrix(t, &q, ps->x + 3 * p, ps->affine + (size_t)(dim * dim) * p);
  if (L)
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) L[9 * p + 3 * a + b] = q.L[a][b];
  double step[3] = {0, 0, 0};
  for (int d = 0; d < dim; d++)
    update_rule(t->scheme, dt, q.v_pic[d], q.v_old[d], q.v_star[d], ps->v + 3 * p + d, &step[d]);
  for (int d = 0; d < 3; d++) {
    if (dx) dx[3 * p + d] = step[d];
    else if (d < dim) ps->x[3 * p + d] += step[d];
  }
}

void mrn_ref_g2p(const mrn_transfer *t, double dt, double *dx, double *L) {
  for (size_t p = 0; p < t->particles->n; p++) mrn_ref_g2p_one(t, p, dt, dx, L);
}

void mrn_ref_gradient(const mrn_transfer *t, const mrn_ref_stencil *s, const double *gvel, double L[9]) {
  const int dim = t->dim;
  for (int e = 0; e < 9; e++) L[e] = 0.0;
  for (int c = 0; c < s->count; c++)
    for (int a = 0; a < dim; a++)
      for (int b = 0; b < dim; b++) L[3 * a + b] += gvel[3 * s->node[c] + a] * s->dN[dim * c + b];
}
