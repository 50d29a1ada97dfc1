/* moraine: Modified Cam-Clay at a single material point against the
 * closed forms of critical-state soil mechanics (Wood 1990, ch. 4-7):
 * the normal compression line, and the critical state q = M p' reached in
 * drained and undrained triaxial compression. Stresses are tension positive,
 * p' = -tr(sigma) / 3. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "core/error.h"
#include "core/tensor.h"
#include "material/driver.h"
#include "material/material.h"

static const double M = 1.2, LAMBDA = 0.2, KAPPA = 0.04, NU = 0.25, PC0 = 200e3, V0 = 2.0;
/* the normal compression line v = N - lambda ln p' through (p_c0, v0) */
static const double N_ = V0 + LAMBDA * 12.206072645530174; /* ln(200e3) */

static mrn_material *mcc(void) {
  mrn_material *m = mrn_material_new(&mrn_material_cam_clay);
  CHECK(mrn_material_set(m, "density", 1800) == MRN_OK);
  CHECK(mrn_material_set(m, "M", M) == MRN_OK);
  CHECK(mrn_material_set(m, "lambda", LAMBDA) == MRN_OK);
  CHECK(mrn_material_set(m, "kappa", KAPPA) == MRN_OK);
  CHECK(mrn_material_set(m, "nu", NU) == MRN_OK);
  CHECK(mrn_material_set(m, "v0", V0) == MRN_OK);
  CHECK(mrn_material_set(m, "p_c0", PC0) == MRN_OK);
  CHECK(mrn_material_prepare(m) == MRN_OK);
  return m;
}

static double p_of(const double s[6]) { return -(s[0] + s[1] + s[2]) / 3.0; }
static double q_of(const double s[6]) { return sym_von_mises(s); }
static double v_of(const mrn_driver *d) { return V0 * exp(d->state[1]); }

/* isotropic start on the NCL at p' = p_c0 */
static void start(mrn_driver *d, const mrn_material *m) {
  const double s0[6] = {-PC0, -PC0, -PC0, 0, 0, 0};
  mrn_driver_init(d, m, s0);
  d->kinematics = MRN_DRIVER_F_MIDPOINT; /* as the explicit step */
}

/* Isotropic compression from p_c0 to 5 p_c0 follows the NCL
 * v = N - lambda ln p', and unloading the swelling line (slope kappa). */
static void test_isotropic(void) {
  mrn_material *m = mcc();
  mrn_driver d;
  start(&d, m);
  const double de[6] = {-2e-5, -2e-5, -2e-5, 0, 0, 0};
  double worst = 0.0;
  while (p_of(d.stress) < 5 * PC0) {
    CHECK(mrn_driver_strain(&d, de, 1.0) == MRN_OK);
    worst = fmax(worst, fabs(v_of(&d) / (N_ - LAMBDA * log(p_of(d.stress))) - 1.0));
  }
  const double pc = PC0 * exp(d.state[0]);
  printf("cam_clay NCL: p' = %.1f kPa, v = %.5f, NCL %.5f, worst error on the way %.2e; p_c/p' = %.6f\n",
         p_of(d.stress) / 1e3, v_of(&d), N_ - LAMBDA * log(p_of(d.stress)), worst, pc / p_of(d.stress));
  CHECK(worst < 0.01);
  CHECK(fabs(pc / p_of(d.stress) - 1.0) < 1e-6);
  /* unloading to p_c / 2: elastic, v rises by kappa ln 2 */
  const double v_top = v_of(&d), p_top = p_of(d.stress), up[6] = {2e-6, 2e-6, 2e-6, 0, 0, 0};
  while (p_of(d.stress) > 0.5 * p_top) CHECK(mrn_driver_strain(&d, up, 1.0) == MRN_OK);
  const double swell = (v_of(&d) - v_top) / (KAPPA * log(p_top / p_of(d.stress)));
  printf("cam_clay swelling line: dv / (kappa ln(p0/p)) = %.5f\n", swell);
  CHECK(fabs(swell - 1.0) < 0.01);
  CHECK(PC0 * exp(d.state[0]) == pc);
  mrn_material_unref(m);
}

/* Drained triaxial compression from the NCL at p0 = p_c0, the cell pressure
 * held: the path dq/dp' = 3 ends on the critical state q = M p' at
 * p' = 3 p0 / (3 - M). The driver's axial strain is the sum of the
 * increments; the model is small strain, and MCC reaches the critical state
 * only asymptotically, so the path runs to 120 %. */
static void test_drained(void) {
  mrn_material *m = mcc();
  mrn_driver d;
  start(&d, m);
  for (int i = 0; i < 12000; i++) {
    CHECK(mrn_driver_triaxial(&d, -1e-4, -PC0, 1.0) == MRN_OK);
    /* the approach is slow: q/(M p') = 0.977 at eps_a = 0.4, 0.9999 past 1 */
    if (i + 1 == 4000) printf("cam_clay drained: q/(M p') = %.4f at eps_a = 0.4\n", q_of(d.stress) / (M * p_of(d.stress)));
  }
  const double p = p_of(d.stress), q = q_of(d.stress);
  const double err_q = fabs(q / (M * p) - 1.0), err_p = fabs(p / (3 * PC0 / (3 - M)) - 1.0);
  /* on the critical-state line in v - ln p': v = Gamma - lambda ln p', Gamma = N - (lambda - kappa) ln 2 */
  const double err_v = fabs(v_of(&d) / (N_ - (LAMBDA - KAPPA) * log(2.0) - LAMBDA * log(p)) - 1.0);
  printf("cam_clay drained: eps_a = %.2f, p' = %.1f kPa, q = %.1f kPa, q/(M p') - 1 = %.2e, p'/p'_cs - 1 = %.2e, "
         "v/v_csl - 1 = %.2e\n",
         d.strain[SZZ], p / 1e3, q / 1e3, q / (M * p) - 1.0, p / (3 * PC0 / (3 - M)) - 1.0, err_v);
  CHECK(err_q < 0.01);
  CHECK(err_p < 0.01);
  CHECK(err_v < 0.01);
  mrn_material_unref(m);
}

/* Undrained (constant volume) triaxial compression from the NCL: v stays
 * v0 and the path ends on the critical state q = M p' with p' on the CSL,
 * p'_cs = exp((Gamma - v0) / lambda) = p0 / 2^((lambda - kappa) / lambda). */
static void test_undrained(void) {
  mrn_material *m = mcc();
  mrn_driver d;
  start(&d, m);
  const double r = 1e-4, L[9] = {0.5 * r, 0, 0, 0, 0.5 * r, 0, 0, 0, -r};
  for (int i = 0; i < 3000; i++) CHECK(mrn_driver_step(&d, L, 1.0) == MRN_OK);
  const double p = p_of(d.stress), q = q_of(d.stress);
  const double p_cs = PC0 / pow(2.0, (LAMBDA - KAPPA) / LAMBDA);
  printf("cam_clay undrained: eps_a = %.2f, v = %.6f, p' = %.2f kPa (CSL %.2f), q = %.2f kPa, q/(M p') - 1 = %.2e, "
         "p'/p'_cs - 1 = %.2e\n",
         d.strain[SZZ], v_of(&d), p / 1e3, p_cs / 1e3, q / 1e3, q / (M * p) - 1.0, p / p_cs - 1.0);
  CHECK(fabs(q / (M * p) - 1.0) < 0.01);
  CHECK(fabs(p / p_cs - 1.0) < 0.01);
  CHECK(fabs(v_of(&d) / V0 - 1.0) < 1e-6);
  mrn_material_unref(m);
}

/* Random states (inside and outside the surface, in tension too) and random
 * increments, none included: every return is finite, lands on the updated
 * surface (or stays inside it when elastic) with p' >= 0. */
static double urand(void) { return rand() / (double)RAND_MAX * 2.0 - 1.0; }

static void test_random_returns(void) {
  mrn_material *m = mcc();
  double worst = 0.0;
  int plastic = 0;
  srand(2828);
  for (int t = 0; t < 20000; t++) {
    double s0[6];
    for (int k = 0; k < 6; k++) s0[k] = (k < 3 ? -0.6 : 0.0) * PC0 + 0.8 * PC0 * urand();
    mrn_driver d;
    mrn_driver_init(&d, m, s0);
    double de[6];
    const double size = t % 3 == 0 ? 0.0 : pow(10.0, -6.0 + 4.0 * (urand() + 1.0) / 2.0);
    for (int k = 0; k < 6; k++) de[k] = size * urand();
    CHECK(mrn_driver_strain(&d, de, 1.0) == MRN_OK);
    const double p = p_of(d.stress), q = q_of(d.stress), pc = PC0 * exp(d.state[0]);
    const double f = q * q / (M * M) + p * (p - pc);
    int finite = isfinite(p) && isfinite(q) && isfinite(pc);
    CHECK(finite);
    if (!finite) break;
    CHECK(p >= -1e-9 * PC0 || f <= 0.0);
    if (d.dw_plastic != 0.0 || d.state[2] != 0.0) {
      plastic++;
      worst = fmax(worst, fabs(f) / (pc * pc));
    } else {
      CHECK(f <= 1e-12 * PC0 * PC0);
    }
  }
  printf("cam_clay random returns: %d plastic of 20000, worst |f| / p_c^2 on the surface %.2e\n", plastic, worst);
  CHECK(plastic > 5000);
  CHECK(worst < 1e-10);
  mrn_material_unref(m);
}

static void test_parameters(void) {
  mrn_material *m = mcc();
  CHECK(mrn_material_set(m, "kappa", 0.3) == MRN_OK);
  CHECK(mrn_material_prepare(m) != MRN_OK); /* kappa above lambda */
  CHECK(mrn_material_set(m, "v0", 0.9) != MRN_OK);
  CHECK(mrn_material_set(m, "p_c0", 0) != MRN_OK);
  mrn_material_unref(m);
}

int main(void) {
  test_isotropic();
  test_drained();
  test_undrained();
  test_random_returns();
  test_parameters();
  CHECK_DONE();
}
