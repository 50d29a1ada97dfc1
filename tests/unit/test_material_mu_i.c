/* moraine: the mu(I) rheology at a single material point. */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "core/error.h"
#include "core/tensor.h"
#include "material/driver.h"
#include "material/material.h"

/* glass beads (Jop et al. 2006): the model's defaults */
static const double MU_S = 0.381863, MU_2 = 0.643468, I0 = 0.279, D = 0.5e-3, RHO_S = 2450;
static const double E = 1e7, NU = 0.3;

static mrn_material *mu_i(void) {
  mrn_material *m = mrn_material_new(&mrn_material_mu_i);
  CHECK(mrn_material_set(m, "density", 0.6 * RHO_S) == MRN_OK);
  CHECK(mrn_material_set(m, "E", E) == MRN_OK);
  CHECK(mrn_material_set(m, "nu", NU) == MRN_OK);
  CHECK(mrn_material_prepare(m) == MRN_OK);
  return m;
}

static double mu_of(double I) { return MU_S + (MU_2 - MU_S) / (I0 / I + 1.0); }

/* Simple shear at an imposed normal stress sigma_yy = -P and shear rate
 * gamma_dot: once the elastic transient is past, tau / P = mu(I) with
 * I = gamma_dot d / sqrt(P / rho_s), over two decades of I. */
static void test_steady_shear(void) {
  mrn_material *m = mu_i();
  const double P = 1000.0, Is[] = {0.003, 0.03, 0.1, 0.3, 1.0, 3.0};
  double worst = 0.0;
  for (int c = 0; c < 6; c++) {
    const double rate = Is[c] * sqrt(P / RHO_S) / D;
    const double dt = 1e-4 / rate; /* a shear strain of 1e-4 per step */
    const double s0[6] = {-P, -P, -P, 0, 0, 0};
    mrn_driver d;
    mrn_driver_init(&d, m, s0);
    for (int i = 0; i < 2000; i++) CHECK(mrn_driver_simple_shear(&d, rate, -P, dt) == MRN_OK);
    const double ratio = d.stress[SXY] / P, expect = mu_of(Is[c]);
    const double err = fabs(ratio / expect - 1.0);
    printf("mu(I) simple shear: I = %-5g tau/P = %.6f, mu(I) = %.6f, error %.2e; model I = %.6g\n", Is[c], ratio,
           expect, err, d.state[1]);
    worst = fmax(worst, err);
    CHECK(err < 0.01);
    CHECK(fabs(d.state[1] / Is[c] - 1.0) < 0.01);
    CHECK(d.w_plastic < 0.0);
  }
  printf("mu(I) simple shear: worst relative error of tau/P against mu(I): %.2e\n", worst);
  mrn_material_unref(m);
}

/* Below mu_s the response is Hooke's law; in tension the grains separate. */
static void test_elastic_and_tension(void) {
  mrn_material *m = mu_i();
  const double P = 1000.0, G = E / (2 * (1 + NU));
  const double s0[6] = {-P, -P, -P, 0, 0, 0};
  mrn_driver d;
  mrn_driver_init(&d, m, s0);
  const double gamma = 0.5 * MU_S * P / G; /* half the static yield */
  for (int i = 0; i < 10; i++) CHECK(mrn_driver_simple_shear(&d, gamma / 10, NAN, 1.0) == MRN_OK);
  CHECK_CLOSE(d.stress[SXY] / (G * gamma), 1.0, 1e-6);
  CHECK(d.state[0] == 0.0 && d.w_plastic == 0.0);
  const double pull[6] = {1e-3, 1e-3, 1e-3, 0, 0, 0};
  CHECK(mrn_driver_strain(&d, pull, 1e-3) == MRN_OK);
  for (int k = 0; k < 6; k++) CHECK(d.stress[k] == 0.0);
  mrn_material_unref(m);
}

static void test_parameters(void) {
  mrn_material *m = mrn_material_new(&mrn_material_mu_i);
  CHECK(mrn_material_set(m, "density", 1500) == MRN_OK);
  CHECK(mrn_material_set(m, "E", 1e7) == MRN_OK);
  CHECK(mrn_material_set(m, "mu_2", 0.3) == MRN_OK);
  CHECK(mrn_material_prepare(m) != MRN_OK); /* mu_2 below the default mu_s */
  CHECK(mrn_material_set(m, "I0", 0) != MRN_OK);
  CHECK(mrn_material_set(m, "d", -1) != MRN_OK);
  mrn_material_unref(m);
}

int main(void) {
  test_steady_shear();
  test_elastic_and_tension();
  test_parameters();
  CHECK_DONE();
}
