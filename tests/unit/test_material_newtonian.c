/* moraine: the Newtonian fluid with Morris's equation of state
 * (002, Eqs. 69-70) at a single material point. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "core/tensor.h"
#include "material/driver.h"
#include "material/material.h"

static const double RHO = 1000, MU = 0.5, C = 50;

static mrn_material *fluid(void) {
  mrn_material *m = mrn_material_new(&mrn_material_newtonian);
  CHECK(mrn_material_set(m, "density", RHO) == MRN_OK);
  CHECK(mrn_material_set(m, "viscosity", MU) == MRN_OK);
  CHECK(mrn_material_set(m, "sound_speed", C) == MRN_OK);
  CHECK(mrn_material_prepare(m) == MRN_OK);
  return m;
}

/* v_x = gamma_dot y: sigma_xy = mu gamma_dot, no pressure (J stays 1), and
 * the viscous dissipation is mu gamma_dot^2 per unit volume and time */
static void test_simple_shear(void) {
  mrn_material *m = fluid();
  mrn_driver d;
  mrn_driver_init(&d, m, NULL);
  const double gdot = 10, dt = 1e-4;
  const double L[9] = {0, gdot, 0, 0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 500; i++) {
    CHECK(mrn_driver_step(&d, L, dt) == MRN_OK);
    CHECK_CLOSE(d.stress[SXY] / (MU * gdot), 1.0, 1e-12);
    CHECK(fabs(d.stress[SXX]) + fabs(d.stress[SYY]) + fabs(d.stress[SZZ]) <= 1e-12 * MU * gdot);
    CHECK_CLOSE(d.dw_plastic / (-MU * gdot * gdot * dt), 1.0, 1e-12);
  }
  CHECK(mat_det(d.F) == 1.0);
  CHECK_CLOSE(d.w_plastic / (-MU * gdot * gdot * d.time), 1.0, 1e-10);
  CHECK(d.e_elastic == 0.0);
  mrn_material_unref(m);
}

/* Oedometric compression: the mean stress is -c^2 (rho - rho_ref) with
 * rho = rho_ref / J, the deviator 2 mu dev(d), and the elastic energy the
 * equation of state's rho_ref c^2 (J - 1 - ln J) exactly. */
static void test_compression(void) {
  mrn_material *m = fluid();
  mrn_driver d;
  mrn_driver_init(&d, m, NULL);
  const double rate = -1.0, dt = 1e-4;
  double visc = 0;
  for (int i = 0; i < 200; i++) {
    double J_old = mat_det(d.F);
    CHECK(mrn_driver_oedometer(&d, rate, dt) == MRN_OK);
    double J = mat_det(d.F), rho = RHO / J;
    CHECK_CLOSE(-sym_trace(d.stress) / 3 / (C * C * (rho - RHO)), 1.0, 1e-12);
    CHECK_CLOSE((d.stress[SZZ] - d.stress[SXX]) / (2 * MU * rate), 1.0, 1e-9);
    visc += 0.5 * (J_old + J) * (-2 * MU * (2.0 / 3.0) * rate * rate * dt);
  }
  double J = mat_det(d.F);
  CHECK_CLOSE(J, pow(1 + rate * dt, 200), 1e-14);
  CHECK_CLOSE(d.e_elastic / (RHO * C * C * (J - 1 - log(J))), 1.0, 1e-10);
  CHECK_CLOSE(d.w_plastic / visc, 1.0, 1e-12);
  /* expanding back returns the stored energy: it follows J, not the path */
  for (int i = 0; i < 200; i++) CHECK(mrn_driver_oedometer(&d, -rate, dt) == MRN_OK);
  J = mat_det(d.F);
  CHECK(fabs(J - 1) < 3e-6); /* (1 - (dt rate)^2)^200 */
  CHECK(fabs(d.e_elastic - RHO * C * C * (J - 1 - log(J))) <= 1e-12 * RHO * C * C * 1e-4);
  mrn_material_unref(m);
}

static void test_parameters(void) {
  mrn_material *m = fluid();
  const mrn_material_type *t = m->type;
  CHECK(mrn_material_type_find("newtonian") == t);
  CHECK(t->rate_form == 0 && t->nstate == 0);
  CHECK(t->wave_speed(m) == C);
  CHECK_CLOSE(mrn_material_young(m), RHO * C * C, 1e-15);
  /* h^2 / nu (002, Eq. 36) */
  CHECK(t->viscous_dt != NULL);
  CHECK_CLOSE(t->viscous_dt(m, 0.01), 0.01 * 0.01 * RHO / MU, 1e-15);
  CHECK(mrn_material_set(m, "viscosity", 0) == MRN_OK);
  CHECK(isinf(t->viscous_dt(m, 0.01)));
  CHECK(mrn_material_set(m, "viscosity", -1) != MRN_OK);
  CHECK(mrn_material_set(m, "sound_speed", 0) != MRN_OK);
  CHECK(mrn_material_type_find("linear_elastic")->viscous_dt == NULL);
  CHECK(mrn_material_type_find("von_mises")->viscous_dt == NULL);
  mrn_material_unref(m);
  m = mrn_material_new(&mrn_material_newtonian);
  CHECK(mrn_material_prepare(m) != MRN_OK); /* density and sound speed are required */
  mrn_material_unref(m);
}

int main(void) {
  test_simple_shear();
  test_compression();
  test_parameters();
  CHECK_DONE();
}
