/* moraine: Drucker-Prager perfect plasticity, non-associated.
 *
 * Hooke's law in rate form on the Jaumann-rotated stress (002, Eq. 28) with
 * (tension positive, I1 = tr sigma, J2 = s:s / 2)
 *   f = sqrt(J2) + alpha I1 - kappa <= 0      (002, Eq. 71)
 *   g = sqrt(J2) + beta I1                    (002, Eq. 73)
 * The cone is fitted to Mohr-Coulomb's phi, psi and c by `plane_strain_match`:
 *   0: through the triaxial-compression corners of Mohr-Coulomb (outer cone);
 *   1: the plane-strain match of 002 (Eqs. 72, 74). It reproduces the
 *      Mohr-Coulomb plane-strain strength exactly for associated flow
 *      (psi = phi) only;
 *   2: the plane-strain match for the actual flow rule. At plane-strain
 *      collapse the out-of-plane plastic strain vanishes, which with g gives
 *      s_zz = -2 beta sqrt(J2); the in-plane radius t = (s1 - s3) / 2 and
 *      centre s_m then obey t = sqrt(1 - 3 beta^2) / (1 - 3 alpha beta)
 *      (kappa - 3 alpha s_m), and equating this with Mohr-Coulomb's
 *      t = c cos(phi) - s_m sin(phi) gives
 *        alpha = sin(phi) / (3 (sqrt(1 - 3 beta^2) + beta sin(phi))),
 *        kappa = c cos(phi) (1 - 3 alpha beta) / sqrt(1 - 3 beta^2),
 *      with beta from Eq. 74. For psi = phi this is Eq. 72 again.
 *
 * The return is radial in the deviatoric plane (cone) unless it would cross
 * the hydrostatic axis, in which case the stress goes to the apex
 * I1 = kappa / alpha (de Souza Neto et al., Box 8.9). */
#include <math.h>

#include "core/error.h"
#include "core/tensor.h"
#include "material/elastoplastic.h"
#include "material/material.h"

enum { P_DENSITY, P_E, P_NU, P_PHI, P_PSI, P_COHESION, P_MATCH, P_COUNT };
enum { D_LAMBDA, D_SHEAR, D_BULK, D_ALPHA, D_KAPPA, D_BETA };
enum { S_EPS_P, S_EPS_V, S_COUNT };

static const double DEG = 3.14159265358979323846 / 180.0;

static const mrn_spec params[P_COUNT] = {
    [P_DENSITY] = {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3", "mass density", NULL},
    [P_E] = {"E", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "Pa", "Young's modulus", NULL},
    [P_NU] = {"nu", MRN_SPEC_NUMBER, 0, 0.0, -1.0, 0.5, 1, 1, "", "Poisson's ratio", NULL},
    [P_PHI] = {"phi", MRN_SPEC_NUMBER, 1, 0, 0, 90, 0, 1, "deg", "friction angle", NULL},
    [P_PSI] = {"psi", MRN_SPEC_NUMBER, 0, 0.0, 0, 90, 0, 1, "deg", "dilatancy angle (at most phi)", NULL},
    [P_COHESION] = {"cohesion", MRN_SPEC_NUMBER, 0, 0.0, 0, HUGE_VAL, 0, 0, "Pa", "cohesion c", NULL},
    [P_MATCH] = {"plane_strain_match", MRN_SPEC_INTEGER, 0, 1, 0, 2, 0, 0, "",
                 "cone fit to Mohr-Coulomb: 0 triaxial compression, 1 plane strain (002 Eq. 72), "
                 "2 plane strain for the flow rule psi",
                 NULL},
};

static const char *const state_names[S_COUNT] = {"eps_p", "eps_pv"};

/* 002, Eqs. 72 and 74 share this form */
static double plane_strain_slope(double angle) { return tan(angle) / sqrt(9 + 12 * tan(angle) * tan(angle)); }

static int prepare(mrn_material *m) {
  double *d = m->derived;
  double phi = m->param[P_PHI] * DEG, psi = m->param[P_PSI] * DEG, c = m->param[P_COHESION];
  double match = m->param[P_MATCH];
  if (match != floor(match))
    return mrn_error("material drucker_prager: plane_strain_match = %g must be 0, 1 or 2", match);
  if (m->param[P_PSI] > m->param[P_PHI])
    return mrn_error("material drucker_prager: psi = %g deg exceeds phi = %g deg (the flow would create energy)",
                     m->param[P_PSI], m->param[P_PHI]);
  if (phi == 0.0 && c == 0.0) return mrn_error("material drucker_prager: phi = 0 and cohesion = 0 leave no strength");
  mrn_lame(m->param[P_E], m->param[P_NU], &d[D_LAMBDA], &d[D_SHEAR], &d[D_BULK]);
  if (match == 0) {
    double r3 = sqrt(3.0);
    d[D_ALPHA] = 2 * sin(phi) / (r3 * (3 - sin(phi)));
    d[D_KAPPA] = 6 * c * cos(phi) / (r3 * (3 - sin(phi)));
    d[D_BETA] = 2 * sin(psi) / (r3 * (3 - sin(psi)));
  } else if (match == 1) {
    d[D_ALPHA] = plane_strain_slope(phi);                                /* (002, Eq. 72) */
    d[D_KAPPA] = 3 * c / sqrt(9 + 12 * tan(phi) * tan(phi));            /* (002, Eq. 72) */
    d[D_BETA] = plane_strain_slope(psi);                                 /* (002, Eq. 74) */
  } else {
    double beta = plane_strain_slope(psi), root = sqrt(1 - 3 * beta * beta);
    d[D_BETA] = beta;
    d[D_ALPHA] = sin(phi) / (3 * (root + beta * sin(phi)));
    d[D_KAPPA] = c * cos(phi) * (1 - 3 * d[D_ALPHA] * beta) / root;
  }
  return MRN_OK;
}

static inline void update_point(const mrn_material *m, mrn_material_point *pt) {
  const double *d = m->derived;
  const double G = d[D_SHEAR], K = d[D_BULK], alpha = d[D_ALPHA], kappa = d[D_KAPPA], beta = d[D_BETA];
  double old[6], trial[6], ds[6], s[6];
  for (int k = 0; k < 6; k++) old[k] = pt->stress[k];
  mrn_hooke_increment(d[D_LAMBDA], G, pt->dstrain, ds);
  for (int k = 0; k < 6; k++) trial[k] = old[k] + ds[k];
  sym_dev(trial, s);
  double rj2 = sqrt(0.5 * sym_ddot(s, s)), I1 = sym_trace(trial);
  double f = rj2 + alpha * I1 - kappa;
  int plastic = f > 0.0;
  if (!plastic) {
    for (int k = 0; k < 6; k++) pt->stress[k] = trial[k];
  } else {
    /* cone: sqrt(J2) drops by G dl and I1 by 9 K beta dl */
    double dl = f / (G + 9 * K * alpha * beta);
    if (rj2 - G * dl >= 0.0) {
      double scale = rj2 > 0.0 ? 1 - G * dl / rj2 : 0.0;
      double mean = (I1 - 9 * K * beta * dl) / 3.0;
      for (int k = 0; k < 6; k++) pt->stress[k] = scale * s[k] + (k < 3 ? mean : 0.0);
    } else {
      /* apex (alpha > 0 here: with alpha = 0, G dl = f <= sqrt(J2)) */
      double mean = kappa / (3 * alpha);
      for (int k = 0; k < 6; k++) pt->stress[k] = k < 3 ? mean : 0.0;
    }
  }
  double dp[6];
  mrn_energy_split(m->param[P_E], m->param[P_NU], old, pt->stress, pt->dstrain, plastic, pt, dp);
  if (plastic && pt->state) {
    pt->state[S_EPS_P] += mrn_equivalent_strain(dp);
    pt->state[S_EPS_V] += sym_trace(dp);
  }
}

MRN_MATERIAL_BATCH_UPDATE(update_point)

const mrn_material_type mrn_material_drucker_prager = {
    .name = "drucker_prager",
    .summary = "Drucker-Prager perfect plasticity, non-associated, fitted to Mohr-Coulomb (002, Eqs. 71-74)",
    .params = params,
    .nparams = P_COUNT,
    .nstate = S_COUNT,
    .state_names = state_names,
    .rate_form = 1,
    .prepare = prepare,
    .update = update,
    .wave_speed = mrn_material_isotropic_wave_speed,
};
