#include "material/advance.h"

#include <math.h>
#include <string.h>

#include "core/tensor.h"

#define MRN_ALWAYS_INLINE static inline __attribute__((always_inline))

/* Increment A of the deformation gradient, F_new = A F (002, Eq. 27). With
 * h = dt/2 and M = I - h L, the mid-point rule's A = M^-1 (I + h L) is
 * 2 M^-1 - I, since I + h L = 2 I - M. In plane strain (dim 2) L has no z row
 * or column, so only the in-plane 2x2 block of A differs from I. Returns 1
 * when M is singular. */
MRN_ALWAYS_INLINE int increment(const int dim, const double L[9], double dt, mrn_f_update f_update, double A[9]) {
  if (f_update != MRN_F_UPDATE_MIDPOINT) {
    for (int k = 0; k < 9; k++) A[k] = (k % 4 == 0 ? 1.0 : 0.0) + dt * L[k]; /* A = I + L dt */
    return 0;
  }
  const double h = 0.5 * dt;
  if (dim == 2) {
    const double m00 = 1.0 - h * L[0], m01 = -h * L[1], m10 = -h * L[3], m11 = 1.0 - h * L[4];
    const double det = m00 * m11 - m01 * m10;
    if (!(fabs(det) > 0.0)) return 1;
    const double r = 2.0 / det; /* 2 M^-1 = (2 / det M) adj M */
    A[0] = r * m11 - 1.0;
    A[1] = -r * m01;
    A[3] = -r * m10;
    A[4] = r * m00 - 1.0;
    A[2] = A[5] = A[6] = A[7] = 0.0;
    A[8] = 1.0;
    return 0;
  }
  double M[9];
  for (int k = 0; k < 9; k++) M[k] = (k % 4 == 0 ? 1.0 : 0.0) - h * L[k];
  const double c0 = M[4] * M[8] - M[5] * M[7], c1 = M[5] * M[6] - M[3] * M[8], c2 = M[3] * M[7] - M[4] * M[6];
  const double det = M[0] * c0 + M[1] * c1 + M[2] * c2;
  if (!(fabs(det) > 0.0)) return 1;
  const double r = 2.0 / det; /* 2 M^-1 = (2 / det M) adj M, adj M the transposed cofactors */
  A[0] = r * c0 - 1.0;
  A[1] = r * (M[2] * M[7] - M[1] * M[8]);
  A[2] = r * (M[1] * M[5] - M[2] * M[4]);
  A[3] = r * c1;
  A[4] = r * (M[0] * M[8] - M[2] * M[6]) - 1.0;
  A[5] = r * (M[2] * M[3] - M[0] * M[5]);
  A[6] = r * c2;
  A[7] = r * (M[1] * M[6] - M[0] * M[7]);
  A[8] = r * (M[0] * M[4] - M[1] * M[3]) - 1.0;
  return 0;
}

/* Jaumann co-rotation s <- s + dW s - s dW over the step (002, Eq. 28), dW
 * the spin increment skew(L) dt (002, Eq. 30). dW s - s dW = T + T^T with
 * T = dW s, as dW is skew and s symmetric; dW = [[0, w01, w02], [-w01, 0,
 * w12], [-w02, -w12, 0]], and in plane strain only w01 is nonzero. */
MRN_ALWAYS_INLINE void jaumann_rotate(const int dim, const double L[9], double dt, double s[6]) {
  const double w01 = 0.5 * dt * (L[1] - L[3]);
  const double sxx = s[SXX], syy = s[SYY], szz = s[SZZ], sxy = s[SXY], syz = s[SYZ], sxz = s[SXZ];
  if (dim == 2) {
    s[SXX] += 2.0 * w01 * sxy;
    s[SYY] -= 2.0 * w01 * sxy;
    s[SXY] += w01 * (syy - sxx);
    s[SYZ] -= w01 * sxz;
    s[SXZ] += w01 * syz;
    return;
  }
  const double w02 = 0.5 * dt * (L[2] - L[6]), w12 = 0.5 * dt * (L[5] - L[7]);
  /* T = dW s, row by row */
  const double t00 = w01 * sxy + w02 * sxz, t01 = w01 * syy + w02 * syz, t02 = w01 * syz + w02 * szz;
  const double t10 = -w01 * sxx + w12 * sxz, t11 = -w01 * sxy + w12 * syz, t12 = -w01 * sxz + w12 * szz;
  const double t20 = -w02 * sxx - w12 * sxy, t21 = -w02 * sxy - w12 * syy, t22 = -w02 * sxz - w12 * syz;
  s[SXX] += 2.0 * t00;
  s[SYY] += 2.0 * t11;
  s[SZZ] += 2.0 * t22;
  s[SXY] += t01 + t10;
  s[SYZ] += t12 + t21;
  s[SXZ] += t02 + t20;
}

/* F advanced over the step, J its determinant after, and before in *J_old
 * unless J_old is NULL (the determinants of the dimension, as the particle
 * volume is formed). F is stored as the particles keep it
 * (mrn_tensor_stride): in plane strain (dim 2) its in-plane block xx, xy,
 * yx, yy only, the z row and column being those of I. Returns 1 (F
 * unchanged) when the increment would invert F. */
MRN_ALWAYS_INLINE int advance_F(const int dim, const double L[9], double dt, mrn_f_update f_update, double *F,
                                double *J_old, double *J) {
  double A[9], Fn[9];
  if (increment(dim, L, dt, f_update, A)) return 1;
  if (dim == 2) {
    /* Fn = A F on the in-plane blocks (A's and F's z rows and columns are
     * those of I); formed in locals and stored once F is known to stay
     * invertible (built in an array and copied, the values went through the
     * stack, and the wide loads of the copy waited on the narrow stores
     * before them) */
    const double fxx = F[0], fxy = F[1], fyx = F[2], fyy = F[3];
    const double nxx = A[0] * fxx + A[1] * fyx, nxy = A[0] * fxy + A[1] * fyy;
    const double nyx = A[3] * fxx + A[4] * fyx, nyy = A[3] * fxy + A[4] * fyy;
    if (J_old) *J_old = fxx * fyy - fxy * fyx;
    *J = nxx * nyy - nxy * nyx;
    if (!(*J > 0.0)) return 1;
    F[0] = nxx;
    F[1] = nxy;
    F[2] = nyx;
    F[3] = nyy;
    return 0;
  }
  mat_mul(A, F, Fn);
  if (J_old) *J_old = mat_det(F);
  *J = mat_det(Fn);
  if (!(*J > 0.0)) return 1;
  memcpy(F, Fn, 9 * sizeof(double));
  return 0;
}

/* The strain increment sym(L) dt (002, Eq. 29). In plane strain (dim 2) L
 * has no z row or column, so the z components are zero without reading L. */
MRN_ALWAYS_INLINE void strain_increment(const int dim, const double L[9], double dt, double de[6]) {
  if (dim == 3) {
    mat_sym_part(L, dt, de);
    return;
  }
  de[SXX] = dt * L[0];
  de[SYY] = dt * L[4];
  de[SXY] = 0.5 * dt * (L[1] + L[3]);
  de[SZZ] = de[SYZ] = de[SXZ] = 0.0;
}

/* Hooke's law of mrn_hooke_update for a plane-strain increment (de_zz =
 * de_yz = de_xz = 0): only sxx, syy, szz and sxy change, and only the
 * in-plane components of de enter the energy; the same values without the
 * products by zero (up to the sign of a zero). */
MRN_ALWAYS_INLINE double hooke_plane_strain(double lambda, double shear, const double de[6], double s[6]) {
  const double old_xx = s[SXX], old_yy = s[SYY], old_xy = s[SXY];
  const double tr = de[SXX] + de[SYY];
  s[SXX] += lambda * tr + 2.0 * shear * de[SXX];
  s[SYY] += lambda * tr + 2.0 * shear * de[SYY];
  s[SZZ] += lambda * tr;
  s[SXY] += 2.0 * shear * de[SXY];
  return 0.5 * (old_xx + s[SXX]) * de[SXX] + 0.5 * (old_yy + s[SYY]) * de[SYY] +
         2.0 * (0.5 * (old_xy + s[SXY]) * de[SXY]);
}

/* The kinematics of one point: F (stored, see advance_F) advanced, and the
 * model's input (rotated start-of-step stress, strain increment, J, F as a
 * full 3 x 3, expanded into F_full in plane strain) set in pt. Returns 1
 * (F unchanged) when the increment would invert F. */
MRN_ALWAYS_INLINE int kinematics(const int dim, const mrn_material *mat, const double L[9], double dt,
                                 mrn_f_update f_update, double *F, double F_full[9], const double stress[6],
                                 double *state, mrn_material_point *pt) {
  double J_old, J;
  if (advance_F(dim, L, dt, f_update, F, &J_old, &J)) return 1;
  if (dim == 2) {
    mrn_tensor_expand(2, F, 1.0, F_full);
    F = F_full;
  }
  memcpy(pt->stress, stress, sizeof pt->stress);
  strain_increment(dim, L, dt, pt->dstrain);
  if (mat->type->rate_form) jaumann_rotate(dim, L, dt, pt->stress);
  pt->F = F;
  pt->J = J;
  pt->J_old = J_old;
  pt->dt = dt;
  pt->state = state;
  pt->de_elastic = pt->dw_plastic = 0.0;
  return 0;
}

/* the mid-step volume V0 (J_old + J) / 2 that weights the energies of the
 * step (000, Eqs. 64-65) */
MRN_ALWAYS_INLINE double mid_volume(double vol0, double J_old, double J) { return 0.5 * (vol0 * J_old + vol0 * J); }

/* A `pure_hooke` model (material.h): the kinematics and the model's update
 * of each point in one loop straight on the arrays, the same arithmetic as
 * kinematics() followed by the model's update without the hand-over through
 * mrn_material_point and the call per batch. */
MRN_ALWAYS_INLINE long advance_hooke(const int dim, const mrn_material *mat, mrn_f_update f_update, double dt,
                                     size_t n, const double *L, double *F, double *stress, double *strain,
                                     const mrn_energy_sums *energy, mrn_point_result *out) {
  const double lambda = mat->derived[0], shear = mat->derived[1];
  long first_bad = -1;
  for (size_t i = 0; i < n; i++) {
    const double *Li = L + 9 * i;
    double *Fi = F + (size_t)mrn_tensor_stride(dim) * i;
    double J_old, J;
    if (advance_F(dim, Li, dt, f_update, Fi, &J_old, &J)) {
      if (out) out[i].inverted = 1;
      if (first_bad < 0) first_bad = (long)i;
      continue;
    }
    double s[6], de[6];
    memcpy(s, stress + 6 * i, sizeof s);
    strain_increment(dim, Li, dt, de);
    jaumann_rotate(dim, Li, dt, s);
    const double de_elastic =
        dim == 2 ? hooke_plane_strain(lambda, shear, de, s) : mrn_hooke_update(lambda, shear, de, s);
    memcpy(stress + 6 * i, s, sizeof s);
    if (strain) {
      double *restrict e = strain + 6 * i;
      if (dim == 2) {
        e[SXX] += de[SXX];
        e[SYY] += de[SYY];
        e[SXY] += de[SXY];
      } else {
        for (int c = 0; c < 6; c++) e[c] += de[c];
      }
    }
    /* no plastic work: w_plastic is left as it is */
    if (energy) energy->e_elastic[i] += mid_volume(energy->vol0[i], J_old, J) * de_elastic;
    if (out) out[i] = (mrn_point_result){J, de_elastic, 0.0, 0};
  }
  return first_bad;
}

enum { BATCH = MRN_MATERIAL_BATCH }; /* points per call of the model's update */

MRN_ALWAYS_INLINE long advance_points(const int dim, const mrn_material *mat, mrn_f_update f_update, double dt,
                                      size_t n, const double *L, double *F, double *stress, double *strain,
                                      double *state, int state_stride, const mrn_energy_sums *energy,
                                      mrn_point_result *out) {
  if (mat->type->pure_hooke) return advance_hooke(dim, mat, f_update, dt, n, L, F, stress, strain, energy, out);
  long first_bad = -1;
  if (!mat->type->nstate) state = NULL;
  for (size_t lo = 0; lo < n; lo += BATCH) {
    const size_t hi = n - lo < BATCH ? n : lo + BATCH;
    mrn_material_point pts[BATCH];
    double F_full[BATCH][9]; /* plane strain: each point's F as a full 3 x 3 */
    size_t idx[BATCH];
    int k = 0;
    for (size_t i = lo; i < hi; i++) {
      double *st = state ? state + (size_t)state_stride * i : NULL;
      if (kinematics(dim, mat, L + 9 * i, dt, f_update, F + (size_t)mrn_tensor_stride(dim) * i,
                     F_full[k], stress + 6 * i, st, &pts[k])) {
        if (out) out[i].inverted = 1;
        if (first_bad < 0) first_bad = (long)i;
        continue;
      }
      idx[k++] = i;
    }
    if (k) mat->type->update(mat, pts, k);
    for (int j = 0; j < k; j++) {
      const size_t i = idx[j];
      const mrn_material_point *pt = &pts[j];
      memcpy(stress + 6 * i, pt->stress, sizeof pt->stress);
      if (strain) {
        double *restrict e = strain + 6 * i;
        for (int c = 0; c < 6; c++) e[c] += pt->dstrain[c];
      }
      if (energy) {
        const double vol_mid = mid_volume(energy->vol0[i], pt->J_old, pt->J);
        energy->e_elastic[i] += vol_mid * pt->de_elastic;
        energy->w_plastic[i] += vol_mid * pt->dw_plastic;
      }
      if (out) out[i] = (mrn_point_result){pt->J, pt->de_elastic, pt->dw_plastic, 0};
    }
  }
  return first_bad;
}

/* one instance per dimension and F update, so that both are constants */
#define MRN_ADVANCE_VARIANT(DIM, FU)                                                                            \
  static long advance_points_##DIM##d_##FU(const mrn_material *mat, double dt, size_t n, const double *L,       \
                                           double *F, double *stress, double *strain, double *state,            \
                                           int state_stride, const mrn_energy_sums *energy, mrn_point_result *out) { \
    return advance_points(DIM, mat, MRN_F_UPDATE_##FU, dt, n, L, F, stress, strain, state, state_stride, energy,    \
                          out);                                                                                     \
  }
MRN_ADVANCE_VARIANT(2, MIDPOINT)
MRN_ADVANCE_VARIANT(2, EULER)
MRN_ADVANCE_VARIANT(3, MIDPOINT)
MRN_ADVANCE_VARIANT(3, EULER)
#undef MRN_ADVANCE_VARIANT

long mrn_material_advance_points(const mrn_material *mat, int dim, mrn_f_update f_update, double dt, size_t n,
                                 const double *L, double *F, double *stress, double *strain, double *state,
                                 int state_stride, const mrn_energy_sums *energy, mrn_point_result *out) {
  const int mid = f_update == MRN_F_UPDATE_MIDPOINT;
  return (dim == 2 ? (mid ? advance_points_2d_MIDPOINT : advance_points_2d_EULER)
                   : (mid ? advance_points_3d_MIDPOINT : advance_points_3d_EULER))(mat, dt, n, L, F, stress, strain,
                                                                                  state, state_stride, energy, out);
}

int mrn_material_advance(const mrn_material *mat, const double L[9], double dt, mrn_f_update f_update, double F[9],
                         double stress[6], double strain[6], double *state, mrn_point_result *out) {
  return mrn_material_advance_points(mat, 3, f_update, dt, 1, L, F, stress, strain, state, 0, NULL, out) >= 0;
}
