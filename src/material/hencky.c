/* moraine: Hencky hyperelasticity (logarithmic strain).
 *
 *   b = F F^T = sum_i l_i^2 n_i (x) n_i,   e = ln V = sum_i ln(l_i) n_i (x) n_i,
 *   tau = lambda tr(e) I + 2 G e,   sigma = tau / J,
 * the elastic part of the Hencky material of 001 (§2). Its stored energy per
 * reference volume, psi = e : D : e / 2 = lambda/2 tr(e)^2 + G e:e, is kept
 * as a history variable so that the energy increment is exact:
 * de_elastic = (psi - psi_old) / ((J_old + J) / 2). The eigenvectors of b
 * come from the Jacobi solver, exact to round-off also for b = I.
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
#include "material/principal.h"

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
  const double lambda = m->derived[D_LAMBDA], G = m->derived[D_SHEAR];
  double Ft[9], B[9], b[6], l2[3], V[9], e[3];
  for (int a = 0; a < 3; a++)
    for (int c = 0; c < 3; c++) Ft[3 * a + c] = pt->F[3 * c + a];
  mat_mul(pt->F, Ft, B);
  for (int a = 0; a < 3; a++)
    for (int c = a; c < 3; c++) b[sym_index(a, c)] = B[3 * a + c];
  mrn_sym_eigen(b, l2, V);
  for (int i = 0; i < 3; i++) e[i] = 0.5 * log(l2[i]);
  double tr = e[0] + e[1] + e[2], sig[3];
  for (int i = 0; i < 3; i++) sig[i] = (lambda * tr + 2 * G * e[i]) / pt->J;
  mrn_sym_from_principal(sig, V, pt->stress);
  double psi = 0.5 * lambda * tr * tr + G * (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  double psi_old = pt->state ? pt->state[S_PSI] : 0.0;
  if (pt->state) pt->state[S_PSI] = psi;
  pt->de_elastic = (psi - psi_old) / (0.5 * (pt->J_old + pt->J));
  pt->dw_plastic = 0.0;
}

MRN_MATERIAL_BATCH_UPDATE(update_point)

/* the implicit integrator's law is this one, with no plasticity */
static void implicit_law(const mrn_material *m, mrn_implicit_law *out) {
  out->lambda = m->derived[D_LAMBDA];
  out->G = m->derived[D_SHEAR];
  out->yield = 0.0;
  out->hardening = 0.0;
}

static const mrn_implicit_form implicit_form = {"Hencky elasticity (the same law as in explicit runs)", implicit_law};

/* P-wave speed of the reference configuration */
const mrn_material_type mrn_material_hencky = {
    .name = "hencky",
    .summary = "Hencky hyperelasticity, stress from the logarithmic strain ln V (rotation-free)",
    .params = params,
    .nparams = P_COUNT,
    .nstate = S_COUNT,
    .state_names = state_names,
    .rate_form = 0,
    .prepare = prepare,
    .update = update,
    .wave_speed = mrn_material_isotropic_wave_speed,
    .implicit = &implicit_form,
};
