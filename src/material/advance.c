#include "material/advance.h"

#include <math.h>
#include <string.h>

#include "core/tensor.h"

int mrn_material_advance(const mrn_material *mat, const double L[9], double dt, mrn_f_update f_update, double F[9],
                         double stress[6], double strain[6], double *state, mrn_point_result *out) {
  double inc[9], Fn[9];
  if (f_update == MRN_F_UPDATE_MIDPOINT) {
    double P[9], M[9], Mi[9];
    for (int k = 0; k < 9; k++) {
      double I = k % 4 == 0 ? 1.0 : 0.0;
      P[k] = I + 0.5 * dt * L[k];
      M[k] = I - 0.5 * dt * L[k];
    }
    if (mat_inverse(M, Mi)) return 1;
    mat_mul(Mi, P, inc);
  } else {
    for (int k = 0; k < 9; k++) inc[k] = (k % 4 == 0 ? 1.0 : 0.0) + dt * L[k]; /* (002, Eq. 27) */
  }
  mat_mul(inc, F, Fn);
  const double J_old = mat_det(F), J = mat_det(Fn);
  if (!(J > 0.0)) return 1;
  memcpy(F, Fn, sizeof Fn);

  mrn_material_point pt;
  memcpy(pt.stress, stress, sizeof pt.stress);
  mat_sym_part(L, dt, pt.dstrain); /* (002, Eq. 29) */
  if (mat->type->rate_form) {
    double W[9];
    mat_skew_part(L, dt, W); /* (002, Eq. 30) */
    sym_jaumann_rotate(pt.stress, W);
  }
  pt.F = F;
  pt.J = J;
  pt.J_old = J_old;
  pt.dt = dt;
  pt.state = mat->type->nstate ? state : NULL;
  pt.de_elastic = pt.dw_plastic = 0.0;
  mat->type->update(mat, &pt);
  memcpy(stress, pt.stress, sizeof pt.stress);
  if (strain)
    for (int k = 0; k < 6; k++) strain[k] += pt.dstrain[k];
  out->J_old = J_old;
  out->J = J;
  out->de_elastic = pt.de_elastic;
  out->dw_plastic = pt.dw_plastic;
  return 0;
}
