/* moraine: compressible Neo-Hookean hyperelasticity.
 *
 *   sigma = G / J (b - I) + lambda ln(J) / J I,   b = F F^T,
 * from the stored energy per reference volume
 *   psi = G / 2 (tr b - 3) - G ln J + lambda / 2 (ln J)^2,
 * kept as a history variable so that the energy increment is exact:
 * de_elastic = (psi - psi_old) / ((J_old + J) / 2). Lambda and G are the
 * small-strain Lame constants of E and nu.
 *
 * The stress follows from the deformation gradient alone (no rate form, no
 * Jaumann rotation), so a rigid rotation of any size leaves it unchanged as
 * long as F stays a rotation; the step's F <- (I + L dt) F does not quite:
 * it stretches a spinning body by sqrt(1 + (omega dt)^2) per step, which
 * test_material_hyperelastic checks. */
#include <math.h>

#include "core/tensor.h"
#include "material/elastoplastic.h"
#include "material/material.h"

enum { P_DENSITY, P_E, P_NU, P_COUNT };
enum { D_LAMBDA, D_SHEAR, D_BULK };
enum { S_PSI, S_COUNT };

static const mrn_spec params[P_COUNT] = {
    [P_DENSITY] = {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3", "mass density (reference)", NULL},
    [P_E] = {"E", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "Pa", "Young's modulus (small-strain)", NULL},
    [P_NU] = {"nu", MRN_SPEC_NUMBER, 0, 0.0, -1.0, 0.5, 1, 1, "", "Poisson's ratio (small-strain)", NULL},
};

static const char *const state_names[S_COUNT] = {"psi"};

static int prepare(mrn_material *m) {
  mrn_lame(m->param[P_E], m->param[P_NU], &m->derived[D_LAMBDA], &m->derived[D_SHEAR], &m->derived[D_BULK]);
  return 0;
}

static inline void update_point(const mrn_material *m, mrn_material_point *pt) {
  const double lambda = m->derived[D_LAMBDA], G = m->derived[D_SHEAR], J = pt->J;
  const double *F = pt->F;
  double b[6];
  for (int a = 0; a < 3; a++)
    for (int c = a; c < 3; c++)
      b[sym_index(a, c)] = F[3 * a] * F[3 * c] + F[3 * a + 1] * F[3 * c + 1] + F[3 * a + 2] * F[3 * c + 2];
  double lnJ = log(J);
  for (int k = 0; k < 6; k++) pt->stress[k] = G / J * (b[k] - (k < 3 ? 1.0 : 0.0)) + (k < 3 ? lambda * lnJ / J : 0.0);
  double psi = 0.5 * G * (sym_trace(b) - 3) - G * lnJ + 0.5 * lambda * lnJ * lnJ;
  double psi_old = pt->state ? pt->state[S_PSI] : 0.0;
  if (pt->state) pt->state[S_PSI] = psi;
  pt->de_elastic = (psi - psi_old) / (0.5 * (pt->J_old + J));
  pt->dw_plastic = 0.0;
}

MRN_MATERIAL_BATCH_UPDATE(update_point)

/* P-wave speed of the reference configuration */
const mrn_material_type mrn_material_neo_hookean = {
    .name = "neo_hookean",
    .summary = "compressible Neo-Hookean hyperelasticity, stress from b = F F^T (rotation-free)",
    .params = params,
    .nparams = P_COUNT,
    .nstate = S_COUNT,
    .state_names = state_names,
    .rate_form = 0,
    .prepare = prepare,
    .update = update,
    .wave_speed = mrn_material_isotropic_wave_speed,
};
