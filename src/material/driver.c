#include "material/driver.h"

#include <math.h>
#include <string.h>

#include "core/error.h"
#include "core/tensor.h"
#include "material/advance.h"
#include "material/principal.h"
#include "material/user.h"

int mrn_driver_init(mrn_driver *d, const mrn_material *m, const double stress0[6]) {
  memset(d, 0, sizeof *d);
  if (m->type->nstate > MRN_DRIVER_MAX_STATE)
    return mrn_error("driver: material %s has %d history variables, more than %d", m->type->name, m->type->nstate,
                     MRN_DRIVER_MAX_STATE);
  d->mat = m;
  mat_identity(d->F);
  if (stress0) memcpy(d->stress, stress0, sizeof d->stress);
  return MRN_OK;
}

/* One step on d itself, through the same mrn_material_advance_points as the step,
 * for a single particle of unit reference volume. */
static int advance(mrn_driver *d, const double L[9], double dt) {
  static const double unit_volume = 1.0;
  const mrn_energy_sums energy = {&unit_volume, &d->e_elastic, &d->w_plastic};
  mrn_point_result r;
  mrn_f_update kind = d->kinematics == MRN_DRIVER_F_MIDPOINT ? MRN_F_UPDATE_MIDPOINT : MRN_F_UPDATE_EULER;
  long bad = mrn_material_advance_points(d->mat, 3, kind, dt, 1, L, d->F, d->stress, d->strain,
                                         d->mat->type->nstate ? d->state : NULL, 0, &energy, &r);
  int failed = mrn_material_user_failure(d->mat);
  if (failed) return failed;
  if (bad >= 0) return mrn_error("driver: the increment would invert F at t = %g s", d->time + dt);
  d->de_elastic = r.de_elastic;
  d->dw_plastic = r.dw_plastic;
  d->time += dt;
  return MRN_OK;
}

int mrn_driver_step(mrn_driver *d, const double L[9], double dt) { return advance(d, L, dt); }

/* row and column of the symmetric component k */
static const int comp_a[6] = {0, 1, 2, 0, 1, 0}, comp_b[6] = {0, 1, 2, 1, 2, 2};

/* set the symmetric part of component k of L to v, keeping its spin */
static void set_sym(double L[9], int k, double v) {
  int a = comp_a[k], b = comp_b[k];
  double w = 0.5 * (L[3 * a + b] - L[3 * b + a]);
  L[3 * a + b] = v + w;
  L[3 * b + a] = v - w;
}

static double get_sym(const double L[9], int k) {
  int a = comp_a[k], b = comp_b[k];
  return 0.5 * (L[3 * a + b] + L[3 * b + a]);
}

/* the stress after a trial step from d with the free components set to x */
static int trial_stress(const mrn_driver *d, const double L[9], const int *free_, int n, const double *x, double dt,
                        mrn_driver *out) {
  double Lt[9];
  memcpy(Lt, L, sizeof Lt);
  for (int i = 0; i < n; i++) set_sym(Lt, free_[i], x[i]);
  *out = *d;
  return advance(out, Lt, dt);
}

static double residual(const mrn_driver *t, const int *free_, int n, const double target[6], double r[6]) {
  double worst = 0.0;
  for (int i = 0; i < n; i++) {
    r[i] = t->stress[free_[i]] - target[free_[i]];
    worst = fmax(worst, fabs(r[i]));
  }
  return worst;
}

int mrn_driver_step_mixed(mrn_driver *d, const double L[9], const int stress_ctrl[6], const double target[6],
                          double dt) {
  int free_[6], n = 0;
  for (int k = 0; k < 6; k++)
    if (stress_ctrl[k]) free_[n++] = k;
  d->iterations = 0;
  if (n == 0) return advance(d, L, dt);

  /* scales: stresses, and the strain-rate perturbation that changes them by
   * about 1e-7 of that through the elastic stiffness */
  const double E = mrn_material_young(d->mat);
  double S = 0.0, rate = 0.0;
  for (int k = 0; k < 6; k++) {
    S = fmax(S, fabs(d->stress[k]));
    if (stress_ctrl[k]) S = fmax(S, fabs(target[k]));
    rate = fmax(rate, fabs(get_sym(L, k)));
  }
  S = fmax(S, E * rate * dt);
  if (!(S > 0.0)) S = 1e-12 * E;
  const double tol = 1e-12 * S, h = 1e-7 * S / (E * dt);

  double x[6], xn[6], r[6], jac[36], dx[6];
  for (int i = 0; i < n; i++) x[i] = get_sym(L, free_[i]);
  mrn_driver t, tn, tp, tm;
  int rc; /* a trial's error (a user material's law fails with its own code) */
  if ((rc = trial_stress(d, L, free_, n, x, dt, &t))) return rc;
  double worst = residual(&t, free_, n, target, r);
  for (int it = 0; it < 60; it++) {
    if (worst <= tol) {
      *d = t;
      d->iterations = it;
      return MRN_OK;
    }
    /* central differences: exact inside one regime of a piecewise-linear
     * (perfectly plastic) response, an average across a corner */
    for (int j = 0; j < n; j++) {
      double xj = x[j];
      x[j] = xj + h;
      if ((rc = trial_stress(d, L, free_, n, x, dt, &tp))) return rc;
      x[j] = xj - h;
      if ((rc = trial_stress(d, L, free_, n, x, dt, &tm))) return rc;
      x[j] = xj;
      for (int i = 0; i < n; i++) jac[n * i + j] = (tp.stress[free_[i]] - tm.stress[free_[i]]) / (2 * h);
    }
    /* pseudo-inverse: on a Mohr-Coulomb edge the lateral stresses of a
     * triaxial test move together and the tangent is singular */
    mrn_pinv_solve(n, jac, r, 1e-9, dx);
    /* backtracking: a full step can jump across a corner of the yield
     * surface and back forever; halve it until the residual drops */
    double rn[6], worst_n = HUGE_VAL;
    for (double step = 1.0; step > 1e-12; step *= 0.5) {
      for (int i = 0; i < n; i++) xn[i] = x[i] - step * dx[i];
      if ((rc = trial_stress(d, L, free_, n, xn, dt, &tn))) return rc;
      worst_n = residual(&tn, free_, n, target, rn);
      if (worst_n < worst) break;
    }
    if (!(worst_n < worst)) break;
    memcpy(x, xn, sizeof x);
    memcpy(r, rn, sizeof r);
    t = tn;
    worst = worst_n;
  }
  return mrn_error("driver: mixed step at t = %g s did not converge (material %s, residual %g Pa)", d->time,
                   d->mat->type->name, worst);
}

int mrn_driver_strain(mrn_driver *d, const double deps[6], double dt) {
  double L[9];
  sym_to_mat(deps, L);
  for (int k = 0; k < 9; k++) L[k] /= dt;
  return advance(d, L, dt);
}

static int mixed(mrn_driver *d, const double D[6], const int ctrl[6], const double target[6], double spin_xy,
                 double dt) {
  double L[9] = {0};
  for (int k = 0; k < 6; k++) set_sym(L, k, D[k]);
  L[1] += spin_xy; /* W_xy = -W_yx */
  L[3] -= spin_xy;
  return mrn_driver_step_mixed(d, L, ctrl, target, dt);
}

int mrn_driver_triaxial(mrn_driver *d, double rate, double lateral, double dt) {
  const double D[6] = {0, 0, rate, 0, 0, 0}, target[6] = {lateral, lateral, 0, 0, 0, 0};
  const int ctrl[6] = {1, 1, 0, 0, 0, 0};
  return mixed(d, D, ctrl, target, 0.0, dt);
}

int mrn_driver_uniaxial(mrn_driver *d, double rate, double dt) {
  const double D[6] = {0, 0, rate, 0, 0, 0}, target[6] = {0};
  const int ctrl[6] = {1, 1, 0, 0, 0, 0};
  return mixed(d, D, ctrl, target, 0.0, dt);
}

int mrn_driver_biaxial(mrn_driver *d, double rate, double lateral, double dt) {
  const double D[6] = {0, rate, 0, 0, 0, 0}, target[6] = {lateral, 0, 0, 0, 0, 0};
  const int ctrl[6] = {1, 0, 0, 0, 0, 0};
  return mixed(d, D, ctrl, target, 0.0, dt);
}

int mrn_driver_oedometer(mrn_driver *d, double rate, double dt) {
  const double D[6] = {0, 0, rate, 0, 0, 0}, target[6] = {0};
  const int ctrl[6] = {0};
  return mixed(d, D, ctrl, target, 0.0, dt);
}

int mrn_driver_simple_shear(mrn_driver *d, double gamma_rate, double normal, double dt) {
  const double D[6] = {0, 0, 0, 0.5 * gamma_rate, 0, 0}, target[6] = {0, isfinite(normal) ? normal : 0.0, 0, 0, 0, 0};
  const int ctrl[6] = {0, isfinite(normal) ? 1 : 0, 0, 0, 0, 0};
  return mixed(d, D, ctrl, target, 0.5 * gamma_rate, dt);
}
