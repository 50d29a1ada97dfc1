/* moraine: von Mises plasticity with linear isotropic hardening.
 *
 * Hooke's law in rate form on the Jaumann-rotated stress (002, Eq. 28) and
 *   f = sqrt(3 J2) - (sigma_y + H eps_p) <= 0   (002, Eq. 66; 001, Eq. 63)
 * with associated flow. The radial return is exact for linear hardening:
 * the trial deviator shrinks towards the origin, eps_p grows by
 * f_trial / (3 G + H), and the mean stress stays elastic. In plane strain
 * sigma_y = sqrt(3) c matches a cohesion c (002, Eq. 67). */
#include <math.h>

#include "core/tensor.h"
#include "material/elastoplastic.h"
#include "material/material.h"

enum { P_DENSITY, P_E, P_NU, P_YIELD, P_HARDENING, P_COUNT };
enum { D_LAMBDA, D_SHEAR, D_BULK };
enum { S_EPS_P, S_COUNT };

static const mrn_spec params[P_COUNT] = {
    [P_DENSITY] = {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3", "mass density", NULL},
    [P_E] = {"E", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "Pa", "Young's modulus", NULL},
    [P_NU] = {"nu", MRN_SPEC_NUMBER, 0, 0.0, -1.0, 0.5, 1, 1, "", "Poisson's ratio", NULL},
    [P_YIELD] = {"yield", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "Pa",
                 "initial yield stress sigma_y in uniaxial tension (sqrt(3) c in plane strain)", NULL},
    [P_HARDENING] = {"hardening", MRN_SPEC_NUMBER, 0, 0.0, 0, HUGE_VAL, 0, 0, "Pa",
                     "hardening modulus H: yield stress sigma_y + H eps_p", NULL},
};

static const char *const state_names[S_COUNT] = {"eps_p"};

static int prepare(mrn_material *m) {
  mrn_lame(m->param[P_E], m->param[P_NU], &m->derived[D_LAMBDA], &m->derived[D_SHEAR], &m->derived[D_BULK]);
  return 0;
}

static inline void update_point(const mrn_material *m, mrn_material_point *pt) {
  const double G = m->derived[D_SHEAR], H = m->param[P_HARDENING];
  double old[6], trial[6], ds[6], s[6];
  for (int k = 0; k < 6; k++) old[k] = pt->stress[k];
  mrn_hooke_increment(m->derived[D_LAMBDA], G, pt->dstrain, ds);
  for (int k = 0; k < 6; k++) trial[k] = old[k] + ds[k];
  double eps_p = pt->state ? pt->state[S_EPS_P] : 0.0;
  sym_dev(trial, s);
  double q = sqrt(1.5 * sym_ddot(s, s));
  double f = q - (m->param[P_YIELD] + H * eps_p);
  int plastic = f > 0.0;
  if (!plastic) {
    for (int k = 0; k < 6; k++) pt->stress[k] = trial[k];
  } else {
    double dep = f / (3 * G + H);
    double scale = 1 - 3 * G * dep / q;
    double mean = sym_trace(trial) / 3.0;
    for (int k = 0; k < 6; k++) pt->stress[k] = scale * s[k] + (k < 3 ? mean : 0.0);
    if (pt->state) pt->state[S_EPS_P] = eps_p + dep;
  }
  mrn_energy_split(m->param[P_E], m->param[P_NU], old, pt->stress, pt->dstrain, plastic, pt, NULL);
}

MRN_MATERIAL_BATCH_UPDATE(update_point)

/* In an implicit run the same parameters drive the finite-strain law: Hencky
 * elasticity with the von Mises yield surface in principal logarithmic
 * strains (001 Eqs. 62-63), not the small-strain rate form above. */
static void implicit_law(const mrn_material *m, mrn_implicit_law *out) {
  out->lambda = m->derived[D_LAMBDA];
  out->G = m->derived[D_SHEAR];
  out->yield = m->param[P_YIELD];
  out->hardening = m->param[P_HARDENING];
}

static const mrn_implicit_form implicit_form = {
    "Hencky elasticity with von Mises plasticity and linear isotropic hardening in logarithmic strains (finite "
    "strain; explicit runs use the small-strain rate form)",
    implicit_law};

const mrn_material_type mrn_material_von_mises = {
    .name = "von_mises",
    .summary = "von Mises plasticity with linear isotropic hardening, radial return (002, Eq. 66)",
    .params = params,
    .nparams = P_COUNT,
    .nstate = S_COUNT,
    .state_names = state_names,
    .rate_form = 1,
    .prepare = prepare,
    .update = update,
    .wave_speed = mrn_material_isotropic_wave_speed,
    .implicit = &implicit_form,
};
