/* moraine: Modified Cam-Clay (Roscoe and Burland 1968), small strain, in
 * rate form.
 *
 * Stresses are tension-positive; the effective mean pressure is
 * p = -tr(sigma) / 3 (compression positive) and q = sqrt(3/2 s:s) the
 * deviatoric stress. Volumes: v the specific volume (1 + void ratio),
 * v = v0 J.
 *   elasticity: K = v p / kappa (the swelling line dv = -kappa dp / p),
 *               G = 3 K (1 - 2 nu) / (2 (1 + nu)); K and G are taken at the
 *               start of the step, with p floored at p_min so that a
 *               stress-free point has a stiffness;
 *   yield:      f = q^2 / M^2 + p (p - p_c) <= 0 (an ellipse through the
 *               origin and p_c, its top on the critical-state line q = M p);
 *   flow:       associated, de_p = dlambda df/dsigma: the plastic volumetric
 *               strain (compression positive) is dlambda (2 p - p_c) and the
 *               plastic shear strain dlambda 2 q / M^2;
 *   hardening:  dp_c / p_c = v / (lambda - kappa) deps_v^p (the normal
 *               compression line dv = -lambda dp / p on isotropic loading).
 * Return mapping (closest point in the energy norm, backward Euler, as in
 * Borja and Lee 1990, Comput. Methods Appl. Mech. Engrg. 78, Eqs. 3.10-3.16,
 * with the elastic moduli held over the step): from the elastic trial
 * (p*, q*, s*), for a multiplier dlambda >= 0
 *   p   = p* - K dlambda (2 p - p_c),          eps_v^p = (p* - p) / K,
 *   p_c = p_c,n exp(theta eps_v^p),            theta = v / (lambda - kappa),
 *   q   = q* / (1 + 6 G dlambda / M^2),        s = s* q / q*,
 * the first two solved for p by Newton's method, and dlambda by a
 * bracketed secant (Illinois) iteration on f(dlambda) = 0, which is
 * positive at 0 and negative for large dlambda.
 * History: log_pc = ln(p_c / p_c0), log_v = ln(v / v0), eps_pv (plastic
 * volumetric strain, compression positive); all start at 0. */
#include <math.h>

#include "core/error.h"
#include "core/tensor.h"
#include "material/elastoplastic.h"
#include "material/material.h"

enum { P_DENSITY, P_M, P_LAMBDA, P_KAPPA, P_NU, P_V0, P_PC0, P_PMIN, P_COUNT };
enum { S_LOG_PC, S_LOG_V, S_EPS_PV, S_COUNT };

static const mrn_spec params[P_COUNT] = {
    [P_DENSITY] = {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3", "mass density", NULL},
    [P_M] = {"M", MRN_SPEC_NUMBER, 1, 0, 0, 3, 1, 1, "", "slope of the critical-state line q = M p'", NULL},
    [P_LAMBDA] = {"lambda", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "",
                  "slope of the normal compression line in v - ln p'", NULL},
    [P_KAPPA] = {"kappa", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "",
                 "slope of the swelling line in v - ln p', < lambda", NULL},
    [P_NU] = {"nu", MRN_SPEC_NUMBER, 0, 0.3, -1.0, 0.5, 1, 1, "", "Poisson's ratio of the elastic response", NULL},
    [P_V0] = {"v0", MRN_SPEC_NUMBER, 1, 0, 1, HUGE_VAL, 0, 0, "", "initial specific volume v = 1 + e", NULL},
    [P_PC0] = {"p_c0", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "Pa", "initial preconsolidation pressure", NULL},
    [P_PMIN] = {"p_min", MRN_SPEC_NUMBER, 0, 1000, 0, HUGE_VAL, 1, 0, "Pa",
                "floor on p' in the elastic moduli (a stress-free point keeps a stiffness)", NULL},
};

static const char *const state_names[S_COUNT] = {"log_pc", "log_v", "eps_pv"};

static int prepare(mrn_material *m) {
  if (!(m->param[P_KAPPA] < m->param[P_LAMBDA]))
    return mrn_error("material cam_clay: kappa = %g must be below lambda = %g (no plastic hardening otherwise)",
                     m->param[P_KAPPA], m->param[P_LAMBDA]);
  return MRN_OK;
}

/* the elastic moduli at specific volume v and pressure p */
static void moduli(const mrn_material *m, double v, double p, double *K, double *G) {
  const double nu = m->param[P_NU];
  *K = v * fmax(p, m->param[P_PMIN]) / m->param[P_KAPPA];
  *G = 3.0 * *K * (1.0 - 2.0 * nu) / (2.0 * (1.0 + nu));
}

/* what a return with multiplier dl gives */
typedef struct mcc_return {
  double p_trial, q_trial, pc_n, K, G, theta, M2;
  double p, pc, q; /* out */
} mcc_return;

/* p (and p_c) for the multiplier dl: p - p* + K dl (2 p - p_c(p)) = 0, whose
 * left side rises with p and is concave: Newton's method from p* converges,
 * monotonically after at most one step past the root */
static void solve_p(mcc_return *r, double dl) {
  double p = r->p_trial;
  for (int it = 0; it < 50; it++) {
    const double pc = r->pc_n * exp(r->theta * (r->p_trial - p) / r->K);
    const double res = p - r->p_trial + r->K * dl * (2.0 * p - pc);
    const double slope = 1.0 + 2.0 * r->K * dl + dl * r->theta * pc;
    const double step = res / slope;
    p -= step;
    if (fabs(step) <= 1e-15 * fabs(p)) break;
  }
  r->p = p;
  r->pc = r->pc_n * exp(r->theta * (r->p_trial - p) / r->K);
  r->q = r->q_trial / (1.0 + 6.0 * r->G * dl / r->M2);
}

static double yield_at(mcc_return *r, double dl) {
  solve_p(r, dl);
  return r->q * r->q / r->M2 + r->p * (r->p - r->pc);
}

/* dlambda by the Illinois variant of regula falsi on [0, hi]; r holds the
 * return of the root on exit */
static void solve_multiplier(mcc_return *r, double f0, double scale) {
  double lo = 0.0, flo = f0, hi = scale, fhi = yield_at(r, hi);
  for (int k = 0; k < 200 && fhi > 0.0; k++) {
    lo = hi, flo = fhi;
    hi *= 4.0;
    fhi = yield_at(r, hi);
  }
  int side = 0;
  for (int it = 0; it < 200; it++) {
    const double x = (lo * fhi - hi * flo) / (fhi - flo);
    const double fx = yield_at(r, x);
    if (fabs(fx) <= 1e-13 * r->pc * r->pc || hi - lo <= 1e-15 * hi) return;
    if ((fx > 0.0) == (flo > 0.0)) {
      lo = x, flo = fx;
      if (side == -1) fhi *= 0.5;
      side = -1;
    } else {
      hi = x, fhi = fx;
      if (side == 1) flo *= 0.5;
      side = 1;
    }
  }
}

static inline void update_point(const mrn_material *m, mrn_material_point *pt) {
  double *st = pt->state;
  const double v = m->param[P_V0] * exp(st[S_LOG_V]), pc_n = m->param[P_PC0] * exp(st[S_LOG_PC]);
  double old[6], s[6], dev[6], K, G;
  for (int k = 0; k < 6; k++) old[k] = s[k] = pt->stress[k];
  moduli(m, v, -sym_trace(old) / 3.0, &K, &G);
  mrn_hooke_update(K - 2.0 * G / 3.0, G, pt->dstrain, s);
  mcc_return r = {.p_trial = -sym_trace(s) / 3.0, .pc_n = pc_n, .K = K, .G = G,
                  .theta = v / (m->param[P_LAMBDA] - m->param[P_KAPPA]), .M2 = m->param[P_M] * m->param[P_M]};
  sym_dev(s, dev);
  r.q_trial = sqrt(1.5 * sym_ddot(dev, dev));
  const double f0 = r.q_trial * r.q_trial / r.M2 + r.p_trial * (r.p_trial - pc_n);
  const int plastic = f0 > 0.0;
  if (plastic) {
    /* the multiplier's scale: a plastic strain of the size of the increment,
     * plus f0 over the size of df/ddlambda, ~ (K + G) p_c^2 (a trial state
     * outside the surface without an increment) */
    const double scale = sqrt(sym_ddot(pt->dstrain, pt->dstrain)) / pc_n + f0 / ((K + G) * pc_n * pc_n);
    solve_multiplier(&r, f0, scale);
    const double ratio = r.q_trial > 0.0 ? r.q / r.q_trial : 0.0;
    for (int k = 0; k < 6; k++) s[k] = ratio * dev[k] + (k < 3 ? -r.p : 0.0);
    const double eps_pv = (r.p_trial - r.p) / K;
    st[S_LOG_PC] += r.theta * eps_pv;
    st[S_EPS_PV] += eps_pv;
  }
  st[S_LOG_V] += log(pt->J / pt->J_old);
  for (int k = 0; k < 6; k++) pt->stress[k] = s[k];
  const double nu = m->param[P_NU];
  mrn_energy_split(3.0 * K * (1.0 - 2.0 * nu), nu, old, s, pt->dstrain, plastic, pt, NULL);
}

MRN_MATERIAL_BATCH_UPDATE(update_point)

/* the P-wave speed at p' = p_c0 (the moduli grow with p') */
static double wave_speed(const mrn_material *m) {
  double K, G;
  moduli(m, m->param[P_V0], m->param[P_PC0], &K, &G);
  return sqrt((K + 4.0 * G / 3.0) / m->param[P_DENSITY]);
}

const mrn_material_type mrn_material_cam_clay = {
    .name = "cam_clay",
    .summary = "Modified Cam-Clay (Roscoe and Burland 1968): pressure-dependent elasticity, elliptic yield, "
               "associated flow, volumetric hardening",
    .params = params,
    .nparams = P_COUNT,
    .nstate = S_COUNT,
    .state_names = state_names,
    .rate_form = 1,
    .prepare = prepare,
    .update = update,
    .wave_speed = wave_speed,
};
