/* moraine: isotropic linear elasticity in rate form.
 *
 * Small-strain incremental Hooke's law on the Jaumann-rotated stress
 * (002, Eq. 28): sigma_new = R(sigma) + lambda tr(de) I + 2 G de. In plane
 * strain de_zz = 0 and sigma_zz still evolves through lambda tr(de). */
#include <math.h>

#include "core/error.h"
#include "core/tensor.h"
#include "material/material.h"

enum { P_DENSITY, P_E, P_NU, P_COUNT };
enum { D_LAMBDA, D_SHEAR, D_BULK };

static const mrn_spec params[P_COUNT] = {
    [P_DENSITY] = {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3", "mass density", NULL},
    [P_E] = {"E", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "Pa", "Young's modulus", NULL},
    [P_NU] = {"nu", MRN_SPEC_NUMBER, 0, 0.0, -1.0, 0.5, 1, 1, "", "Poisson's ratio", NULL},
};

static int prepare(mrn_material *m) {
  double E = m->param[P_E], nu = m->param[P_NU];
  m->derived[D_LAMBDA] = E * nu / ((1 + nu) * (1 - 2 * nu));
  m->derived[D_SHEAR] = E / (2 * (1 + nu));
  m->derived[D_BULK] = E / (3 * (1 - 2 * nu));
  return MRN_OK;
}

static inline void update_point(const mrn_material *m, mrn_material_point *pt) {
  pt->de_elastic = mrn_hooke_update(m->derived[D_LAMBDA], m->derived[D_SHEAR], pt->dstrain, pt->stress);
  pt->dw_plastic = 0.0;
}

MRN_MATERIAL_BATCH_UPDATE(update_point)

const mrn_material_type mrn_material_linear_elastic = {
    .name = "linear_elastic",
    .summary = "isotropic linear elasticity, incremental with the Jaumann rate (002, Eq. 28)",
    .params = params,
    .nparams = P_COUNT,
    .nstate = 0,
    .state_names = NULL,
    .rate_form = 1,
    .pure_hooke = 1, /* derived[D_LAMBDA], derived[D_SHEAR] are lambda, G */
    .prepare = prepare,
    .update = update,
    .wave_speed = mrn_material_isotropic_wave_speed,
};
