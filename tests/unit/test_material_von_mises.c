/* moraine: von Mises with linear hardening at a single material point. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "core/tensor.h"
#include "material/driver.h"
#include "material/elastoplastic.h"
#include "material/material.h"

static const double E = 200e9, NU = 0.3, SY = 250e6, H = 2e9;

static mrn_material *von_mises(double hardening) {
  mrn_material *m = mrn_material_new(&mrn_material_von_mises);
  CHECK(mrn_material_set(m, "density", 7800) == MRN_OK);
  CHECK(mrn_material_set(m, "E", E) == MRN_OK);
  CHECK(mrn_material_set(m, "nu", NU) == MRN_OK);
  CHECK(mrn_material_set(m, "yield", SY) == MRN_OK);
  CHECK(mrn_material_set(m, "hardening", hardening) == MRN_OK);
  CHECK(mrn_material_prepare(m) == MRN_OK);
  return m;
}

/* Uniaxial tension (lateral stresses held at zero): once yielding, the axial
 * stress is sigma_y + H eps_p exactly, with eps_p both the model's history
 * variable and the axial plastic strain eps_zz - sigma_zz / E. The plastic
 * work is then the integral of sigma_y + H eps_p over eps_p, which the
 * mid-step stress of 000 §5.1.4 integrates exactly (a linear integrand) once
 * the first, partly elastic, step is past. */
static void test_uniaxial(void) {
  mrn_material *m = von_mises(H);
  mrn_driver d;
  mrn_driver_init(&d, m, NULL);
  const double deps = 1e-4;
  double worst_law = 0, worst_ep = 0, worst_lat = 0, max_dw = -1, w_after = 0, ep_first = -1;
  int plastic = 0;
  for (int i = 0; i < 300; i++) {
    double J_old = mat_det(d.F), w_old = d.w_plastic;
    CHECK(mrn_driver_uniaxial(&d, 1.0, deps) == MRN_OK);
    double ep = d.state[0];
    max_dw = fmax(max_dw, d.dw_plastic);
    worst_lat = fmax(worst_lat, fmax(fabs(d.stress[SXX]), fabs(d.stress[SYY])) / SY);
    if (ep > 0) {
      plastic++;
      worst_law = fmax(worst_law, fabs(d.stress[SZZ] / (SY + H * ep) - 1));
      worst_ep = fmax(worst_ep, fabs(ep - (d.strain[SZZ] - d.stress[SZZ] / E)) / ep);
      if (ep_first < 0) {
        ep_first = ep;
      } else {
        /* the plastic work of the fully plastic steps, per unit current volume */
        w_after += (d.w_plastic - w_old) / (0.5 * (J_old + mat_det(d.F)));
      }
    }
  }
  double ep = d.state[0];
  CHECK(plastic > 250);
  CHECK(worst_law <= 1e-12);
  CHECK(worst_ep <= 1e-9);
  CHECK(worst_lat <= 1e-12);
  CHECK(max_dw <= 0.0);
  /* -w = int sigma d(eps_p) from ep_first to ep */
  double expect = SY * (ep - ep_first) + 0.5 * H * (ep * ep - ep_first * ep_first);
  CHECK_CLOSE(-w_after / expect, 1.0, 1e-9);
  mrn_material_unref(m);
}

/* Random strain increments from random admissible states: the return lands
 * on the hardened surface, radially, and unloading is elastic and exact. */
static double urand(void) { return rand() / (double)RAND_MAX * 2.0 - 1.0; }

static void test_returns(void) {
  mrn_material *m = von_mises(H);
  double lambda, G, K;
  mrn_lame(E, NU, &lambda, &G, &K);
  double worst = 0, worst_dir = 0, worst_mean = 0;
  int n = 0;
  srand(4242);
  for (int t = 0; t < 5000; t++) {
    double s0[6];
    for (int k = 0; k < 6; k++) s0[k] = 0.3 * SY * urand();
    double ep0 = 0.01 * (urand() + 1);
    if (sym_von_mises(s0) > SY + H * ep0) continue;
    double L[9];
    for (int k = 0; k < 9; k++) L[k] = urand() * 5 * SY / E;
    for (int a = 0; a < 3; a++)
      for (int b = a + 1; b < 3; b++) L[3 * b + a] = L[3 * a + b];
    double de[6], ds[6], trial[6];
    mat_sym_part(L, 1.0, de);
    mrn_hooke_increment(lambda, G, de, ds);
    for (int k = 0; k < 6; k++) trial[k] = s0[k] + ds[k];
    if (sym_von_mises(trial) <= SY + H * ep0) continue;
    mrn_driver d;
    mrn_driver_init(&d, m, s0);
    d.state[0] = ep0;
    CHECK(mrn_driver_step(&d, L, 1.0) == MRN_OK);
    n++;
    worst = fmax(worst, fabs(sym_von_mises(d.stress) - (SY + H * d.state[0])) / SY);
    worst_mean = fmax(worst_mean, fabs(sym_trace(d.stress) - sym_trace(trial)) / SY);
    double dv[6], dt_[6];
    sym_dev(d.stress, dv);
    sym_dev(trial, dt_);
    double a = sym_norm(dv), b = sym_norm(dt_);
    for (int k = 0; k < 6; k++) worst_dir = fmax(worst_dir, fabs(dv[k] / a - dt_[k] / b));
    CHECK(d.dw_plastic < 0.0);
    /* reversing a tenth of the increment unloads elastically, exactly */
    double back[9], old[6];
    for (int k = 0; k < 9; k++) back[k] = -0.1 * L[k];
    memcpy(old, d.stress, sizeof old);
    double ep = d.state[0];
    CHECK(mrn_driver_step(&d, back, 1.0) == MRN_OK);
    mat_sym_part(back, 1.0, de);
    mrn_hooke_increment(lambda, G, de, ds);
    for (int k = 0; k < 6; k++) CHECK(fabs(d.stress[k] - (old[k] + ds[k])) <= 1e-12 * SY);
    CHECK(d.state[0] == ep && d.dw_plastic == 0.0);
  }
  printf("  von Mises: %d plastic returns, worst |f| / sigma_y %.3g\n", n, worst);
  CHECK(n > 1000);
  CHECK(worst <= 1e-10);
  CHECK(worst_dir <= 1e-10);
  CHECK(worst_mean <= 1e-10);
  mrn_material_unref(m);
}

/* Perfect plasticity in plane-strain simple shear: the shear stress
 * saturates at the cohesion c = sigma_y / sqrt(3) (002, Eq. 67), less an
 * O(gamma^2) share taken by the normal stresses the Jaumann spin creates
 * (1.2e-6 at gamma = 0.004). */
static void test_shear(void) {
  mrn_material *m = von_mises(0.0);
  mrn_driver d;
  mrn_driver_init(&d, m, NULL);
  for (int i = 0; i < 400; i++) {
    CHECK(mrn_driver_simple_shear(&d, 1.0, NAN, 1e-5) == MRN_OK);
    CHECK(d.dw_plastic <= 0.0);
  }
  CHECK_CLOSE(d.stress[SXY] / (SY / sqrt(3.0)), 1.0, 1e-5);
  CHECK(m->type->nstate == 1 && strcmp(m->type->state_names[0], "eps_p") == 0);
  mrn_material_unref(m);
}

int main(void) {
  test_uniaxial();
  test_returns();
  test_shear();
  CHECK_DONE();
}
