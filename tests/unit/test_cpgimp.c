/* moraine: the cpGIMP stencil (transfer/cpgimp.h), 2D and 3D.
 * - F = I: the stencil is uGIMP's bit for bit (nodes, values, gradients,
 *   branch vectors) at random positions, formed from F or from the domains
 *   the step freezes.
 * - Partition of unity, gradients summing to zero, linear reproduction
 *   (sum S x_i = x_p, sum x_i (x) grad S = I) for boxes stretched and
 *   compressed along the axes (half-widths 0.05 to 3 cells), at random
 *   positions: 1e-12.
 * - The 1D weights against a numerical convolution of the hat function with
 *   the box (midpoint rule, 2e5 points, blind to the kinks: 1e-8), zero on
 *   the nodes beyond the ones listed; the derivatives against central
 * *   differences of the weights (1e-5: their second derivative jumps).
 * - The kernels route cpGIMP through the reference stencil: P2G gives the
 *   reference's nodal values bit for bit, conserves mass and momentum, the
 *   internal forces sum to zero; a box stretched far beyond the grid keeps
 *   the partition of unity and its nodes inside the padded grid.
 * - Whole explicit steps (PIC, FLIP, APIC, TPIC x USF, USL, MUSL, USAVG):
 *   total momentum to 1e-12 of sum m |v|.
 * - The step refuses a box turned over (F_xx < 0) and one wider than a
 *   stencil holds, naming the particle. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "core/tensor.h"
#include "material/material.h"
#include "particles/domain.h"
#include "solver/simulation.h"
#include "transfer/cpgimp.h"
#include "transfer/kernels.h"
#include "transfer/reference.h"

#define TOL 1e-12

#include "domain_shapes.h"

/* an F stretched or compressed along the axes (0.2 to 3) with a little shear */
static void axis_F(int dim, double shear, double *F) {
  for (int a = 0; a < dim; a++)
    for (int b = 0; b < dim; b++) F[dim * a + b] = a == b ? 0.2 + 2.8 * rnd() : shear * (rnd() - 0.5);
}

static int same_stencil(const mrn_ref_stencil *a, const mrn_ref_stencil *b, int dim) {
  const size_t n = (size_t)a->count;
  return a->count == b->count && memcmp(a->node, b->node, n * sizeof(size_t)) == 0 &&
         memcmp(a->N, b->N, n * sizeof(double)) == 0 && memcmp(a->dN, b->dN, dim * n * sizeof(double)) == 0 &&
         memcmp(a->off, b->off, dim * n * sizeof(double)) == 0;
}

/* F = I: uGIMP's stencil, bit for bit */
static void ugimp(int dim) {
  mrn_sim *sim = make_sim(dim, MRN_SHAPE_CPGIMP);
  for (int k = 0; k < 400; k++) {
    double xi[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) xi[d] = 16.0 * rnd();
    add(sim, xi, 0.05 + 0.95 * rnd(), NULL); /* half-widths up to 1/2 cell, uGIMP's range */
  }
  double *A = malloc(9 * sim->particles.n * sizeof(double)), extent = 0.0;
  CHECK(mrn_cpgimp_domains(&sim->particles, dim, sim->grid.inv_cell, A, &extent) == -1);
  CHECK(extent <= 0.5);
  mrn_transfer t = mrn_sim_transfer(sim), frozen = t, gimp = t;
  frozen.domain = A;
  gimp.kernel.shape = MRN_SHAPE_GIMP;
  int same = 1;
  for (size_t p = 0; p < sim->particles.n; p++) {
    mrn_ref_stencil s, f, u;
    mrn_ref_stencil_build(&t, p, &s);
    mrn_ref_stencil_build(&frozen, p, &f);
    mrn_ref_stencil_build(&gimp, p, &u);
    same &= same_stencil(&s, &u, dim) && same_stencil(&f, &u, dim);
  }
  printf("%dD F = I: %zu stencils, uGIMP's bit for bit: %s\n", dim, sim->particles.n, same ? "yes" : "no");
  CHECK(same);
  free(A);
  mrn_sim_free(sim);
}

static void consistency(int dim, double shear) {
  mrn_sim *sim = make_sim(dim, MRN_SHAPE_CPGIMP);
  for (int k = 0; k < 200; k++) {
    double xi[3] = {0, 0, 0}, F[9];
    for (int d = 0; d < dim; d++) xi[d] = 5.0 + 6.0 * rnd();
    axis_F(dim, shear, F);
    add(sim, xi, 0.25 + 0.75 * rnd(), F);
  }
  mrn_transfer t = mrn_sim_transfer(sim);
  mrn_ref_stencil s;
  double worst = 0.0, widest = 0.0, narrowest = INFINITY;
  for (size_t p = 0; p < sim->particles.n; p++) {
    mrn_ref_stencil_build(&t, p, &s);
    worst = fmax(worst, consistency_error(&s, dim, sim->grid.cell));
    double A[9], U0[9], l[3];
    mrn_particle_domain(&sim->particles, dim, p, -1, mrn_particle_half_side(sim->particles.vol0[p], dim), U0, A);
    CHECK(mrn_cpgimp_box(A, dim, sim->grid.inv_cell, l) == s.count);
    for (int d = 0; d < dim; d++) widest = fmax(widest, l[d]), narrowest = fmin(narrowest, l[d]);
  }
  printf("%dD boxes of half-width %.3f to %.3f cells (shear %.1f): worst partition of unity / gradient sum / "
         "linear reproduction error %.2e\n", dim, narrowest, widest, shear, worst);
  CHECK(widest > 1.0 && narrowest < 0.1); /* both sides of uGIMP's form */
  CHECK(worst < TOL);
  mrn_sim_free(sim);
}

/* the 1D weights against the convolution of the hat with the box, by a
 * midpoint rule that knows nothing of the kinks */
static void one_d(void) {
  const int M = 200000;
  double worst_w = 0.0, worst_dw = 0.0;
  for (int k = 0; k < 200; k++) {
    const double l = k < 10 ? 0.5 : 0.05 + 2.95 * rnd(), xi = 3.0 + 4.0 * rnd();
    double w[MRN_REF_STENCIL_MAX], dw[MRN_REF_STENCIL_MAX], wp[MRN_REF_STENCIL_MAX], wm[MRN_REF_STENCIL_MAX],
        scratch[MRN_REF_STENCIL_MAX];
    const int base = mrn_cpgimp_1d(xi, l, w, dw), n = mrn_cpgimp_nodes(l);
    const double e = 1e-7;
    CHECK(mrn_cpgimp_1d(xi + e, l, wp, scratch) == base && mrn_cpgimp_1d(xi - e, l, wm, scratch) == base);
    for (int j = -1; j <= n; j++) { /* one node beyond each end: zero */
      double sum = 0.0;
      for (int q = 0; q < M; q++) {
        const double s = xi - l + (q + 0.5) * (2.0 * l / M) - (base + j);
        sum += fmax(0.0, 1.0 - fabs(s));
      }
      const double conv = sum / M, mine = j >= 0 && j < n ? w[j] : 0.0;
      worst_w = fmax(worst_w, fabs(mine - conv));
      if (j >= 0 && j < n) worst_dw = fmax(worst_dw, fabs(dw[j] - (wp[j] - wm[j]) / (2.0 * e)));
    }
  }
  printf("1D weights against the numerical convolution: worst %.2e; derivatives against differences: worst %.2e\n",
         worst_w, worst_dw);
  CHECK(worst_w < 1e-8);
  CHECK(worst_dw < 1e-5);
}

/* P2G through the kernels: the reference's nodal values bit for bit, mass
 * and momentum conserved, internal forces summing to zero; then a box far
 * wider than the ghost layers by a face */
static void kernels(int dim) {
  mrn_sim *sim = make_sim(dim, MRN_SHAPE_CPGIMP);
  for (int k = 0; k < 300; k++) {
    double xi[3] = {0, 0, 0}, F[9];
    for (int d = 0; d < dim; d++) xi[d] = 3.0 + 10.0 * rnd();
    axis_F(dim, 0.3, F);
    add(sim, xi, 0.3 + 0.7 * rnd(), F);
  }
  mrn_sim_particles_changed(sim);
  mrn_grid *g = &sim->grid;
  mrn_transfer t = mrn_sim_transfer(sim);
  p2g_against_reference(sim, &t);
  /* by the lower x face, a box 6 cells wide along x: 4 beyond the ghost layers */
  const double xi[3] = {0.5, 8, 8}, F[9] = {6, 0, 0, 0, 1, 0, 0, 0, 1}, F2[4] = {6, 0, 0, 1};
  const size_t p = add(sim, xi, 1.0, dim == 2 ? F2 : F);
  mrn_ref_stencil s;
  mrn_ref_stencil_build(&t, p, &s);
  double sum = 0.0, gsum = 0.0;
  for (int c = 0; c < s.count; c++) {
    sum += s.N[c], gsum += s.dN[dim * c];
    CHECK(s.node[c] < g->n);
  }
  CHECK(s.count > 14);
  CHECK_CLOSE(sum, 1.0, TOL);
  CHECK(fabs(gsum) * g->cell < TOL);
  mrn_sim_free(sim);
}

static mrn_sim *elastic_sim(int dim) {
  mrn_sim *sim = make_sim(dim, MRN_SHAPE_CPGIMP);
  add_elastic(sim);
  return sim;
}

/* total momentum through steps of each strategy and stress update */
static void steps(int dim) {
  static const char *const presets[] = {"PIC", "FLIP", "APIC", "TPIC"};
  double worst = 0.0;
  for (int k = 0; k < 4; k++)
    for (int u = MRN_STRESS_USF; u <= MRN_STRESS_USAVG; u++) {
      mrn_sim *sim = elastic_sim(dim);
      CHECK(mrn_scheme_from_preset(presets[k], &sim->scheme) == 0);
      sim->scheme.stress_update = (mrn_stress_update_kind)u;
      for (int p = 0; p < 60; p++) {
        double xi[3] = {0, 0, 0}, F[9];
        for (int d = 0; d < dim; d++) xi[d] = 5.0 + 6.0 * rnd();
        axis_F(dim, 0.3, F);
        add(sim, xi, 0.5, F);
      }
      worst = fmax(worst, momentum_drift(sim));
      mrn_sim_free(sim);
    }
  printf("%dD steps, every strategy and stress update: worst momentum change %.2e of sum m |v|\n", dim, worst);
  CHECK(worst < TOL);
}

/* the step refuses a box turned over and one wider than a stencil holds */
static void refusals(int dim) {
  const double Fs[2][9] = {{-0.5, 0, 0, 0, 1, 0, 0, 0, 1}, {1, 0, 0, 0, 1, 0, 0, 0, 200}};
  char wide[64];
  snprintf(wide, sizeof wide, "more than the %d nodes", MRN_REF_STENCIL_MAX);
  const char *const says[2] = {"collapsed or turned over", wide};
  for (int k = 0; k < 2; k++) {
    mrn_sim *sim = elastic_sim(dim);
    const double xi[3] = {8, 8, 8};
    double F[9];
    for (int a = 0; a < dim; a++)
      for (int b = 0; b < dim; b++) F[dim * a + b] = Fs[k][3 * a + b] + (dim == 2 && a == 1 && b == 1 && k ? 199 : 0);
    add(sim, xi, 0.5, NULL);
    add(sim, xi, 0.5, F);
    mrn_sim_particles_changed(sim);
    mrn_error_clear();
    CHECK(mrn_sim_step_dt(sim, 1e-4) != 0);
    printf("%dD refused: %s\n", dim, mrn_error_message());
    CHECK(strstr(mrn_error_message(), says[k]) != NULL);
    CHECK(strstr(mrn_error_message(), "particle 2 at") != NULL); /* the second one added (ids from 1) */
    mrn_sim_free(sim);
  }
}

int main(void) {
  domain_seed = 4242u;
  one_d();
  for (int dim = 2; dim <= 3; dim++) {
    ugimp(dim);
    consistency(dim, 0.0);
    consistency(dim, 0.4);
    kernels(dim);
    steps(dim);
    refusals(dim);
  }
  CHECK_DONE();
}
