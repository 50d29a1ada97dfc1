/* moraine: Mohr-Coulomb perfect plasticity with a tension cut-off.
 *
 * Hooke's law in rate form on the Jaumann-rotated stress (002, Eq. 28), the
 * Mohr-Coulomb criterion with a non-associated flow rule (dilatancy psi) and
 * a Rankine tension cut-off, as in 000 §5.1.3 (Table 2: the default cut-off
 * is c / tan(phi), the apex of the cone).
 *
 * Stresses are tension-positive. In principal stresses s1 >= s2 >= s3 the
 * criterion and the plastic potential are
 *   f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi) <= 0,
 *   g = (s1 - s3) + (s1 + s3) sin(psi),
 * written below divided by (1 - sin(phi)) as f = k s1 - s3 - sc with
 * k = (1 + sin phi) / (1 - sin phi), sc = 2 c cos(phi) / (1 - sin phi) the
 * unconfined compressive strength, and flow direction (m, 0, -1) with
 * m = (1 + sin psi) / (1 - sin psi).
 *
 * The return map works in the principal frame of the trial stress (isotropic
 * elasticity and an isotropic criterion keep that frame). Every yield plane
 * is linear and the flow directions constant, so the return onto any set of
 * active planes is one small linear solve, exact for perfect plasticity. The
 * possible returns (main plane, the two edges s1 = s2 and s2 = s3, the
 * tension plane s1 = T, its edges and corners, and the apex) are tried in
 * turn, as in the closed-form algorithms of de Souza Neto et al. and Clausen
 * et al.; the first one with non-negative multipliers, ordered principal
 * stresses and an admissible result is the return. */
#include <math.h>

#include "core/error.h"
#include "core/tensor.h"
#include "material/elastoplastic.h"
#include "material/material.h"
#include "material/principal.h"

enum { P_DENSITY, P_E, P_NU, P_PHI, P_PSI, P_COHESION, P_TENSION, P_COUNT };
enum { D_LAMBDA, D_SHEAR, D_BULK, D_K, D_M, D_SC, D_TENSION, D_REACH };
enum { S_EPS_P, S_EPS_V, S_COUNT };

static const double DEG = 3.14159265358979323846 / 180.0;

static const mrn_spec params[P_COUNT] = {
    [P_DENSITY] = {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3", "mass density", NULL},
    [P_E] = {"E", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "Pa", "Young's modulus", NULL},
    [P_NU] = {"nu", MRN_SPEC_NUMBER, 0, 0.0, -1.0, 0.5, 1, 1, "", "Poisson's ratio", NULL},
    [P_PHI] = {"phi", MRN_SPEC_NUMBER, 1, 0, 0, 90, 0, 1, "deg", "friction angle", NULL},
    [P_PSI] = {"psi", MRN_SPEC_NUMBER, 0, 0.0, 0, 90, 0, 1, "deg", "dilatancy angle (at most phi)", NULL},
    [P_COHESION] = {"cohesion", MRN_SPEC_NUMBER, 0, 0.0, 0, HUGE_VAL, 0, 0, "Pa", "cohesion c", NULL},
    [P_TENSION] = {"tension", MRN_SPEC_NUMBER, 0, -1.0, -HUGE_VAL, HUGE_VAL, 0, 0, "Pa",
                   "tension cut-off on the largest principal stress; negative: c / tan(phi), the apex", NULL},
};

static const char *const state_names[S_COUNT] = {"eps_p", "eps_pv"};

static int prepare(mrn_material *m) {
  double *d = m->derived;
  double phi = m->param[P_PHI] * DEG, psi = m->param[P_PSI] * DEG, c = m->param[P_COHESION];
  if (m->param[P_PSI] > m->param[P_PHI])
    return mrn_error("material mohr_coulomb: psi = %g deg exceeds phi = %g deg (the flow would create energy)",
                     m->param[P_PSI], m->param[P_PHI]);
  if (phi == 0.0 && c == 0.0) return mrn_error("material mohr_coulomb: phi = 0 and cohesion = 0 leave no strength");
  mrn_lame(m->param[P_E], m->param[P_NU], &d[D_LAMBDA], &d[D_SHEAR], &d[D_BULK]);
  d[D_K] = (1 + sin(phi)) / (1 - sin(phi));
  d[D_M] = (1 + sin(psi)) / (1 - sin(psi));
  d[D_SC] = 2 * c * cos(phi) / (1 - sin(phi));
  /* the apex c / tan(phi); a cut-off above it never acts */
  double apex = phi > 0.0 ? c / tan(phi) : HUGE_VAL;
  double t = m->param[P_TENSION];
  d[D_TENSION] = t < 0.0 || t > apex ? apex : t;
  d[D_REACH] = 2.0 / sqrt(3.0) * sqrt(d[D_K] * d[D_K] + d[D_K] + 1.0); /* see surely_elastic */
  return MRN_OK;
}

/* A yield plane a . s <= r with flow direction b, in ordered principal stresses. */
typedef struct {
  double a[3], b[3], r;
} plane;

enum { PM, PA, PB, PT1, PT2, PT3, NPLANES };

/* Candidate active sets, in the order they are tried. PA and PB are the
 * main plane of the neighbouring sextants: active with PM they pin the
 * edges s1 = s2 (triaxial compression) and s2 = s3 (triaxial extension). The
 * corner s1 = s2 = T, s3 = kT - sc has four active planes; any three of
 * them span its cone of flow directions, so all four triples are tried. */
static const struct {
  int n, id[3];
} candidates[] = {
    {1, {PM}},          {1, {PT1}},          {2, {PM, PA}},       {2, {PM, PB}},        {2, {PM, PT1}},
    {2, {PT1, PT2}},    {3, {PM, PB, PT1}},  {3, {PM, PA, PT1}},  {3, {PM, PA, PT2}},   {3, {PM, PT1, PT2}},
    {3, {PA, PT1, PT2}}, {3, {PT1, PT2, PT3}},
};
enum { NCANDIDATES = sizeof candidates / sizeof candidates[0] };

static void make_planes(const mrn_material *m, plane pl[NPLANES]) {
  const double k = m->derived[D_K], mm = m->derived[D_M], sc = m->derived[D_SC], T = m->derived[D_TENSION];
  pl[PM] = (plane){{k, 0, -1}, {mm, 0, -1}, sc};
  pl[PA] = (plane){{0, k, -1}, {0, mm, -1}, sc};
  pl[PB] = (plane){{k, -1, 0}, {mm, -1, 0}, sc};
  pl[PT1] = (plane){{1, 0, 0}, {1, 0, 0}, T};
  pl[PT2] = (plane){{0, 1, 0}, {0, 1, 0}, T};
  pl[PT3] = (plane){{0, 0, 1}, {0, 0, 1}, T};
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Gaussian elimination with partial pivoting, n <= 3; 0 when singular */
static int solve(int n, double A[3][3], double r[3], double x[3]) {
  for (int c = 0; c < n; c++) {
    int p = c;
    for (int i = c + 1; i < n; i++)
      if (fabs(A[i][c]) > fabs(A[p][c])) p = i;
    if (!(fabs(A[p][c]) > 1e-14)) return 0;
    for (int j = 0; j < n; j++) {
      double t = A[c][j];
      A[c][j] = A[p][j];
      A[p][j] = t;
    }
    double t = r[c];
    r[c] = r[p];
    r[p] = t;
    for (int i = c + 1; i < n; i++) {
      double f = A[i][c] / A[c][c];
      for (int j = c; j < n; j++) A[i][j] -= f * A[c][j];
      r[i] -= f * r[c];
    }
  }
  for (int i = n - 1; i >= 0; i--) {
    double s = r[i];
    for (int j = i + 1; j < n; j++) s -= A[i][j] * x[j];
    x[i] = s / A[i][i];
  }
  return 1;
}

/* Return of the trial principal stresses `tr` onto the active set `c`:
 * s = tr - sum_j dl_j D b_j with a_i . s = r_i for every active plane.
 * Returns 1 and the stresses in `out` when the return is admissible. */
static int try_return(const mrn_material *m, const plane pl[NPLANES], int c, const double tr[3], double tol,
                      double out[3]) {
  const double lambda = m->derived[D_LAMBDA], G = m->derived[D_SHEAR];
  const int n = candidates[c].n;
  const int *id = candidates[c].id;
  const int tension = isfinite(m->derived[D_TENSION]);
  double Db[3][3], A[3][3], r[3], dl[3];
  for (int j = 0; j < n; j++) {
    const double *b = pl[id[j]].b;
    double tb = b[0] + b[1] + b[2];
    for (int q = 0; q < 3; q++) Db[j][q] = lambda * tb + 2 * G * b[q];
    if (!tension && id[j] >= PT1) return 0;
  }
  /* scaled by 1/(2G) so that the pivot threshold is dimensionless */
  for (int i = 0; i < n; i++) {
    r[i] = (dot3(pl[id[i]].a, tr) - pl[id[i]].r) / (2 * G);
    for (int j = 0; j < n; j++) A[i][j] = dot3(pl[id[i]].a, Db[j]) / (2 * G);
  }
  if (!solve(n, A, r, dl)) return 0;
  for (int j = 0; j < n; j++)
    if (dl[j] * 2 * G < -tol) return 0;
  for (int q = 0; q < 3; q++) {
    out[q] = tr[q];
    for (int j = 0; j < n; j++) out[q] -= dl[j] * Db[j][q];
  }
  if (out[0] < out[1] - tol || out[1] < out[2] - tol) return 0;
  if (dot3(pl[PM].a, out) - pl[PM].r > tol * (1 + pl[PM].a[0])) return 0;
  if (tension && out[0] - pl[PT1].r > tol) return 0;
  return 1;
}

/* Principal-stress return map; returns 0 when the trial is admissible. */
static int return_map(const mrn_material *m, double s[3]) {
  const double T = m->derived[D_TENSION];
  int tension = isfinite(T);
  /* the main plane PM, k s1 - s3 <= sc, tested before the planes are built:
   * most points of a flow are inside */
  if (m->derived[D_K] * s[0] - s[2] - m->derived[D_SC] <= 0.0 && (!tension || s[0] <= T)) return 0;
  plane pl[NPLANES];
  make_planes(m, pl);
  double scale = fmax(fmax(fabs(s[0]), fabs(s[2])), m->derived[D_SC]);
  if (tension) scale = fmax(scale, fabs(T));
  const double tol = 1e-12 * scale;
  double out[3];
  for (int c = 0; c < NCANDIDATES; c++)
    if (try_return(m, pl, c, s, tol, out)) {
      for (int q = 0; q < 3; q++) s[q] = out[q];
      return 1;
    }
  /* the apex, where the tension corner meets the cone (or the cut-off apex);
   * Tresca (phi = 0) has none, and its hydrostatic axis is always admissible */
  double apex = tension ? T : (s[0] + s[1] + s[2]) / 3.0;
  for (int q = 0; q < 3; q++) s[q] = apex;
  return 1;
}

/* A sufficient condition for an elastic trial stress s, without its
 * principal values. With p the mean stress and r = sqrt(J2), the principal
 * values are p + (2/sqrt 3) r cos(theta - 2 pi i / 3), i = 0, 1, 2, for a
 * Lode angle theta, so that for any theta
 *   k s1 - s3 <= (k - 1) p + (2/sqrt 3) sqrt(k^2 + k + 1) r   (the amplitude
 *   of (k + 1/2) cos theta + (sqrt 3 / 2) sin theta), and
 *   s1 <= p + (2/sqrt 3) r.
 * When both bounds clear the main plane and the cut-off by a margin of 1e-10
 * of the stress scale, far above the round-off of the eigenvalues, the test
 * of return_map on the principal stresses passes as well: the result is the
 * one of the full path, without the eigen-decomposition (most points of a
 * flow are elastic at any step). The bounds are compared squared (r^2 =
 * J2, no square root); the scale takes the sum of the deviatoric and shear
 * magnitudes, which is >= r. */
static inline int surely_elastic(const mrn_material *m, const double s[6]) {
  const double k = m->derived[D_K], T = m->derived[D_TENSION], sc = m->derived[D_SC];
  const double p = (s[SXX] + s[SYY] + s[SZZ]) * (1.0 / 3.0);
  const double dx = s[SXX] - p, dy = s[SYY] - p, dz = s[SZZ] - p;
  const double J2 = 0.5 * (dx * dx + dy * dy + dz * dz) + s[SXY] * s[SXY] + s[SYZ] * s[SYZ] + s[SXZ] * s[SXZ];
  const double rbound = fabs(dx) + fabs(dy) + fabs(dz) + fabs(s[SXY]) + fabs(s[SYZ]) + fabs(s[SXZ]);
  const int tension = isfinite(T);
  const double margin = 1e-10 * ((k + 1.0) * (fabs(p) + 2.0 * rbound) + sc + (tension ? fabs(T) : 0.0));
  const double room = sc - (k - 1.0) * p - margin, reach = m->derived[D_REACH];
  if (!(room >= 0.0 && reach * reach * J2 <= room * room)) return 0;
  const double room_t = T - margin - p;
  return !tension || (room_t >= 0.0 && (4.0 / 3.0) * J2 <= room_t * room_t);
}

/* the trial stress outside the elastic region surely_elastic proves: the
 * principal-stress return (kept out of line: the elastic path is the common
 * one and stays small enough to inline in the batch loop) */
static __attribute__((noinline)) void update_general(const mrn_material *m, mrn_material_point *pt,
                                                     const double old[6], const double trial[6]) {
  double lam[3], V[9];
  mrn_sym_eigen(trial, lam, V);
  int plastic = return_map(m, lam);
  /* an elastic step keeps the trial tensor itself, not its re-assembly */
  if (plastic)
    mrn_sym_from_principal(lam, V, pt->stress);
  else
    for (int k = 0; k < 6; k++) pt->stress[k] = trial[k];
  double dp[6];
  mrn_energy_split(m->param[P_E], m->param[P_NU], old, pt->stress, pt->dstrain, plastic, pt, dp);
  if (plastic && pt->state) {
    pt->state[S_EPS_P] += mrn_equivalent_strain(dp);
    pt->state[S_EPS_V] += sym_trace(dp);
  }
}

static inline void update_point(const mrn_material *m, mrn_material_point *pt) {
  double old[6], trial[6], ds[6];
  for (int k = 0; k < 6; k++) old[k] = pt->stress[k];
  mrn_hooke_increment(m->derived[D_LAMBDA], m->derived[D_SHEAR], pt->dstrain, ds);
  for (int k = 0; k < 6; k++) trial[k] = old[k] + ds[k];
  if (!surely_elastic(m, trial)) {
    update_general(m, pt, old, trial);
    return;
  }
  for (int k = 0; k < 6; k++) pt->stress[k] = trial[k];
  mrn_energy_split(m->param[P_E], m->param[P_NU], old, pt->stress, pt->dstrain, 0, pt, NULL);
}

MRN_MATERIAL_BATCH_UPDATE(update_point)

const mrn_material_type mrn_material_mohr_coulomb = {
    .name = "mohr_coulomb",
    .summary = "Mohr-Coulomb perfect plasticity, non-associated, with tension cut-off (000 §5.1.3)",
    .params = params,
    .nparams = P_COUNT,
    .nstate = S_COUNT,
    .state_names = state_names,
    .rate_form = 1,
    .prepare = prepare,
    .update = update,
    .wave_speed = mrn_material_isotropic_wave_speed,
};
