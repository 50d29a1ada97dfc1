/* moraine: the mu(I) rheology of dense granular flow (Jop, Forterre and
 * Pouliquen 2006, Nature 441, 727-730), with an elastic response below
 * yield, in rate form.
 *
 * The friction coefficient depends on the inertial number I,
 *   mu(I) = mu_s + (mu_2 - mu_s) / (I0 / I + 1),   I = gamma_dot d / sqrt(p / rho_s),
 * with gamma_dot = sqrt(2 D':D') the plastic shear rate, p = -tr(sigma) / 3
 * the pressure (stresses are tension-positive), d the grain diameter and
 * rho_s the grain density. The stress is
 *   sigma = -p I + tau s' / |s'|,  tau = sqrt(s':s' / 2) = mu(I) p  while flowing.
 * Jop et al. write it for an incompressible flow with the pressure a
 * Lagrange multiplier; here, as in moraine's other explicit laws, the
 * pressure comes from the elastic bulk response (Hooke's law, E and nu), the
 * deviator from an elastic predictor, and the flow is the return
 * (Dunatunga and Kamrin 2015 take the same route, J. Fluid Mech. 779):
 *   trial  sigma* = R(sigma) + lambda tr(de) I + 2 G de,  p, tau* from sigma*;
 *   p <= 0: the grains separate and carry nothing, sigma = 0;
 *   tau* <= mu_s p: elastic (below the static yield);
 *   else the plastic shear rate g over the step, along s*', solves
 *     tau* - G dt g = p mu(I(g)),  I(g) = g d / sqrt(p / rho_s),
 *   a quadratic in g with one positive root, and s' = s*' (1 - G dt g / tau*).
 * A steady shear at rate gamma_dot then has exactly tau = mu(I(gamma_dot)) p.
 * The return keeps p (no dilatancy: the plastic flow is deviatoric).
 * History: gamma_p (accumulated plastic shear strain), I (the inertial
 * number of the last step). */
#include <math.h>

#include "core/error.h"
#include "core/tensor.h"
#include "material/elastoplastic.h"
#include "material/material.h"

enum { P_DENSITY, P_E, P_NU, P_MU_S, P_MU_2, P_I0, P_D, P_RHO_S, P_COUNT };
enum { D_LAMBDA, D_SHEAR, D_BULK };
enum { S_GAMMA_P, S_I, S_COUNT };

static const mrn_spec params[P_COUNT] = {
    [P_DENSITY] = {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3",
                   "bulk density of the granular material (solid fraction times rho_s)", NULL},
    [P_E] = {"E", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "Pa", "Young's modulus of the elastic response", NULL},
    [P_NU] = {"nu", MRN_SPEC_NUMBER, 0, 0.3, -1.0, 0.5, 1, 1, "", "Poisson's ratio of the elastic response", NULL},
    [P_MU_S] = {"mu_s", MRN_SPEC_NUMBER, 0, 0.381863, 0, HUGE_VAL, 0, 0, "",
                "static friction coefficient (default tan 20.9 deg, glass beads)", NULL},
    [P_MU_2] = {"mu_2", MRN_SPEC_NUMBER, 0, 0.643468, 0, HUGE_VAL, 0, 0, "",
                "limiting friction coefficient at large I, > mu_s (default tan 32.76 deg)", NULL},
    [P_I0] = {"I0", MRN_SPEC_NUMBER, 0, 0.279, 0, HUGE_VAL, 1, 0, "", "inertial number scale", NULL},
    [P_D] = {"d", MRN_SPEC_NUMBER, 0, 0.5e-3, 0, HUGE_VAL, 1, 0, "m", "grain diameter", NULL},
    [P_RHO_S] = {"rho_s", MRN_SPEC_NUMBER, 0, 2450, 0, HUGE_VAL, 1, 0, "kg/m^3", "density of the grains", NULL},
};

static const char *const state_names[S_COUNT] = {"gamma_p", "I"};

static int prepare(mrn_material *m) {
  double *d = m->derived;
  if (!(m->param[P_MU_2] > m->param[P_MU_S]))
    return mrn_error("material mu_i: mu_2 = %g must exceed mu_s = %g (mu(I) rises from mu_s to mu_2)",
                     m->param[P_MU_2], m->param[P_MU_S]);
  mrn_lame(m->param[P_E], m->param[P_NU], &d[D_LAMBDA], &d[D_SHEAR], &d[D_BULK]);
  return MRN_OK;
}

/* the plastic shear rate g > 0 of a return from tau (> mu_s p) at pressure p:
 * (tau - G dt g)(I0 + c g) = p (mu_2 - mu_s) c g with c = d / sqrt(p / rho_s),
 * i.e. A g^2 + B g - C = 0 with A = G dt c, B = G dt I0 + (p dmu - a) c,
 * C = a I0, a = tau - mu_s p > 0; the root in the form without cancellation */
static double plastic_rate(const mrn_material *m, double tau, double p, double dt) {
  const double G = m->derived[D_SHEAR], I0 = m->param[P_I0];
  const double c = m->param[P_D] / sqrt(p / m->param[P_RHO_S]);
  const double a = tau - m->param[P_MU_S] * p, dmu = m->param[P_MU_2] - m->param[P_MU_S];
  const double A = G * dt * c, B = G * dt * I0 + (p * dmu - a) * c, C = a * I0;
  if (!(A > 0.0)) return 0.0; /* a step of no time: no flow (and no division by A) */
  const double disc = sqrt(B * B + 4.0 * A * C);
  return B >= 0.0 ? 2.0 * C / (B + disc) : (disc - B) / (2.0 * A);
}

static inline void update_point(const mrn_material *m, mrn_material_point *pt) {
  double old[6], s[6], dev[6];
  for (int k = 0; k < 6; k++) old[k] = s[k] = pt->stress[k];
  mrn_hooke_update(m->derived[D_LAMBDA], m->derived[D_SHEAR], pt->dstrain, s);
  const double p = -sym_trace(s) / 3.0;
  int plastic = 0;
  double g = 0.0;
  if (!(p > 0.0)) {
    for (int k = 0; k < 6; k++) s[k] = 0.0; /* separated grains */
    plastic = 1;
  } else {
    sym_dev(s, dev);
    const double tau = sqrt(0.5 * sym_ddot(dev, dev));
    if (tau > m->param[P_MU_S] * p) {
      g = plastic_rate(m, tau, p, pt->dt);
      const double scale = 1.0 - m->derived[D_SHEAR] * pt->dt * g / tau;
      for (int k = 0; k < 6; k++) s[k] = scale * dev[k] + (k < 3 ? -p : 0.0);
      plastic = 1;
    }
  }
  for (int k = 0; k < 6; k++) pt->stress[k] = s[k];
  pt->state[S_GAMMA_P] += g * pt->dt;
  pt->state[S_I] = p > 0.0 ? g * m->param[P_D] / sqrt(p / m->param[P_RHO_S]) : 0.0;
  mrn_energy_split(m->param[P_E], m->param[P_NU], old, s, pt->dstrain, plastic, pt, NULL);
}

MRN_MATERIAL_BATCH_UPDATE(update_point)

const mrn_material_type mrn_material_mu_i = {
    .name = "mu_i",
    .summary = "mu(I) rheology of dense granular flow (Jop et al. 2006) with an elastic response below mu_s",
    .params = params,
    .nparams = P_COUNT,
    .nstate = S_COUNT,
    .state_names = state_names,
    .rate_form = 1,
    .prepare = prepare,
    .update = update,
    .wave_speed = mrn_material_isotropic_wave_speed,
};
