/* moraine: particle splitting (solver/split.h) conserves, at each split,
 * mass, volume, linear momentum, angular momentum (the affine part
 * m D skew(C) too, D the constant inertia tensor of the B-splines) and
 * E_k + E_g + E_el to round-off: relative changes below 1e-12. The particles
 * are given a general state (F a rotated stretch, so the split axis is
 * oblique; velocity, affine matrix, stress, energies, history); each child
 * must hold the half of its parent's domain: F U0 of a child is
 * (I - n n^T / 2) F U0 of the parent, its centre at +-sigma n / 2. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "core/tensor.h"
#include "particles/sort.h"
#include "material/material.h"
#include "solver/simulation.h"
#include "solver/split.h"

#define BOUND 1e-12

static double rnd(unsigned *s) {
  *s = *s * 1103515245u + 12345u;
  return ((*s >> 8) & 0xffff) / 65535.0 - 0.5;
}

/* what the split must keep */
typedef struct totals {
  double mass, volume, p[3], L[3], La[3], energy, scale_p, scale_L;
} totals;

static totals sum_up(const mrn_sim *sim) {
  const mrn_particles *ps = &sim->particles;
  const int dim = sim->dim, ts = mrn_tensor_stride(dim);
  mrn_diagnostics d;
  mrn_sim_diagnostics(sim, &d);
  totals t = {.mass = d.mass, .energy = d.total};
  memcpy(t.p, d.momentum, sizeof t.p);
  memcpy(t.L, d.angular, sizeof t.L);
  for (size_t i = 0; i < ps->n; i++) {
    double C[9];
    mrn_tensor_expand(dim, ps->affine + (size_t)ts * i, 0.0, C);
    /* sum_i w m (x_i - x) x C (x_i - x) = m D eps : C^T for D = I */
    t.La[0] += ps->mass[i] * (C[7] - C[5]);
    t.La[1] += ps->mass[i] * (C[2] - C[6]);
    t.La[2] += ps->mass[i] * (C[3] - C[1]);
    t.volume += mrn_particle_volume(ps, i);
    double speed = 0.0, reach = 0.0;
    for (int a = 0; a < 3; a++) speed += ps->v[3 * i + a] * ps->v[3 * i + a], reach += ps->x[3 * i + a] * ps->x[3 * i + a];
    t.scale_p += ps->mass[i] * sqrt(speed);
    t.scale_L += ps->mass[i] * sqrt(speed * reach);
  }
  return t;
}

static int close_rel(double a, double b, double scale) { return fabs(a - b) <= BOUND * scale; }

/* a rotation by angle about axis z (2D) or the unit (1, 2, 2) / 3 (3D) */
static void rotation(int dim, double angle, double R[9]) {
  const double k[3] = {dim == 2 ? 0.0 : 1.0 / 3, dim == 2 ? 0.0 : 2.0 / 3, dim == 2 ? 1.0 : 2.0 / 3};
  const double c = cos(angle), s = sin(angle);
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      double cross = 0.0;
      if (a != b) {
        const int e = 3 - a - b; /* the third axis */
        cross = ((b - a + 3) % 3 == 1 ? -1.0 : 1.0) * k[e];
      }
      R[3 * a + b] = (a == b ? c : 0.0) + (1 - c) * k[a] * k[b] + s * cross;
    }
}

static mrn_sim *make(int dim, unsigned seed) {
  mrn_sim_config cfg = {.dim = dim, .origin = {0, 0, 0}, .size = {2, 2, 2}, .cell = 0.1,
                        .shape = MRN_SHAPE_QUADRATIC_BSPLINE, .gravity = {0.3, -9.81, dim == 3 ? 1.0 : 0.0}};
  mrn_sim *sim = mrn_sim_new(&cfg);
  mrn_material *m = mrn_material_new(&mrn_material_linear_elastic);
  mrn_material_set(m, "density", 2000);
  mrn_material_set(m, "E", 1e6);
  mrn_material_set(m, "nu", 0.3);
  mrn_material_prepare(m);
  const int mi = mrn_sim_add_material(sim, m);
  mrn_material_unref(m);
  mrn_particles *ps = &sim->particles;
  const int ts = mrn_tensor_stride(dim);
  const double h = 0.05, vol = pow(h, dim);
  for (int k = 0; k < 40; k++) {
    double x[3] = {0.6 + 0.7 * (rnd(&seed) + 0.5), 0.6 + 0.7 * (rnd(&seed) + 0.5), dim == 3 ? 1.0 + rnd(&seed) : 0.0};
    const long p = mrn_particles_add(ps, x, 2000 * vol * (1 + 0.2 * rnd(&seed)), vol, mi);
    double R[9], S[9] = {3.0 + rnd(&seed), 0, 0, 0, 0.8, 0, 0, 0, dim == 3 ? 1.1 : 1.0}, F[9], C[9];
    rotation(dim, 6.0 * rnd(&seed), R);
    mat_mul(R, S, F);
    for (int a = 0; a < 9; a++) C[a] = 10.0 * rnd(&seed);
    mrn_tensor_pack(dim, F, ps->F + (size_t)ts * p);
    mrn_tensor_pack(dim, C, ps->affine + (size_t)ts * p);
    for (int a = 0; a < dim; a++) ps->v[3 * p + a] = 4.0 * rnd(&seed), ps->x0[3 * p + a] -= 0.1 * rnd(&seed);
    for (int a = 0; a < 6; a++) ps->stress[6 * p + a] = 1e4 * rnd(&seed), ps->strain[6 * p + a] = 0.1 * rnd(&seed);
    ps->e_elastic[p] = 3.0 * (rnd(&seed) + 0.5);
    ps->w_plastic[p] = -(rnd(&seed) + 0.5);
  }
  mrn_sim_particles_changed(sim);
  return sim;
}

/* the current domain F U0 of particle i (dim x dim block of 3 x 3) */
static void current_domain(const mrn_sim *sim, size_t i, double A[9]) {
  const mrn_particles *ps = &sim->particles;
  const mrn_user_field *u = mrn_particles_user_field(ps, MRN_SPLIT_DOMAIN_FIELD);
  double F[9];
  mrn_tensor_expand(sim->dim, ps->F + (size_t)mrn_tensor_stride(sim->dim) * i, 1.0, F);
  mat_mul(F, ps->user + i * ps->user_stride + u->offset, A);
}

static void check_dim(int dim) {
  mrn_sim *sim = make(dim, 7u + (unsigned)dim);
  mrn_particles *ps = &sim->particles;
  const size_t n = ps->n;
  CHECK(mrn_sim_set_split(sim, 2.0, 2) == MRN_OK);
  CHECK(mrn_sim_set_split(sim, 0.5, 2) != MRN_OK); /* a stretch must be above 1 */
  double stretch0[64], x[64][3];
  for (size_t i = 0; i < n; i++) {
    stretch0[i] = mrn_split_stretch(sim, i);
    memcpy(x[i], ps->x + 3 * i, sizeof x[i]);
  }
  const totals before = sum_up(sim);
  CHECK(mrn_sim_split(sim) == (long)n); /* every particle stretched 2.5 to 3.5 times */
  CHECK(ps->n == 2 * n && sim->split_count == (long)n);
  const totals after = sum_up(sim);
  CHECK(close_rel(after.mass, before.mass, before.mass));
  CHECK(close_rel(after.volume, before.volume, before.volume));
  CHECK(close_rel(after.energy, before.energy, fabs(before.energy)));
  for (int a = 0; a < 3; a++) {
    CHECK(close_rel(after.p[a], before.p[a], before.scale_p));
    CHECK(close_rel(after.L[a], before.L[a], before.scale_L));
    CHECK(close_rel(after.La[a], before.La[a], fabs(before.La[a]) + 1e-300));
  }
  for (size_t i = 0; i < n; i++) {
    const size_t j = n + i;
    double A[9], B[9], d = 0.0, c = 0.0;
    current_domain(sim, i, A);
    current_domain(sim, j, B);
    for (int a = 0; a < 9; a++) d += fabs(A[a] - B[a]); /* the two halves alike */
    for (int a = 0; a < 3; a++) c += fabs(0.5 * (ps->x[3 * i + a] + ps->x[3 * j + a]) - x[i][a]);
    CHECK(d == 0.0 && c < 1e-14);
    /* the largest half-axis halved: the stretch now max(s / 2, 0.8) */
    CHECK_CLOSE(mrn_split_stretch(sim, i), fmax(0.5 * stretch0[i], 0.8), 1e-12);
    CHECK(ps->id[j] != ps->id[i] && ps->material[j] == ps->material[i]);
  }
  /* stretched 1.25 to 1.75: none is due at 2; at 1.2 each splits once more, then max_level 2 */
  CHECK(mrn_sim_split(sim) == 0);
  CHECK(mrn_sim_set_split(sim, 1.2, 2) == MRN_OK);
  const totals before2 = sum_up(sim);
  CHECK(mrn_sim_split(sim) == (long)(2 * n));
  CHECK(mrn_sim_split(sim) == 0);
  const totals after2 = sum_up(sim);
  CHECK(close_rel(after2.energy, before2.energy, fabs(before2.energy)));
  CHECK(close_rel(after2.mass, before.mass, before.mass));
  mrn_sim_free(sim);
}

/* The second children take their ids from next_id on in the order of
 * their parents' ids, wherever the parents sit in the arrays (solver/split.h):
 * with the particles in reverse order the child of the parent of id q is
 * appended as the q-th and takes id n + q (the ids were 1 .. n). */
static void check_ids(int dim) {
  mrn_sim *sim = make(dim, 11u);
  mrn_particles *ps = &sim->particles;
  const size_t n = ps->n;
  uint32_t order[64];
  for (size_t i = 0; i < n; i++) order[i] = (uint32_t)(n - 1 - i);
  CHECK(mrn_particles_permute(ps, order) == MRN_OK);
  CHECK(ps->id[0] == (int64_t)n && ps->next_id == (int64_t)n + 1);
  CHECK(mrn_sim_set_split(sim, 2.0, 2) == MRN_OK);
  CHECK(mrn_sim_split(sim) == (long)n);
  for (size_t k = 0; k < n; k++) {
    const size_t parent = n - 1 - k; /* the particle of id k + 1 */
    CHECK(ps->id[parent] == (int64_t)k + 1 && ps->id[n + k] == (int64_t)(n + k + 1));
    CHECK(ps->mass[n + k] == ps->mass[parent]); /* the halves of that parent */
  }
  CHECK(ps->next_id == (int64_t)(2 * n) + 1);
  mrn_sim_free(sim);
}

int main(void) {
  check_dim(2);
  check_dim(3);
  check_ids(2);
  check_ids(3);
  CHECK_DONE();
}
