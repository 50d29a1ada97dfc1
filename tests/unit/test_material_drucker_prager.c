/* moraine: Drucker-Prager at a single material point, and its fits to
 * Mohr-Coulomb (002, Eqs. 71-74). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "core/tensor.h"
#include "material/driver.h"
#include "material/elastoplastic.h"
#include "material/material.h"

static const double DEG = 3.14159265358979323846 / 180.0;

static mrn_material *make(const mrn_material_type *type, double phi, double psi, double c, int match) {
  mrn_material *m = mrn_material_new(type);
  CHECK(mrn_material_set(m, "density", 1400) == MRN_OK);
  CHECK(mrn_material_set(m, "E", 1e7) == MRN_OK);
  CHECK(mrn_material_set(m, "nu", 0.3) == MRN_OK);
  CHECK(mrn_material_set(m, "phi", phi) == MRN_OK);
  CHECK(mrn_material_set(m, "psi", psi) == MRN_OK);
  CHECK(mrn_material_set(m, "cohesion", c) == MRN_OK);
  if (match >= 0) CHECK(mrn_material_set(m, "plane_strain_match", match) == MRN_OK);
  CHECK(mrn_material_prepare(m) == MRN_OK);
  return m;
}

/* the cone constants as prepare() derived them */
static void cone(const mrn_material *m, double *alpha, double *kappa, double *beta) {
  *alpha = m->derived[3];
  *kappa = m->derived[4];
  *beta = m->derived[5];
}

static double yield_dp(const mrn_material *m, const double s[6]) {
  double alpha, kappa, beta, dev[6];
  cone(m, &alpha, &kappa, &beta);
  sym_dev(s, dev);
  return sqrt(0.5 * sym_ddot(dev, dev)) + alpha * sym_trace(s) - kappa;
}

/* ---- plane-strain biaxial compression at fixed lateral stress ----------- */

/* Compress along y (D_yy < 0) with sigma_xx = -p0 held and D_zz = 0 until
 * the stress stops changing; returns the limit sigma_yy. Every step must
 * dissipate (or be elastic). For Drucker-Prager the out-of-plane stress
 * relaxes towards the collapse state exponentially, by e every ~2 % of
 * axial strain here, so the path is long: 40 % in steps of 1e-4. */
static double biaxial_limit(const mrn_material *m, double p0) {
  const double s0[6] = {-p0, -p0, -p0, 0, 0, 0};
  mrn_driver d;
  mrn_driver_init(&d, m, s0);
  double max_dw = -1;
  for (int i = 0; i < 4000; i++) {
    if (mrn_driver_biaxial(&d, -1.0, -p0, 1e-4) != MRN_OK) {
      CHECK(!"biaxial step failed");
      break;
    }
    max_dw = fmax(max_dw, d.dw_plastic);
  }
  CHECK(max_dw <= 0.0);
  CHECK(d.w_plastic < 0.0);
  CHECK(fabs(d.stress[SXX] + p0) <= 1e-10 * p0);
  return d.stress[SYY];
}

static void test_plane_strain_match(void) {
  const double p0 = 1e5;
  struct {
    double phi, psi, c;
    int match;
  } cases[] = {
      {30, 0, 1e4, 2},  /* the flow-consistent match, non-associated */
      {35, 0, 0, 2},    /* 002 §5.5's sand */
      {30, 30, 1e4, 1}, /* 002's Eq. 72 is exact for associated flow */
      {35, 35, 5e3, 1},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mrn_material *dp = make(&mrn_material_drucker_prager, cases[i].phi, cases[i].psi, cases[i].c, cases[i].match);
    mrn_material *mc = make(&mrn_material_mohr_coulomb, cases[i].phi, cases[i].psi, cases[i].c, -1);
    double s_dp = biaxial_limit(dp, p0), s_mc = biaxial_limit(mc, p0);
    /* Mohr-Coulomb's closed form, s3 = k s1 - sc with s1 = -p0 */
    double sp = sin(cases[i].phi * DEG), k = (1 + sp) / (1 - sp);
    double closed = -k * p0 - 2 * cases[i].c * cos(cases[i].phi * DEG) / (1 - sp);
    printf("  phi %g psi %g c %g match %d: DP / MC plane-strain strength = %.8f\n", cases[i].phi, cases[i].psi,
           cases[i].c, cases[i].match, s_dp / s_mc);
    CHECK_CLOSE(s_mc / closed, 1.0, 1e-10);
    CHECK(fabs(s_dp / s_mc - 1) < 1e-2);
    CHECK(fabs(s_dp / s_mc - 1) < 1e-6); /* in fact exact once the limit state is reached */
    mrn_material_unref(dp);
    mrn_material_unref(mc);
  }

  /* 002's match with psi = 0 (the sand column's choice) is not Mohr-Coulomb's
   * plane-strain strength: with beta = 0 the collapse has s_zz = 0 and
   * t = kappa - 3 alpha s_m, so sigma_yy = -(2 kappa + (1 + 3 alpha) p0) / (1 - 3 alpha) */
  mrn_material *dp = make(&mrn_material_drucker_prager, 35, 0, 0, 1);
  mrn_material *mc = make(&mrn_material_mohr_coulomb, 35, 0, 0, -1);
  double alpha, kappa, beta;
  cone(dp, &alpha, &kappa, &beta);
  double s_dp = biaxial_limit(dp, p0), s_mc = biaxial_limit(mc, p0);
  CHECK_CLOSE(s_dp / (-(2 * kappa + (1 + 3 * alpha) * p0) / (1 - 3 * alpha)), 1.0, 1e-6);
  printf("  phi 35 psi 0 match 1 (002 Eq. 72): DP / MC plane-strain strength = %.6f (deviator ratio %.6f)\n",
         s_dp / s_mc, (s_dp + p0) / (s_mc + p0));
  CHECK(s_dp / s_mc < 0.99); /* the 002 fit is weaker here; match = 2 fixes it */
  mrn_material_unref(dp);
  mrn_material_unref(mc);
}

/* match = 0 passes through Mohr-Coulomb's triaxial-compression corners */
static void test_triaxial_match(void) {
  const double phi = 30, c = 1e4, p0 = 1e5;
  mrn_material *dp = make(&mrn_material_drucker_prager, phi, 0, c, 0);
  const double s0[6] = {-p0, -p0, -p0, 0, 0, 0};
  mrn_driver d;
  mrn_driver_init(&d, dp, s0);
  double qmax = 0;
  for (int i = 0; i < 3000; i++) {
    CHECK(mrn_driver_triaxial(&d, -1.0, -p0, 1e-5) == MRN_OK);
    qmax = fmax(qmax, d.stress[SXX] - d.stress[SZZ]);
  }
  double sp = sin(phi * DEG), k = (1 + sp) / (1 - sp), sc = 2 * c * cos(phi * DEG) / (1 - sp);
  CHECK_CLOSE(qmax / ((k - 1) * p0 + sc), 1.0, 1e-8);
  mrn_material_unref(dp);
}

/* ---- returns on the cone and at the apex -------------------------------- */

static double urand(void) { return rand() / (double)RAND_MAX * 2.0 - 1.0; }

static void test_returns(double psi, int match) {
  const double E = 1e7, nu = 0.3, scale = 1e5;
  mrn_material *m = make(&mrn_material_drucker_prager, 30, psi, 2e4, match);
  double alpha, kappa, beta, lambda, G, K;
  cone(m, &alpha, &kappa, &beta);
  mrn_lame(E, nu, &lambda, &G, &K);
  int ncone = 0, napex = 0;
  double worst = 0, worst_dir = 0, min_diss = 1;
  srand(777);
  for (int t = 0; t < 20000; t++) {
    double s0[6], p = -scale * (0.05 + 0.95 * (urand() + 1) / 2);
    for (int k = 0; k < 6; k++) s0[k] = (k < 3 ? p : 0.0) + 0.05 * scale * urand();
    if (yield_dp(m, s0) > 0) continue;
    double L[9];
    for (int k = 0; k < 9; k++) L[k] = urand() * 3 * scale / E;
    for (int a = 0; a < 3; a++)
      for (int b = a + 1; b < 3; b++) L[3 * b + a] = L[3 * a + b];
    double de[6], ds[6], trial[6];
    mat_sym_part(L, 1.0, de);
    mrn_hooke_increment(lambda, G, de, ds);
    for (int k = 0; k < 6; k++) trial[k] = s0[k] + ds[k];
    if (yield_dp(m, trial) <= 0) continue;
    mrn_driver d;
    mrn_driver_init(&d, m, s0);
    CHECK(mrn_driver_step(&d, L, 1.0) == MRN_OK);
    worst = fmax(worst, fabs(yield_dp(m, d.stress)) / scale);
    double dev[6], devt[6];
    sym_dev(d.stress, dev);
    sym_dev(trial, devt);
    double rj2 = sqrt(0.5 * sym_ddot(dev, dev));
    if (rj2 <= 1e-10 * scale) {
      napex++;
      CHECK(fabs(sym_trace(d.stress) - kappa / alpha) <= 1e-10 * scale);
    } else {
      ncone++;
      /* the cone return is radial in the deviatoric plane */
      double rt = sqrt(0.5 * sym_ddot(devt, devt));
      for (int k = 0; k < 6; k++) worst_dir = fmax(worst_dir, fabs(dev[k] / rj2 - devt[k] / rt));
    }
    double dsig[6], dep_el[6], dep_p[6];
    for (int k = 0; k < 6; k++) dsig[k] = d.stress[k] - s0[k];
    mrn_hooke_compliance(E, nu, dsig, dep_el);
    for (int k = 0; k < 6; k++) dep_p[k] = de[k] - dep_el[k];
    min_diss = fmin(min_diss, sym_ddot(d.stress, dep_p) / (scale * scale / E));
  }
  printf("  DP psi %g match %d: %d cone and %d apex returns, worst |f| %.3g\n", psi, match, ncone, napex, worst);
  CHECK(ncone > 100);
  CHECK(napex > 100);
  CHECK(worst <= 1e-10);
  CHECK(worst_dir <= 1e-10);
  CHECK(min_diss >= -1e-12);
  mrn_material_unref(m);
}

/* ---- elastic unloading and parameters ----------------------------------- */

static void test_unloading(void) {
  const double p0 = 1e5, E = 1e7, nu = 0.3;
  mrn_material *m = make(&mrn_material_drucker_prager, 30, 10, 0, 1);
  const double s0[6] = {-p0, -p0, -p0, 0, 0, 0};
  mrn_driver d;
  mrn_driver_init(&d, m, s0);
  for (int i = 0; i < 3000; i++) CHECK(mrn_driver_triaxial(&d, -1.0, -p0, 1e-5) == MRN_OK);
  CHECK(d.state[0] > 0 && d.state[1] > 0); /* psi > 0 dilates */
  double eps_p = d.state[0], lambda, G, K;
  mrn_lame(E, nu, &lambda, &G, &K);
  for (int i = 0; i < 20; i++) {
    double old[6], strain_old[6], de[6], ds[6];
    memcpy(old, d.stress, sizeof old);
    memcpy(strain_old, d.strain, sizeof old);
    CHECK(mrn_driver_triaxial(&d, 1.0, -p0, 1e-5) == MRN_OK);
    for (int k = 0; k < 6; k++) de[k] = d.strain[k] - strain_old[k];
    mrn_hooke_increment(lambda, G, de, ds);
    for (int k = 0; k < 6; k++) CHECK(fabs(d.stress[k] - (old[k] + ds[k])) <= 1e-12 * p0);
    CHECK(d.dw_plastic == 0.0);
  }
  CHECK(d.state[0] == eps_p);
  mrn_material_unref(m);
}

static void test_parameters(void) {
  mrn_material *m = mrn_material_new(&mrn_material_drucker_prager);
  CHECK(mrn_material_set(m, "phi", 91) != MRN_OK);
  CHECK(mrn_material_set(m, "plane_strain_match", 3) != MRN_OK);
  mrn_material_set(m, "density", 1400);
  mrn_material_set(m, "E", 1e7);
  mrn_material_set(m, "phi", 35);
  CHECK(mrn_material_get(m, "plane_strain_match") == 1);
  CHECK(mrn_material_prepare(m) == MRN_OK);
  /* (002, Eq. 72) for phi = 35 deg, c = 0 */
  double t = tan(35 * DEG);
  CHECK_CLOSE(m->derived[3], t / sqrt(9 + 12 * t * t), 1e-15);
  CHECK(m->derived[4] == 0.0);
  mrn_material_set(m, "plane_strain_match", 1.5);
  CHECK(mrn_material_prepare(m) != MRN_OK);
  mrn_material_set(m, "plane_strain_match", 2);
  mrn_material_set(m, "psi", 40);
  CHECK(mrn_material_prepare(m) != MRN_OK);
  CHECK(strstr(mrn_error_message(), "psi") != NULL);
  mrn_material_unref(m);
}

int main(void) {
  test_plane_strain_match();
  test_triaxial_match();
  test_returns(0, 1);
  test_returns(20, 2);
  test_returns(30, 0);
  test_unloading();
  test_parameters();
  CHECK_DONE();
}
