/* moraine: what the unit tests of the domain-tracking shapes (CPDI, CPDI2,
 * cpGIMP: test_cpdi.c, test_cpgimp.c) share: a small simulation, particles
 * placed by grid coordinates, and the checks of their kernels against the
 * reference stencil and of whole steps. Include after check.h, with the
 * file's own TOL and a seed `domain_seed` it may reset. */
#ifndef MRN_TESTS_DOMAIN_SHAPES_H
#define MRN_TESTS_DOMAIN_SHAPES_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/tensor.h"
#include "material/material.h"
#include "solver/simulation.h"
#include "transfer/kernels.h"
#include "transfer/reference.h"

static unsigned domain_seed = 12345u;
static double rnd(void) { /* in [0, 1) */
  domain_seed = domain_seed * 1103515245u + 12345u;
  return ((domain_seed >> 8) & 0xffffff) / 16777216.0;
}

static mrn_sim *make_sim(int dim, mrn_shape_kind shape) {
  mrn_sim_config cfg = {.dim = dim, .origin = {-0.3, 0.7, 1.1}, .size = {1.6, 1.6, 1.6}, .cell = 0.1, .shape = shape};
  mrn_sim *sim = mrn_sim_new(&cfg);
  CHECK(sim != NULL);
  return sim;
}

/* an elastic material (rho 1000, E 1e5, nu 0.3) for every particle */
static void add_elastic(mrn_sim *sim) {
  mrn_material *m = mrn_material_new(&mrn_material_linear_elastic);
  mrn_material_set(m, "density", 1000);
  mrn_material_set(m, "E", 1e5);
  mrn_material_set(m, "nu", 0.3);
  mrn_material_prepare(m);
  CHECK(mrn_sim_add_material(sim, m) == 0);
  mrn_material_unref(m);
}

/* a particle at grid coordinates xi with side `side` cells and deformation
 * F (dim x dim stored; NULL: I), a random velocity and stress */
static size_t add(mrn_sim *sim, const double xi[3], double side, const double *F) {
  const mrn_grid *g = &sim->grid;
  double x[3] = {0, 0, 0};
  for (int d = 0; d < sim->dim; d++) x[d] = g->origin[d] + xi[d] * g->cell;
  const double s = side * g->cell, vol = sim->dim == 2 ? s * s : s * s * s;
  const long p = mrn_particles_add(&sim->particles, x, 1e3 * vol, vol, 0);
  CHECK(p >= 0);
  const int ts = mrn_tensor_stride(sim->dim);
  if (F) memcpy(sim->particles.F + (size_t)ts * (size_t)p, F, (size_t)ts * sizeof(double));
  for (int d = 0; d < 3; d++) sim->particles.v[3 * p + d] = rnd() - 0.5;
  for (int k = 0; k < 6; k++) sim->particles.stress[6 * p + k] = 1e3 * (rnd() - 0.5);
  return (size_t)p;
}

/* the largest departure of a stencil from the partition of unity, from
 * gradients summing to zero (times the cell h), from linear reproduction
 * sum S (x_i - x_p) = 0 (over h) and from sum (x_i - x_p) (x) grad S = I */
static double consistency_error(const mrn_ref_stencil *s, int dim, double h) {
  double sum = 0.0, gsum[3] = {0, 0, 0}, xs[3] = {0, 0, 0}, G[3][3] = {{0}}, worst;
  for (int c = 0; c < s->count; c++) {
    sum += s->N[c];
    for (int a = 0; a < dim; a++) {
      gsum[a] += s->dN[dim * c + a];
      xs[a] += s->N[c] * s->off[dim * c + a];
      for (int b = 0; b < dim; b++) G[a][b] += s->off[dim * c + a] * s->dN[dim * c + b];
    }
  }
  worst = fabs(sum - 1.0);
  for (int a = 0; a < dim; a++) {
    worst = fmax(worst, fabs(gsum[a]) * h);
    worst = fmax(worst, fabs(xs[a]) / h);
    for (int b = 0; b < dim; b++) worst = fmax(worst, fabs(G[a][b] - (a == b)));
  }
  return worst;
}

/* P2G through the kernels gives the reference's nodal values bit for bit,
 * conserves mass and momentum, and the internal forces sum to zero */
static void p2g_against_reference(mrn_sim *sim, const mrn_transfer *tr) {
  mrn_transfer t = *tr;
  const mrn_grid *g = &sim->grid;
  const int dim = sim->dim;
  mrn_p2g(&t, 1, 1);
  const size_t n = g->n;
  double *fast = malloc(7 * n * sizeof(double));
  CHECK(fast != NULL);
  memcpy(fast, g->mass, n * sizeof(double));
  memcpy(fast + n, g->mom, 3 * n * sizeof(double));
  memcpy(fast + 4 * n, g->force, 3 * n * sizeof(double));
  mrn_ref_p2g(&t, 1, 1);
  CHECK(memcmp(fast, g->mass, n * sizeof(double)) == 0);
  CHECK(memcmp(fast + n, g->mom, 3 * n * sizeof(double)) == 0);
  CHECK(memcmp(fast + 4 * n, g->force, 3 * n * sizeof(double)) == 0);
  double m = 0.0, mp = 0.0, P[3] = {0, 0, 0}, Pp[3] = {0, 0, 0}, f[3] = {0, 0, 0}, fs = 0.0;
  for (size_t i = 0; i < n; i++) {
    m += g->mass[i];
    for (int d = 0; d < 3; d++) P[d] += g->mom[3 * i + d], f[d] += g->force[3 * i + d], fs += fabs(g->force[3 * i + d]);
  }
  for (size_t p = 0; p < sim->particles.n; p++) {
    mp += sim->particles.mass[p];
    for (int d = 0; d < dim; d++) Pp[d] += sim->particles.mass[p] * sim->particles.v[3 * p + d];
  }
  CHECK_CLOSE(m, mp, TOL);
  for (int d = 0; d < dim; d++) {
    CHECK(fabs(P[d] - Pp[d]) <= TOL * mp);
    CHECK(fabs(f[d]) <= TOL * fs);
  }
  free(fast);
}

/* the largest change of the total momentum over five steps of 1e-4 s,
 * relative to sum m |v| (the particles placed, no gravity) */
static double momentum_drift(mrn_sim *sim) {
  for (int d = 0; d < 3; d++) sim->gravity[d] = 0.0;
  mrn_sim_particles_changed(sim);
  mrn_diagnostics d0, d1;
  mrn_sim_diagnostics(sim, &d0);
  double scale = 0.0, worst = 0.0;
  for (size_t p = 0; p < sim->particles.n; p++)
    scale += sim->particles.mass[p] * sqrt(pow(sim->particles.v[3 * p], 2) + pow(sim->particles.v[3 * p + 1], 2) +
                                           pow(sim->particles.v[3 * p + 2], 2));
  for (int s = 0; s < 5; s++) CHECK(mrn_sim_step_dt(sim, 1e-4) == 0);
  mrn_sim_diagnostics(sim, &d1);
  for (int a = 0; a < sim->dim; a++) worst = fmax(worst, fabs(d1.momentum[a] - d0.momentum[a]) / scale);
  return worst;
}

#endif
