/* moraine: Mohr-Coulomb at a single material point (material/driver). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "core/tensor.h"
#include "material/driver.h"
#include "material/elastoplastic.h"
#include "material/material.h"
#include "material/principal.h"

static const double DEG = 3.14159265358979323846 / 180.0;

static mrn_material *mohr_coulomb(double E, double nu, double phi, double psi, double c, double tension) {
  mrn_material *m = mrn_material_new(&mrn_material_mohr_coulomb);
  CHECK(mrn_material_set(m, "density", 2000) == MRN_OK);
  CHECK(mrn_material_set(m, "E", E) == MRN_OK);
  CHECK(mrn_material_set(m, "nu", nu) == MRN_OK);
  CHECK(mrn_material_set(m, "phi", phi) == MRN_OK);
  CHECK(mrn_material_set(m, "psi", psi) == MRN_OK);
  CHECK(mrn_material_set(m, "cohesion", c) == MRN_OK);
  CHECK(mrn_material_set(m, "tension", tension) == MRN_OK);
  CHECK(mrn_material_prepare(m) == MRN_OK);
  return m;
}

/* f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi), s1 >= s2 >= s3 */
static double yield_mc(const double s[3], double phi, double c) {
  return (s[0] - s[2]) + (s[0] + s[2]) * sin(phi * DEG) - 2 * c * cos(phi * DEG);
}

static double tension_of(const mrn_material *m) {
  double phi = mrn_material_get(m, "phi") * DEG, c = mrn_material_get(m, "cohesion");
  double apex = phi > 0 ? c / tan(phi) : HUGE_VAL, t = mrn_material_get(m, "tension");
  return t < 0 || t > apex ? apex : t;
}

/* ---- triaxial compression: the closed-form peak ------------------------- */

/* Lateral stresses held at -p0, axial compression from isotropic -p0.
 * Compression-positive principal stresses at failure, sigma_a > sigma_r = p0:
 * sigma_a - p0 = (sigma_a + p0) sin(phi), so q = sigma_a - p0 =
 * 2 sin(phi) / (1 - sin(phi)) p0, and with p = (sigma_a + 2 p0) / 3 the same
 * state obeys q = 6 sin(phi) p / (3 - sin(phi)), the triaxial-compression
 * line of the issue. */
static void test_triaxial(double psi) {
  const double E = 1e7, nu = 0.3, phi = 30, p0 = 1e5, rate = -1.0, dt = 1e-5;
  mrn_material *m = mohr_coulomb(E, nu, phi, psi, 0.0, -1);
  const double s0[6] = {-p0, -p0, -p0, 0, 0, 0};
  mrn_driver d;
  CHECK(mrn_driver_init(&d, m, s0) == MRN_OK);
  double qmax = 0, p_at = 0, lateral_err = 0, work = 0, el_sum = 0, worst_f = -1, max_dw = -1, worst_id = 0;
  int plastic_steps = 0, edge_steps = 0;
  for (int i = 0; i < 3000; i++) {
    double old[6], strain_old[6], J_old = mat_det(d.F);
    memcpy(old, d.stress, sizeof old);
    memcpy(strain_old, d.strain, sizeof old);
    if (mrn_driver_triaxial(&d, rate, -p0, dt) != MRN_OK) {
      CHECK(!"triaxial step failed");
      break;
    }
    double de[6], mid[6];
    for (int k = 0; k < 6; k++) {
      de[k] = d.strain[k] - strain_old[k];
      mid[k] = 0.5 * (old[k] + d.stress[k]);
    }
    /* per step, elastic energy plus dissipation is the mid-step stress work */
    double w = sym_ddot(mid, de);
    worst_id = fmax(worst_id, fabs(d.de_elastic - d.dw_plastic - w) / (p0 * fabs(rate) * dt));
    work += 0.5 * (J_old + mat_det(d.F)) * w;
    el_sum += d.de_elastic;
    double q = d.stress[SXX] - d.stress[SZZ], p = -sym_trace(d.stress) / 3;
    if (q > qmax) {
      qmax = q;
      p_at = p;
    }
    lateral_err = fmax(lateral_err, fmax(fabs(d.stress[SXX] + p0), fabs(d.stress[SYY] + p0)) / p0);
    double lam[3], V[9];
    mrn_sym_eigen(d.stress, lam, V);
    worst_f = fmax(worst_f, yield_mc(lam, phi, 0) / p0);
    max_dw = fmax(max_dw, d.dw_plastic);
    if (d.dw_plastic < 0) {
      plastic_steps++;
      if (fabs(yield_mc(lam, phi, 0)) <= 1e-10 * p0 && fabs(lam[0] - lam[1]) <= 1e-10 * p0) edge_steps++;
    }
  }
  double sphi = sin(phi * DEG);
  CHECK(plastic_steps > 500);
  CHECK(edge_steps == plastic_steps); /* triaxial compression is the s1 = s2 edge */
  CHECK_CLOSE(qmax / (6 * sphi * p_at / (3 - sphi)), 1.0, 1e-8);
  CHECK_CLOSE(qmax / (2 * sphi / (1 - sphi) * p0), 1.0, 1e-8);
  CHECK(lateral_err < 1e-10);
  CHECK(worst_f <= 1e-10);
  CHECK(max_dw <= 0.0);
  CHECK(d.w_plastic < 0.0);
  /* (000, Eqs. 64-65): elastic energy plus dissipation is the stress work
   * (per unit reference volume, over the mid-step volume), and the sum of
   * the elastic increments is exactly the change of the complementary
   * energy sigma : C^-1 : sigma / 2 */
  CHECK(worst_id < 1e-9);
  CHECK_CLOSE((d.e_elastic - d.w_plastic) / work, 1.0, 1e-12);
  double c0[6], c1[6];
  mrn_hooke_compliance(E, nu, s0, c0);
  mrn_hooke_compliance(E, nu, d.stress, c1);
  CHECK_CLOSE(el_sum / (0.5 * sym_ddot(d.stress, c1) - 0.5 * sym_ddot(s0, c0)), 1.0, 1e-10);
  /* dilatancy: eps_pv = sum tr(deps_p); zero for psi = 0, expansion (> 0) otherwise */
  if (psi == 0)
    CHECK(fabs(d.state[1]) < 1e-12);
  else
    CHECK(d.state[1] > 0.0);
  CHECK(d.state[0] > 0.0);

  /* elastic unloading is exact: the stress follows C : deps and nothing else moves */
  double eps_p = d.state[0];
  for (int i = 0; i < 20; i++) {
    double old[6], strain_old[6], ds[6], lambda, G, K;
    memcpy(old, d.stress, sizeof old);
    memcpy(strain_old, d.strain, sizeof old);
    CHECK(mrn_driver_triaxial(&d, -rate, -p0, dt) == MRN_OK);
    double de[6];
    for (int k = 0; k < 6; k++) de[k] = d.strain[k] - strain_old[k];
    mrn_lame(E, nu, &lambda, &G, &K);
    mrn_hooke_increment(lambda, G, de, ds);
    for (int k = 0; k < 6; k++) CHECK(fabs(d.stress[k] - (old[k] + ds[k])) <= 1e-12 * p0);
    CHECK(d.dw_plastic == 0.0);
  }
  CHECK(d.state[0] == eps_p);
  mrn_material_unref(m);
}

/* ---- every return lands on the surface ---------------------------------- */

enum { MODE_MAIN, MODE_EDGE12, MODE_EDGE23, MODE_APEX, MODE_T, MODE_T_MC, MODE_T_EDGE, MODE_T_CORNER, NMODES };
static const char *const mode_names[NMODES] = {"main plane", "edge s1=s2",   "edge s2=s3",   "apex",
                                               "tension",    "tension + MC", "tension edge", "tension corner"};

static int classify(const double s[3], double phi, double c, double T, double tol) {
  int on_t = isfinite(T) && fabs(s[0] - T) <= tol, on_mc = fabs(yield_mc(s, phi, c)) <= tol;
  int e12 = fabs(s[0] - s[1]) <= tol, e23 = fabs(s[1] - s[2]) <= tol;
  if (e12 && e23) return MODE_APEX;
  if (on_t && on_mc) return e12 || e23 ? MODE_T_CORNER : MODE_T_MC;
  if (on_t) return e12 ? MODE_T_EDGE : MODE_T;
  return e12 ? MODE_EDGE12 : e23 ? MODE_EDGE23 : MODE_MAIN;
}

static double urand(void) { return rand() / (double)RAND_MAX * 2.0 - 1.0; }

/* Random admissible start stresses and random strain increments large
 * enough to reach every part of the surface; each plastic result must be
 * admissible, on the surface, in the trial's principal frame, and dissipate. */
static void test_returns(double psi, double tension, int expect_tension) {
  const double E = 1e7, nu = 0.25, phi = 30, c = 2e4, scale = 1e5;
  mrn_material *m = mohr_coulomb(E, nu, phi, psi, c, tension);
  const double T = tension_of(m), mflow = (1 + sin(psi * DEG)) / (1 - sin(psi * DEG));
  double lambda, G, K;
  mrn_lame(E, nu, &lambda, &G, &K);
  int count[NMODES] = {0};
  double worst_on = 0, worst_out = -1, worst_flow = 0, worst_frame = 0, min_diss = 1;
  int positive_mid = 0, plastic = 0;
  srand(12345);
  for (int trial = 0; trial < 20000; trial++) {
    /* a start stress inside the surface: isotropic compression plus a small deviator */
    double p = -scale * (0.05 + 0.95 * (urand() + 1) / 2), s0[6];
    for (int k = 0; k < 6; k++) s0[k] = (k < 3 ? p : 0.0) + 0.1 * c * urand();
    double l0[3], V0[9];
    mrn_sym_eigen(s0, l0, V0);
    if (yield_mc(l0, phi, c) > 0 || l0[0] > T) continue;
    double L[9];
    for (int k = 0; k < 9; k++) L[k] = urand() * 3 * scale / E * (trial % 3 == 0 ? 3.0 : 1.0);
    /* no spin, so the trial below is exactly what the model sees */
    for (int a = 0; a < 3; a++)
      for (int b = a + 1; b < 3; b++) L[3 * b + a] = L[3 * a + b];
    mrn_driver d;
    mrn_driver_init(&d, m, s0);
    double trial_s[6], ds[6], de[6];
    mat_sym_part(L, 1.0, de);
    mrn_hooke_increment(lambda, G, de, ds);
    for (int k = 0; k < 6; k++) trial_s[k] = s0[k] + ds[k];
    if (mrn_driver_step(&d, L, 1.0) != MRN_OK) continue;
    double lt[3], Vt[9], ln[3], Vn[9];
    mrn_sym_eigen(trial_s, lt, Vt);
    if (yield_mc(lt, phi, c) <= 0 && lt[0] <= T) continue; /* elastic */
    mrn_sym_eigen(d.stress, ln, Vn);
    double sc = fmax(fabs(lt[0]), fabs(lt[2])), tol = 1e-10 * sc;
    double fm = yield_mc(ln, phi, c), ft = isfinite(T) ? ln[0] - T : -HUGE_VAL;
    worst_out = fmax(worst_out, fmax(fm, ft) / sc);
    worst_on = fmax(worst_on, fabs(fmax(fm, ft)) / sc);
    /* the return dissipates at the end state: sigma_new : deps_p >= 0 (the
     * mid-step work of 000 §5.1.4 can have either sign for a jump this
     * large, see the paths below for its sign under ordinary increments) */
    double dsig[6], dep_el[6], dep_p[6];
    for (int k = 0; k < 6; k++) dsig[k] = d.stress[k] - s0[k];
    mrn_hooke_compliance(E, nu, dsig, dep_el);
    for (int k = 0; k < 6; k++) dep_p[k] = de[k] - dep_el[k];
    min_diss = fmin(min_diss, sym_ddot(d.stress, dep_p) / (sc * sc / E));
    if (d.dw_plastic > 0) positive_mid++;
    /* the return keeps the trial's principal frame: sigma_new is diagonal there */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        if (i == j) continue;
        double v = 0;
        for (int a = 0; a < 3; a++)
          for (int b = 0; b < 3; b++) v += Vt[3 * a + i] * d.stress[sym_index(a, b)] * Vt[3 * b + j];
        worst_frame = fmax(worst_frame, fabs(v) / sc);
      }
    int mode = classify(ln, phi, c, T, tol);
    count[mode]++;
    plastic++;
    /* main-plane returns flow along (m, 0, -1): D^-1 (trial - new) in principal stresses */
    if (mode == MODE_MAIN) {
      double dsp[3] = {lt[0] - ln[0], lt[1] - ln[1], lt[2] - ln[2]}, dep[3];
      double tr = dsp[0] + dsp[1] + dsp[2];
      for (int i = 0; i < 3; i++) dep[i] = ((1 + nu) * dsp[i] - nu * tr) / E;
      worst_flow = fmax(worst_flow, fmax(fabs(dep[1]), fabs(dep[0] + mflow * dep[2])) / fabs(dep[0]));
      CHECK(dep[0] > 0);
    }
  }
  for (int i = 0; i < NMODES; i++) printf("  psi %g, T %g: %-15s %d returns\n", psi, T, mode_names[i], count[i]);
  CHECK(count[MODE_MAIN] > 0);
  CHECK(count[MODE_EDGE12] > 0);
  CHECK(count[MODE_EDGE23] > 0);
  CHECK(count[MODE_APEX] > 0);
  if (expect_tension) {
    CHECK(count[MODE_T] > 0);
    CHECK(count[MODE_T_MC] > 0);
    CHECK(count[MODE_T_EDGE] > 0);
    CHECK(count[MODE_T_CORNER] > 0);
  } else {
    CHECK(count[MODE_T] + count[MODE_T_MC] + count[MODE_T_EDGE] + count[MODE_T_CORNER] == 0);
  }
  CHECK(worst_out <= 1e-10);
  CHECK(worst_on <= 1e-10);
  CHECK(worst_frame <= 1e-10);
  CHECK(worst_flow <= 1e-8);
  CHECK(min_diss >= -1e-12);
  printf("  worst |f| %.3g, frame %.3g, flow %.3g; mid-step dw > 0 in %d of %d large jumps\n", worst_on, worst_frame,
         worst_flow, positive_mid, plastic);
  mrn_material_unref(m);
}

/* ---- uniaxial tension: Mohr-Coulomb strength or the cut-off -------------- */

static double uniaxial_tension_peak(double tension) {
  mrn_material *m = mohr_coulomb(1e7, 0.2, 30, 0, 2e4, tension);
  mrn_driver d;
  mrn_driver_init(&d, m, NULL);
  double peak = -HUGE_VAL;
  for (int i = 0; i < 200; i++) {
    CHECK(mrn_driver_uniaxial(&d, 1.0, 2e-5) == MRN_OK);
    peak = fmax(peak, d.stress[SZZ]);
    /* with a cut-off at zero nothing dissipates; allow its round-off */
    CHECK(d.dw_plastic <= 1e-12 * 2e4 * 2e-5);
  }
  mrn_material_unref(m);
  return peak;
}

static void test_tension(void) {
  double phi = 30 * DEG, c = 2e4;
  /* default cut-off (the apex): uniaxial tension fails on the cone */
  CHECK_CLOSE(uniaxial_tension_peak(-1) / (2 * c * cos(phi) / (1 + sin(phi))), 1.0, 1e-10);
  /* a cut-off above the apex has no effect */
  CHECK_CLOSE(uniaxial_tension_peak(1e9) / (2 * c * cos(phi) / (1 + sin(phi))), 1.0, 1e-10);
  CHECK_CLOSE(uniaxial_tension_peak(5e3) / 5e3, 1.0, 1e-10);
  CHECK(fabs(uniaxial_tension_peak(0.0)) <= 1e-10 * c);
}

/* ---- simple shear at constant normal stress, with spin ----------------- */

/* Plane-strain simple shear, v_x = gamma_rate y, sigma_yy held. With psi = 0
 * the steady state is isochoric shear with principal axes at 45 degrees, so
 * sigma_xx = sigma_yy and the shear stress reaches the radius of the Mohr
 * circle tangent to the envelope, tau = sigma_n sin(phi) + c cos(phi)
 * (compression positive sigma_n); the Jaumann spin only perturbs this by
 * O(gamma) at small shear strain. */
static void test_simple_shear(void) {
  const double E = 2e7, nu = 0.3, phi = 30, c = 5e3, sn = 1e5;
  mrn_material *m = mohr_coulomb(E, nu, phi, 0.0, c, -1);
  const double s0[6] = {-sn, -sn, -sn, 0, 0, 0};
  mrn_driver d;
  mrn_driver_init(&d, m, s0);
  double max_dw = -1, worst_f = -1;
  for (int i = 0; i < 2000; i++) {
    if (mrn_driver_simple_shear(&d, 1.0, -sn, 1e-5) != MRN_OK) {
      CHECK(!"simple shear step failed");
      break;
    }
    max_dw = fmax(max_dw, d.dw_plastic);
    double lam[3], V[9];
    mrn_sym_eigen(d.stress, lam, V);
    worst_f = fmax(worst_f, yield_mc(lam, phi, c) / sn);
  }
  double tau = sn * sin(phi * DEG) + c * cos(phi * DEG);
  printf("  simple shear: tau / (sigma_n sin(phi) + c cos(phi)) = %.6f at gamma = 0.02\n", d.stress[SXY] / tau);
  CHECK(fabs(d.stress[SXY] / tau - 1) < 1e-2);
  CHECK(fabs(d.stress[SYY] + sn) < 1e-10 * sn);
  CHECK(max_dw <= 0.0);
  CHECK(d.w_plastic < 0.0);
  CHECK(worst_f <= 1e-10);
  mrn_material_unref(m);
}

/* ---- parameters --------------------------------------------------------- */

static void test_parameters(void) {
  mrn_material *m = mrn_material_new(&mrn_material_mohr_coulomb);
  CHECK(mrn_material_set(m, "phi", 95) != MRN_OK);
  CHECK(mrn_material_set(m, "phi", 90) != MRN_OK);
  CHECK(mrn_material_set(m, "nu", 0.5) != MRN_OK);
  CHECK(mrn_material_set(m, "cohesion", -1) != MRN_OK);
  CHECK(mrn_material_set(m, "dilatancy", 1) != MRN_OK);
  CHECK(strstr(mrn_error_message(), "unknown parameter") != NULL);
  CHECK(mrn_material_prepare(m) != MRN_OK); /* density, E and phi are required */
  mrn_material_set(m, "density", 1748);
  mrn_material_set(m, "E", 1.284e7);
  mrn_material_set(m, "nu", 0.16);
  mrn_material_set(m, "phi", 20);
  mrn_material_set(m, "psi", 25);
  CHECK(mrn_material_prepare(m) != MRN_OK);
  CHECK(strstr(mrn_error_message(), "psi") != NULL);
  mrn_material_set(m, "psi", 0);
  mrn_material_set(m, "phi", 0);
  CHECK(mrn_material_prepare(m) != MRN_OK); /* no strength at all */
  /* 000 Table 2 */
  mrn_material_set(m, "phi", 33.75);
  mrn_material_set(m, "cohesion", 1);
  CHECK(mrn_material_prepare(m) == MRN_OK);
  CHECK_CLOSE(tension_of(m), 1 / tan(33.75 * DEG), 1e-14);
  CHECK(mrn_material_type_find("mohr_coulomb") == &mrn_material_mohr_coulomb);
  CHECK(m->type->nstate == 2 && strcmp(m->type->state_names[0], "eps_p") == 0);
  CHECK_CLOSE(m->type->wave_speed(m), sqrt(1.284e7 * 0.84 / (1.16 * 0.68) / 1748), 1e-12);
  mrn_material_unref(m);
}

int main(void) {
  test_triaxial(0.0);
  test_triaxial(10.0);
  test_returns(0.0, -1, 0);
  test_returns(10.0, -1, 0);
  test_returns(10.0, 5e3, 1);
  test_returns(30.0, 5e3, 1);
  test_tension();
  test_simple_shear();
  test_parameters();
  CHECK_DONE();
}
