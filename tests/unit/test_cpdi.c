/* moraine: the CPDI stencil (transfer/cpdi.h), 2D and 3D.
 * - Partition of unity, gradients summing to zero, linear reproduction
 *   (sum S x_i = x_p, sum x_i (x) grad S = I) for undeformed and for
 *   sheared, stretched and rotated domains, at random positions: 1e-12.
 * - The gradient against the divergence theorem evaluated independently
 *   from the corners' coordinates (2D): (1/V) sum over the edges of the
 *   edge-mean of the corner-interpolated N_i times the edge's outward normal
 *   times its length, V the shoelace area: 1e-12.
 * - uGIMP: an undeformed square (cube) domain that no grid line crosses
 *   (one cell centred in a cell, or a smaller one inside a cell) gives
 *   uGIMP's weights and gradients to 1e-12. Where a grid line crosses the
 *   domain they differ by design: CPDI interpolates N_i linearly across the
 *   domain from its corners (a domain of one cell centred on a node gives
 *   that node 1/2 per axis, uGIMP 3/4).
 * - The kernels route CPDI through the reference stencil: P2G gives the
 *   reference's nodal values bit for bit, conserves mass and momentum, and
 *   the internal forces sum to zero; a domain stretched far beyond the grid
 *   (corners taken back onto the last ghost nodes) keeps the partition of
 *   unity and its nodes inside the padded grid.
 * - The gradient bound behind the CFL step (mrn_cpdi_gradient_bound): an
 *   undeformed domain stays within the hat's own largest gradient,
 *   sqrt(dim) / h, so the particle CFL step is bit for bit the linear
 *   kernel's; a thin domain sheared over many cells (principal stretches
 *   30 and 0.16, the aspect ratio of 190 reached in the shear band of a
 *   collapsing column) exceeds 5 times that somewhere (no average of the
 *   hat's gradient can), and the CFL step falls at least 5 times.
 * - Whole explicit steps (PIC, FLIP, APIC, TPIC x USF, USL, MUSL, USAVG,
 *   no gravity, free faces, deformed domains): the total momentum stays to
 *   1e-12 of sum m |v|, since every transfer of a step uses the domains the
 *   step froze; likewise with CPDI2 in 2D, whose quadrilaterals are
 *   recentred on the particles after each step.
 * CPDI2 (transfer/cpdi2.h), 2D, on quadrilaterals that are not
 * parallelograms:
 * - w_c and g_c against a 3 x 3 Gauss quadrature of M_c det J and of
 *   adj(J)^T grad_xi M_c over the reference square (exact for these
 *   polynomials), and V_p against the shoelace area: 1e-12.
 * - Partition of unity, gradients summing to zero, sum x_i (x) grad S = I,
 *   and sum S_ip x_i = the polygon's centroid (its own formula) for a
 *   particle placed anywhere in its domain: 1e-12.
 * - A parallelogram (corners unset, or stored as A xi_c) gives CPDI1's
 *   weights and gradients node by node: 1e-12.
 * - The corner update under an affine grid velocity V~ = v0 + L x moves the
 *   offsets to (I + dt L) off exactly (1e-12), so that a homogeneous
 *   deformation keeps the parallelogram of CPDI1's (I + dt L) F U0. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/tensor.h"
#include "material/material.h"
#include "solver/simulation.h"
#include "solver/timestep.h"
#include "transfer/cpdi.h"
#include "transfer/cpdi2.h"
#include "transfer/kernels.h"
#include "transfer/reference.h"

#define TOL 1e-12

#include "domain_shapes.h"

static void random_F(int dim, double *F) {
  double M[9];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) M[3 * a + b] = (a == b ? 0.5 + 2.0 * rnd() : 0.0) + (a < b ? 1.5 * (rnd() - 0.5) : 0.0);
  const double angle = 6.0 * rnd(), c = cos(angle), s = sin(angle);
  const double R[9] = {c, -s, 0, s, c, 0, 0, 0, 1};
  double RM[9];
  mat_mul(R, M, RM);
  for (int a = 0; a < dim; a++)
    for (int b = 0; b < dim; b++) F[dim * a + b] = RM[3 * a + b];
}

/* node position along d */
static double node_x(const mrn_sim *sim, size_t node, int d) {
  int ijk[3];
  mrn_grid_node_ijk(&sim->grid, node, ijk);
  return sim->grid.origin[d] + ijk[d] * sim->grid.cell;
}

static void consistency(int dim, int deformed) {
  mrn_sim *sim = make_sim(dim, MRN_SHAPE_CPDI);
  for (int k = 0; k < 40; k++) {
    double xi[3] = {0, 0, 0}, F[9];
    for (int d = 0; d < dim; d++) xi[d] = 5.0 + 6.0 * rnd();
    random_F(dim, F);
    add(sim, xi, 0.3 + 1.2 * rnd(), deformed ? F : NULL);
  }
  mrn_transfer t = mrn_sim_transfer(sim);
  mrn_ref_stencil s;
  double worst = 0.0;
  for (size_t p = 0; p < sim->particles.n; p++) {
    mrn_ref_stencil_build(&t, p, &s);
    worst = fmax(worst, consistency_error(&s, dim, sim->grid.cell));
  }
  printf("%dD %s: worst partition of unity / gradient sum / linear reproduction error %.2e\n", dim,
         deformed ? "deformed" : "undeformed", worst);
  CHECK(worst < TOL);
  mrn_sim_free(sim);
}

/* (N, dN) summed per node over a stencil's entries into acc (1 + dim per node) */
static void per_node(const mrn_ref_stencil *s, int dim, double *acc) {
  for (int c = 0; c < s->count; c++) {
    acc[(1 + dim) * s->node[c]] += s->N[c];
    for (int d = 0; d < dim; d++) acc[(1 + dim) * s->node[c] + 1 + d] += s->dN[dim * c + d];
  }
}

/* the divergence theorem on the quadrilateral of the 2D corners */
static void divergence_2d(void) {
  mrn_sim *sim = make_sim(2, MRN_SHAPE_CPDI);
  const mrn_grid *g = &sim->grid;
  double worst = 0.0;
  for (int k = 0; k < 40; k++) {
    double xi[3] = {5.0 + 6.0 * rnd(), 5.0 + 6.0 * rnd(), 0}, F[4];
    random_F(2, F);
    const size_t p = add(sim, xi, 0.3 + 1.2 * rnd(), F);
    mrn_transfer t = mrn_sim_transfer(sim);
    mrn_ref_stencil s;
    mrn_ref_stencil_build(&t, p, &s);
    double *cp = calloc(3 * g->n, sizeof(double));
    per_node(&s, 2, cp);
    /* the corners, counter-clockwise: (-1,-1), (1,-1), (1,1), (-1,1) */
    const double r = 0.5 * sqrt(sim->particles.vol0[p]), *x = sim->particles.x + 3 * p;
    const double sg[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    double X[4][2], area = 0.0;
    for (int c = 0; c < 4; c++)
      for (int a = 0; a < 2; a++) X[c][a] = x[a] + r * (F[2 * a] * sg[c][0] + F[2 * a + 1] * sg[c][1]);
    for (int c = 0; c < 4; c++) area += 0.5 * (X[c][0] * X[(c + 1) % 4][1] - X[(c + 1) % 4][0] * X[c][1]);
    for (size_t i = 0; i < g->n; i++) {
      double Nc[4], grad[2] = {0, 0};
      for (int c = 0; c < 4; c++) { /* the hat function of node i at corner c */
        Nc[c] = 1.0;
        for (int a = 0; a < 2; a++) Nc[c] *= fmax(0.0, 1.0 - fabs(X[c][a] - node_x(sim, i, a)) * g->inv_cell);
      }
      for (int c = 0; c < 4; c++) {
        const int e = (c + 1) % 4;
        const double mean = 0.5 * (Nc[c] + Nc[e]);
        grad[0] += mean * (X[e][1] - X[c][1]) / area;
        grad[1] -= mean * (X[e][0] - X[c][0]) / area;
      }
      for (int a = 0; a < 2; a++) worst = fmax(worst, fabs(cp[3 * i + 1 + a] - grad[a]) * g->cell);
    }
    free(cp);
  }
  printf("2D gradient against the divergence theorem on the corners: worst %.2e\n", worst);
  CHECK(worst < TOL);
  mrn_sim_free(sim);
}

/* one particle's stencil per node, CPDI against uGIMP (same particle, same grid) */
static double against_gimp(mrn_sim *sim, size_t p, double *cp, double *gp) {
  const int dim = sim->dim, w = 1 + dim;
  const size_t n = sim->grid.n;
  memset(cp, 0, w * n * sizeof(double));
  memset(gp, 0, w * n * sizeof(double));
  mrn_transfer t = mrn_sim_transfer(sim);
  mrn_ref_stencil s;
  mrn_ref_stencil_build(&t, p, &s);
  per_node(&s, dim, cp);
  t.kernel.shape = MRN_SHAPE_GIMP;
  mrn_ref_stencil_build(&t, p, &s);
  per_node(&s, dim, gp);
  double worst = 0.0;
  for (size_t k = 0; k < w * n; k++) worst = fmax(worst, fabs(cp[k] - gp[k]) * (k % w ? sim->grid.cell : 1.0));
  return worst;
}

static void gimp(int dim) {
  mrn_sim *sim = make_sim(dim, MRN_SHAPE_CPDI);
  const size_t n = sim->grid.n, w = (size_t)(1 + dim);
  double *cp = calloc(w * n, sizeof(double)), *gp = calloc(w * n, sizeof(double));
  double worst = 0.0;
  for (int k = 0; k < 20; k++) {
    /* a domain of one cell centred in a cell, and a smaller one that no grid line crosses */
    const double side = k % 2 ? 1.0 : 0.2 + 0.6 * rnd();
    double xi[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) xi[d] = 4 + k % 7 + (k % 2 ? 0.5 : 0.5 * side + (1.0 - side) * rnd());
    worst = fmax(worst, against_gimp(sim, add(sim, xi, side, NULL), cp, gp));
  }
  printf("%dD undeformed domains inside a cell: worst difference from uGIMP %.2e\n", dim, worst);
  CHECK(worst < TOL);
  /* one cell centred on a node: CPDI gives the node 1/2 per axis, uGIMP 3/4 */
  const double xi[3] = {8, 8, 8};
  const size_t p = add(sim, xi, 1.0, NULL);
  against_gimp(sim, p, cp, gp);
  const size_t node = mrn_grid_index(&sim->grid, 8, 8, dim == 3 ? 8 : 0);
  CHECK_CLOSE(cp[w * node], pow(0.5, dim), TOL);
  CHECK_CLOSE(gp[w * node], pow(0.75, dim), TOL);
  free(cp);
  free(gp);
  mrn_sim_free(sim);
}

/* P2G through the kernels: the reference's nodal values bit for bit, mass
 * and momentum conserved, internal forces summing to zero */
static void kernels(int dim) {
  mrn_sim *sim = make_sim(dim, MRN_SHAPE_CPDI);
  for (int k = 0; k < 300; k++) {
    double xi[3] = {0, 0, 0}, F[9];
    for (int d = 0; d < dim; d++) xi[d] = 3.0 + 10.0 * rnd();
    random_F(dim, F);
    add(sim, xi, 0.3 + 1.2 * rnd(), F);
  }
  mrn_sim_particles_changed(sim);
  mrn_grid *g = &sim->grid;
  mrn_transfer t = mrn_sim_transfer(sim);
  p2g_against_reference(sim, &t);
  /* a particle by the lower x face, its domain 20 cells long along x */
  const double xi[3] = {0.5, 8, 8}, F[9] = {40, 0, 0, 0, 1, 0, 0, 0, 1}, F2[4] = {40, 0, 0, 1};
  const size_t p = add(sim, xi, 1.0, dim == 2 ? F2 : F);
  mrn_ref_stencil s;
  mrn_ref_stencil_build(&t, p, &s);
  double sum = 0.0;
  for (int c = 0; c < s.count; c++) {
    sum += s.N[c];
    CHECK(s.node[c] < g->n);
  }
  CHECK_CLOSE(sum, 1.0, TOL);
  mrn_sim_free(sim);
}

/* total momentum through steps of each strategy and stress update */
static void steps(int dim, mrn_shape_kind shape) {
  static const char *const presets[] = {"PIC", "FLIP", "APIC", "TPIC"};
  double worst = 0.0;
  for (int k = 0; k < 4; k++)
    for (int u = MRN_STRESS_USF; u <= MRN_STRESS_USAVG; u++) {
      mrn_sim *sim = make_sim(dim, shape);
      CHECK(mrn_scheme_from_preset(presets[k], &sim->scheme) == 0);
      sim->scheme.stress_update = (mrn_stress_update_kind)u;
      add_elastic(sim);
      for (int p = 0; p < 60; p++) {
        double xi[3] = {0, 0, 0}, F[9] = {0};
        for (int d = 0; d < dim; d++) xi[d] = 5.0 + 6.0 * rnd();
        for (int a = 0; a < dim; a++)
          for (int b = 0; b < dim; b++) F[dim * a + b] = (a == b) + 0.3 * (rnd() - 0.5);
        add(sim, xi, 0.5, F);
      }
      worst = fmax(worst, momentum_drift(sim));
      mrn_sim_free(sim);
    }
  printf("%dD %s steps, every strategy and stress update: worst momentum change %.2e of sum m |v|\n", dim,
         mrn_shape_info_of(shape)->name, worst);
  CHECK(worst < TOL);
}

/* `count` particles of side 0.5 cells at random places, each with F (dim x
 * dim stored; NULL: I) turned by a random rotation when `turn`, in an
 * elastic material, on a sim of shape `shape` */
static mrn_sim *bound_sim(int dim, mrn_shape_kind shape, const double *F, int turn, int count, unsigned seed) {
  mrn_sim *sim = make_sim(dim, shape);
  add_elastic(sim);
  domain_seed = seed;
  for (int p = 0; p < count; p++) {
    double xi[3] = {0, 0, 0}, Fp[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int d = 0; d < dim; d++) xi[d] = 5.0 + 6.0 * rnd();
    if (dim == 2) Fp[1] = 0, Fp[2] = 0, Fp[3] = 1; /* 2 x 2 stored */
    if (F) {
      const double a = turn ? 3.14159 * rnd() : 0.0, b = turn ? 3.14159 * rnd() : 0.0;
      const double R[4] = {cos(a), -sin(a), sin(a), cos(a)}, Q[4] = {cos(b), -sin(b), sin(b), cos(b)};
      double RF[4];
      for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) RF[2 * i + j] = R[2 * i] * F[j] + R[2 * i + 1] * F[2 + j];
      for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) Fp[2 * i + j] = RF[2 * i] * Q[j] + RF[2 * i + 1] * Q[2 + j];
    }
    add(sim, xi, 0.5, Fp);
    for (int d = 0; d < 3; d++) sim->particles.v[3 * (size_t)p + d] = 0.0;
  }
  mrn_sim_particles_changed(sim);
  return sim;
}

static double largest_bound(mrn_sim *sim) {
  const mrn_transfer t = mrn_sim_transfer(sim);
  double worst = 0.0;
  for (size_t p = 0; p < sim->particles.n; p++) worst = fmax(worst, mrn_cpdi_gradient_bound(&t, p));
  return worst * sim->grid.cell;
}

static void gradient_bound(void) {
  mrn_sim *plain = bound_sim(2, MRN_SHAPE_CPDI, NULL, 0, 200, 777u);
  mrn_sim *linear = bound_sim(2, MRN_SHAPE_LINEAR, NULL, 0, 200, 777u);
  const double undeformed = largest_bound(plain);
  CHECK(undeformed <= sqrt(2.0));
  CHECK(mrn_dt_particle_critical(plain) == mrn_dt_particle_critical(linear));
  static const double thin[4] = {30.0, 0.0, 0.0, 0.16}; /* principal stretches, turned at random */
  mrn_sim *sheared = bound_sim(2, MRN_SHAPE_CPDI, thin, 1, 200, 778u);
  mrn_sim *same = bound_sim(2, MRN_SHAPE_LINEAR, thin, 1, 200, 778u);
  const double amplified = largest_bound(sheared), ratio = mrn_dt_particle_critical(same) / mrn_dt_particle_critical(sheared);
  printf("2D CPDI gradient bound: h |grad S| up to %.3f undeformed, %.2f stretched 30 x 0.16; CFL step %.2f times "
         "smaller\n", undeformed, amplified, ratio);
  CHECK(amplified > 5.0 * sqrt(2.0));
  CHECK(ratio > 5.0);
  mrn_sim_free(plain), mrn_sim_free(linear), mrn_sim_free(sheared), mrn_sim_free(same);
}

/* ---- CPDI2 ------------------------------------------------------------------------ */

/* a convex quadrilateral about the origin (offsets, counter-clockwise from
 * (-1,-1)): a random parallelogram A xi_c of about `size` with each corner
 * moved by up to a fifth of it */
static void random_quad(double size, double q[4][2]) {
  double F[4];
  random_F(2, F);
  for (int c = 0; c < 4; c++)
    for (int a = 0; a < 2; a++)
      q[c][a] = size * (0.5 * (F[2 * a] * mrn_cpdi2_xi[c][0] + F[2 * a + 1] * mrn_cpdi2_xi[c][1]) +
                        0.2 * (rnd() - 0.5));
}

/* the shoelace area and the polygon's centroid */
static double polygon(const double q[4][2], double centroid[2]) {
  double area = 0.0;
  centroid[0] = centroid[1] = 0.0;
  for (int c = 0; c < 4; c++) {
    const double *u = q[c], *v = q[(c + 1) % 4], k = u[0] * v[1] - v[0] * u[1];
    area += 0.5 * k;
    for (int a = 0; a < 2; a++) centroid[a] += (u[a] + v[a]) * k / 6.0;
  }
  for (int a = 0; a < 2; a++) centroid[a] /= area;
  return area;
}

/* w_c, g_c and V_p against quadrature over the reference square */
static void cpdi2_integrals(void) {
  static const double gx[3] = {-0.7745966692414834, 0.0, 0.7745966692414834}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double worst = 0.0;
  for (int k = 0; k < 200; k++) {
    double q[4][2], w[4], g[4][2], cen[2], wq[4] = {0}, gq[4][2] = {{0}};
    random_quad(0.5 + rnd(), q);
    const double V = mrn_cpdi2_integrals(q, w, g), area = polygon(q, cen);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        const double xi = gx[i], eta = gx[j];
        double J[2][2] = {{0, 0}, {0, 0}}; /* dx_a / d(xi, eta)_b */
        for (int c = 0; c < 4; c++) {
          const double xc = mrn_cpdi2_xi[c][0], ec = mrn_cpdi2_xi[c][1];
          for (int a = 0; a < 2; a++) {
            J[a][0] += 0.25 * xc * (1 + ec * eta) * q[c][a];
            J[a][1] += 0.25 * ec * (1 + xc * xi) * q[c][a];
          }
        }
        const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        for (int c = 0; c < 4; c++) {
          const double xc = mrn_cpdi2_xi[c][0], ec = mrn_cpdi2_xi[c][1];
          const double M = 0.25 * (1 + xc * xi) * (1 + ec * eta), dM[2] = {0.25 * xc * (1 + ec * eta),
                                                                             0.25 * ec * (1 + xc * xi)};
          wq[c] += gw[i] * gw[j] * M * det;
          /* grad M det J = adj(J)^T grad_xi M */
          gq[c][0] += gw[i] * gw[j] * (J[1][1] * dM[0] - J[1][0] * dM[1]);
          gq[c][1] += gw[i] * gw[j] * (-J[0][1] * dM[0] + J[0][0] * dM[1]);
        }
      }
    worst = fmax(worst, fabs(V - area) / area);
    for (int c = 0; c < 4; c++) {
      worst = fmax(worst, fabs(w[c] - wq[c]) / area);
      for (int a = 0; a < 2; a++) worst = fmax(worst, fabs(g[c][a] - gq[c][a]) / sqrt(area));
    }
  }
  printf("CPDI2 w_c, g_c, V_p against quadrature and the shoelace area: worst %.2e\n", worst);
  CHECK(worst < TOL);
}

/* particle p's corner offsets stored in the CPDI2 field */
static void store_quad(mrn_sim *sim, size_t p, const double q[4][2]) {
  mrn_particles *ps = &sim->particles;
  const mrn_user_field *u = mrn_particles_user_field(ps, MRN_CPDI2_FIELD);
  if (!u) {
    CHECK(mrn_particles_add_user_field(ps, MRN_CPDI2_FIELD, 8, 0.0, "m") == 0);
    u = mrn_particles_user_field(ps, MRN_CPDI2_FIELD);
  }
  memcpy(ps->user + p * (size_t)ps->user_stride + (size_t)u->offset, q, 8 * sizeof(double));
}

/* the stencil's sums on quadrilaterals, the particle anywhere inside */
static void cpdi2_consistency(void) {
  mrn_sim *sim = make_sim(2, MRN_SHAPE_CPDI2);
  double cen[40][2];
  for (int k = 0; k < 40; k++) {
    double xi[3] = {5.0 + 6.0 * rnd(), 5.0 + 6.0 * rnd(), 0}, q[4][2], shift[2] = {rnd() - 0.5, rnd() - 0.5};
    random_quad(0.1 + 0.15 * rnd(), q);
    polygon(q, cen[k]);
    for (int c = 0; c < 4; c++) /* the particle off the centroid by up to a tenth of the domain */
      for (int a = 0; a < 2; a++) q[c][a] -= cen[k][a] + 0.2 * shift[a] * (q[2][a] - q[0][a]);
    polygon(q, cen[k]);
    store_quad(sim, add(sim, xi, 1.0, NULL), q);
  }
  mrn_transfer t = mrn_sim_transfer(sim);
  mrn_ref_stencil s;
  double worst = 0.0;
  for (size_t p = 0; p < sim->particles.n; p++) {
    mrn_ref_stencil_build(&t, p, &s);
    double sum = 0.0, gsum[2] = {0, 0}, xs[2] = {0, 0}, G[2][2] = {{0}};
    for (int c = 0; c < s.count; c++) {
      sum += s.N[c];
      for (int a = 0; a < 2; a++) {
        gsum[a] += s.dN[2 * c + a];
        xs[a] += s.N[c] * s.off[2 * c + a];
        for (int b = 0; b < 2; b++) G[a][b] += s.off[2 * c + a] * s.dN[2 * c + b];
      }
    }
    worst = fmax(worst, fabs(sum - 1.0));
    for (int a = 0; a < 2; a++) {
      worst = fmax(worst, fabs(gsum[a]) * sim->grid.cell);
      worst = fmax(worst, fabs(xs[a] - cen[p][a]) / sim->grid.cell); /* sum S x_i = the centroid */
      for (int b = 0; b < 2; b++) worst = fmax(worst, fabs(G[a][b] - (a == b)));
    }
  }
  printf("CPDI2 quadrilaterals: worst partition of unity / gradient sum / centroid / linear gradient error %.2e\n",
         worst);
  CHECK(worst < TOL);
  mrn_sim_free(sim);
}

/* particle p's per-node (N, dN) under CPDI and under CPDI2, the largest difference */
static double against_cpdi1(mrn_sim *sim, size_t p, double *a, double *b) {
  const size_t n = 3 * sim->grid.n;
  memset(a, 0, n * sizeof(double));
  memset(b, 0, n * sizeof(double));
  mrn_transfer t = mrn_sim_transfer(sim);
  mrn_ref_stencil s;
  t.kernel.shape = MRN_SHAPE_CPDI;
  mrn_ref_stencil_build(&t, p, &s);
  per_node(&s, 2, a);
  t.kernel.shape = MRN_SHAPE_CPDI2;
  mrn_ref_stencil_build(&t, p, &s);
  per_node(&s, 2, b);
  double worst = 0.0;
  for (size_t k = 0; k < n; k++) worst = fmax(worst, fabs(a[k] - b[k]) * (k % 3 ? sim->grid.cell : 1.0));
  return worst;
}

/* a parallelogram, unset or stored: CPDI1's stencil */
static void cpdi2_parallelogram(void) {
  mrn_sim *sim = make_sim(2, MRN_SHAPE_CPDI2);
  double *a = calloc(3 * sim->grid.n, sizeof(double)), *b = calloc(3 * sim->grid.n, sizeof(double));
  double worst = 0.0;
  for (int k = 0; k < 40; k++) {
    double xi[3] = {5.0 + 6.0 * rnd(), 5.0 + 6.0 * rnd(), 0}, F[4], q[4][2];
    random_F(2, F);
    const size_t p = add(sim, xi, 0.3 + 1.2 * rnd(), F);
    worst = fmax(worst, against_cpdi1(sim, p, a, b)); /* unset: formed from F */
    const double r = 0.5 * sqrt(sim->particles.vol0[p]);
    for (int c = 0; c < 4; c++)
      for (int d = 0; d < 2; d++) q[c][d] = r * (F[2 * d] * mrn_cpdi2_xi[c][0] + F[2 * d + 1] * mrn_cpdi2_xi[c][1]);
    store_quad(sim, p, q);
    worst = fmax(worst, against_cpdi1(sim, p, a, b)); /* stored */
  }
  printf("CPDI2 on parallelograms against CPDI1: worst difference %.2e\n", worst);
  CHECK(worst < TOL);
  free(a);
  free(b);
  mrn_sim_free(sim);
}

/* the corners under an affine V~ = v0 + L x: offsets (I + dt L) off, and
 * the parallelogram CPDI1 forms from (I + dt L) F */
static void cpdi2_affine_update(void) {
  mrn_sim *sim = make_sim(2, MRN_SHAPE_CPDI2);
  mrn_grid *g = &sim->grid;
  const double dt = 0.05, v0[2] = {0.3, -0.2}, L[2][2] = {{0.4, 1.1}, {-0.7, -0.3}};
  for (size_t i = 0; i < g->n; i++)
    for (int a = 0; a < 2; a++) g->vel_new[3 * i + a] = v0[a] + L[a][0] * node_x(sim, i, 0) + L[a][1] * node_x(sim, i, 1);
  double F[40][4], before[40][4][2];
  for (int k = 0; k < 40; k++) {
    double xi[3] = {5.0 + 6.0 * rnd(), 5.0 + 6.0 * rnd(), 0};
    random_F(2, F[k]);
    const size_t p = add(sim, xi, 0.3 + 1.2 * rnd(), F[k]);
    if (k % 2) { /* every other one a quadrilateral, about its centroid */
      double cen[2];
      random_quad(0.05 + 0.1 * rnd(), before[k]);
      polygon(before[k], cen);
      for (int c = 0; c < 4; c++)
        for (int a = 0; a < 2; a++) before[k][c][a] -= cen[a];
      store_quad(sim, p, before[k]);
    }
  }
  double *corners = malloc(8 * sim->particles.n * sizeof(double)), reach;
  CHECK(mrn_cpdi2_begin(&sim->particles, g->inv_cell, corners, &reach) == 0);
  for (size_t p = 0; p < sim->particles.n; p++) mrn_cpdi2_offsets(&sim->particles, p, before[p]);
  mrn_transfer t = mrn_sim_transfer(sim);
  mrn_cpdi2_move_corners(&t, corners, dt);
  double worst = 0.0, worst1 = 0.0;
  double *a = calloc(3 * g->n, sizeof(double)), *b = calloc(3 * g->n, sizeof(double));
  const int ts = mrn_tensor_stride(2);
  for (size_t p = 0; p < sim->particles.n; p++) {
    double after[4][2];
    mrn_cpdi2_offsets(&sim->particles, p, after);
    for (int c = 0; c < 4; c++)
      for (int d = 0; d < 2; d++) {
        const double want = before[p][c][d] + dt * (L[d][0] * before[p][c][0] + L[d][1] * before[p][c][1]);
        worst = fmax(worst, fabs(after[c][d] - want) / g->cell);
      }
    if (p % 2) continue;
    double *Fp = sim->particles.F + (size_t)ts * p; /* F <- (I + dt L) F, the homogeneous deformation */
    for (int c = 0; c < 2; c++)
      for (int d = 0; d < 2; d++) Fp[2 * d + c] = F[p][2 * d + c] + dt * (L[d][0] * F[p][c] + L[d][1] * F[p][2 + c]);
    worst1 = fmax(worst1, against_cpdi1(sim, p, a, b));
  }
  printf("CPDI2 corners under an affine velocity: worst offset error %.2e cells; against CPDI1's (I + dt L) F "
         "%.2e\n", worst, worst1);
  CHECK(worst < TOL);
  CHECK(worst1 < TOL);
  free(a);
  free(b);
  free(corners);
  mrn_sim_free(sim);
}

int main(void) {
  for (int dim = 2; dim <= 3; dim++) {
    consistency(dim, 0);
    consistency(dim, 1);
    gimp(dim);
    kernels(dim);
    steps(dim, MRN_SHAPE_CPDI);
  }
  divergence_2d();
  gradient_bound();
  cpdi2_integrals();
  cpdi2_consistency();
  cpdi2_parallelogram();
  cpdi2_affine_update();
  steps(2, MRN_SHAPE_CPDI2);
  CHECK_DONE();
}
