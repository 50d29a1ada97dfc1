/* moraine: Hencky and Neo-Hookean hyperelasticity, and what rigid rotations
 * do to them and to the small-strain model with the Jaumann rate. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "core/tensor.h"
#include "material/driver.h"
#include "material/elastoplastic.h"
#include "material/material.h"

static const double PI = 3.14159265358979323846;
static const double E = 1e7, NU = 0.3;

static mrn_material *make(const mrn_material_type *type) {
  mrn_material *m = mrn_material_new(type);
  CHECK(mrn_material_set(m, "density", 1000) == MRN_OK);
  CHECK(mrn_material_set(m, "E", E) == MRN_OK);
  CHECK(mrn_material_set(m, "nu", NU) == MRN_OK);
  CHECK(mrn_material_prepare(m) == MRN_OK);
  return m;
}

/* the stress of a hyperelastic model at F, straight from its update */
static void stress_at(const mrn_material *m, const double F[9], double s[6]) {
  double state[4] = {0};
  mrn_material_point pt;
  memset(&pt, 0, sizeof pt);
  pt.F = F;
  pt.J = mat_det(F);
  pt.J_old = 1.0;
  pt.dt = 1.0;
  pt.state = state;
  m->type->update(m, &pt, 1);
  memcpy(s, pt.stress, sizeof pt.stress);
}

/* rotation by angle t about the unit axis n (Rodrigues) */
static void rotation(const double n_in[3], double t, double R[9]) {
  double l = sqrt(n_in[0] * n_in[0] + n_in[1] * n_in[1] + n_in[2] * n_in[2]);
  double n[3] = {n_in[0] / l, n_in[1] / l, n_in[2] / l}, c = cos(t), s = sin(t);
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) R[3 * a + b] = (a == b ? c : 0.0) + (1 - c) * n[a] * n[b];
  R[1] -= s * n[2];
  R[2] += s * n[1];
  R[3] += s * n[2];
  R[5] -= s * n[0];
  R[6] -= s * n[1];
  R[7] += s * n[0];
}

static double max_abs(const double s[6]) {
  double v = 0;
  for (int k = 0; k < 6; k++) v = fmax(v, fabs(s[k]));
  return v;
}

/* ---- stress from F ------------------------------------------------------ */

static void test_closed_forms(const mrn_material *m, int hencky) {
  double lambda, G, K;
  mrn_lame(E, NU, &lambda, &G, &K);
  /* F = R: no stress, for a quarter turn and for any rotation */
  const double z[3] = {0, 0, 1}, n[3] = {1, 2, 3};
  double R[9], s[6];
  rotation(z, PI / 2, R);
  stress_at(m, R, s);
  CHECK(max_abs(s) <= 1e-8 * E);
  printf("  %s: F = R(90 deg) gives |sigma| / E = %.3g\n", m->type->name, max_abs(s) / E);
  rotation(n, 2.2, R);
  stress_at(m, R, s);
  CHECK(max_abs(s) <= 1e-8 * E);

  /* principal stretches: the closed forms */
  const double l[3] = {1.3, 0.8, 1.05};
  const double F[9] = {l[0], 0, 0, 0, l[1], 0, 0, 0, l[2]};
  double J = l[0] * l[1] * l[2];
  stress_at(m, F, s);
  for (int i = 0; i < 3; i++) {
    double expect = hencky ? (lambda * log(J) + 2 * G * log(l[i])) / J
                           : G / J * (l[i] * l[i] - 1) + lambda * log(J) / J;
    CHECK_CLOSE(s[i] / E, expect / E, 1e-13);
  }
  CHECK(fabs(s[SXY]) + fabs(s[SYZ]) + fabs(s[SXZ]) <= 1e-13 * E);

  /* objectivity: sigma(R F) = R sigma(F) R^T, for a general F */
  const double F0[9] = {1.2, 0.3, -0.1, 0.05, 0.9, 0.2, -0.15, 0.1, 1.1};
  double RF[9], s0[6], s1[6], S0[9], RS[9], RSRt[9], Rt[9];
  rotation(n, 0.7, R);
  mat_mul(R, F0, RF);
  stress_at(m, F0, s0);
  stress_at(m, RF, s1);
  sym_to_mat(s0, S0);
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) Rt[3 * a + b] = R[3 * b + a];
  mat_mul(R, S0, RS);
  mat_mul(RS, Rt, RSRt);
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) CHECK(fabs(s1[sym_index(a, b)] - RSRt[3 * a + b]) <= 1e-12 * E);

  /* small strains: Hooke's law */
  const double e = 1e-7, Fs[9] = {1 + e, 0.5 * e, 0, 0.5 * e, 1 - 2 * e, 0, 0, 0, 1};
  double de[6] = {e, -2 * e, 0, 0.5 * e, 0, 0}, ds[6];
  stress_at(m, Fs, s);
  mrn_hooke_increment(lambda, G, de, ds);
  for (int k = 0; k < 6; k++) CHECK(fabs(s[k] - ds[k]) <= 1e-5 * E * e);
}

/* Along a loading-unloading path the energy increments sum to the stored
 * energy psi(F) (the step's bookkeeping), no work is called plastic, and the
 * energy is back to zero when F is. */
static void test_energy(const mrn_material *m) {
  mrn_driver d;
  mrn_driver_init(&d, m, NULL);
  const double L1[9] = {0.4, 0.3, 0, 0, -0.2, 0, 0, 0.1, 0.1};
  for (int i = 0; i < 100; i++) {
    CHECK(mrn_driver_step(&d, L1, 0.01) == MRN_OK);
    CHECK(d.dw_plastic == 0.0);
  }
  double peak = d.e_elastic;
  CHECK(peak > 0);
  CHECK_CLOSE(d.e_elastic / d.state[0], 1.0, 1e-12);
  /* back along the same path: F returns to I up to O(dt) terms */
  double Linv[9];
  for (int k = 0; k < 9; k++) Linv[k] = -L1[k];
  for (int i = 0; i < 100; i++) CHECK(mrn_driver_step(&d, Linv, 0.01) == MRN_OK);
  CHECK_CLOSE(d.e_elastic / d.state[0], 1.0, 1e-10);
  CHECK(d.e_elastic < 1e-3 * peak);
}

/* ---- rigid rotation through the step's kinematics ----------------------- */

/* 90 degrees about z in N steps of the spin L = W (omega dt = pi / (2 N)).
 * Returns the final stress. */
static void spin(const mrn_material *m, int N, int kinematics, const double s0[6], double out[6]) {
  mrn_driver d;
  mrn_driver_init(&d, m, s0);
  d.kinematics = kinematics;
  double w = PI / 2 / N;
  const double L[9] = {0, -w, 0, w, 0, 0, 0, 0, 0};
  for (int i = 0; i < N; i++) CHECK(mrn_driver_step(&d, L, 1.0) == MRN_OK);
  memcpy(out, d.stress, sizeof d.stress);
}

static void test_rotation(void) {
  mrn_material *le = make(&mrn_material_linear_elastic);
  mrn_material *he = make(&mrn_material_hencky);
  mrn_material *nh = make(&mrn_material_neo_hookean);
  double lambda, G, K, s[6];
  mrn_lame(E, NU, &lambda, &G, &K);
  const double zero[6] = {0};
  for (int N = 100; N <= 1000; N *= 10) {
    /* small strain + Jaumann: dstrain = sym(W) dt = 0, nothing happens */
    spin(le, N, MRN_DRIVER_F_EULER, zero, s);
    CHECK(max_abs(s) == 0.0);

    /* hyperelastic, F <- (I + W dt) F as the explicit step does: each step
     * stretches the rotation plane by sqrt(1 + (omega dt)^2), so the block
     * ends up dilated by l = (1 + (pi / 2N)^2)^(N/2) in x and y */
    double lnl = 0.5 * N * log1p(pow(PI / 2 / N, 2)), J = exp(2 * lnl);
    spin(he, N, MRN_DRIVER_F_EULER, zero, s);
    CHECK_CLOSE(s[SXX] / E, (2 * lambda + 2 * G) * lnl / J / E, 1e-10);
    CHECK_CLOSE(s[SZZ] / E, 2 * lambda * lnl / J / E, 1e-10);
    printf("  90 deg in %d steps, F <- (I + L dt) F: J - 1 = %.4g, Hencky sigma_xx = %.4g E, ", N, J - 1, s[SXX] / E);
    spin(nh, N, MRN_DRIVER_F_EULER, zero, s);
    CHECK_CLOSE(s[SXX] / E, (G / J * (J - 1) + lambda * log(J) / J) / E, 1e-10);
    printf("Neo-Hookean sigma_xx = %.4g E\n", s[SXX] / E);

    /* the mid-point increment is orthogonal for a spin: no stress at all */
    spin(he, N, MRN_DRIVER_F_MIDPOINT, zero, s);
    CHECK(max_abs(s) <= 1e-8 * E);
    spin(nh, N, MRN_DRIVER_F_MIDPOINT, zero, s);
    CHECK(max_abs(s) <= 1e-8 * E);
    printf("  90 deg in %d steps, mid-point F: |sigma| <= %.3g E\n", N, max_abs(s) / E);

    /* a pre-stressed block, sigma_xx = s0: the explicit Jaumann update
     * multiplies the in-plane deviator a + i b = (sxx - syy) / 2 + i sxy by
     * (1 + 2 i omega dt) per step, so it grows by (1 + (pi / N)^2)^(N/2)
     * instead of only turning by 180 degrees */
    const double s0 = 1e-3 * E, pre[6] = {s0, 0, 0, 0, 0, 0};
    spin(le, N, MRN_DRIVER_F_EULER, pre, s);
    double mag = pow(1 + pow(PI / N, 2), 0.5 * N), ang = N * atan(PI / N);
    CHECK_CLOSE(s[SXX] / s0, 0.5 + 0.5 * mag * cos(ang), 1e-10);
    CHECK_CLOSE(s[SYY] / s0, 0.5 - 0.5 * mag * cos(ang), 1e-10);
    CHECK_CLOSE(s[SXY] / s0, 0.5 * mag * sin(ang), 1e-10);
    double err[6] = {s[SXX], s[SYY] - s0, s[SZZ], s[SXY], s[SYZ], s[SXZ]};
    printf("  90 deg in %d steps, linear_elastic pre-stressed s0: |sigma - R s0 R^T| = %.4g s0\n", N,
           max_abs(err) / s0);
  }
  mrn_material_unref(le);
  mrn_material_unref(he);
  mrn_material_unref(nh);
}

int main(void) {
  mrn_material *he = make(&mrn_material_hencky), *nh = make(&mrn_material_neo_hookean);
  test_closed_forms(he, 1);
  test_closed_forms(nh, 0);
  test_energy(he);
  test_energy(nh);
  CHECK(he->type->rate_form == 0 && nh->type->rate_form == 0);
  CHECK(strcmp(he->type->state_names[0], "psi") == 0);
  mrn_material_unref(he);
  mrn_material_unref(nh);
  test_rotation();
  CHECK_DONE();
}
