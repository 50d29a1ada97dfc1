/* moraine: small tensor helpers (header-only, inlined into the kernels).
 *
 * Conventions used everywhere in the engine:
 *  - vectors have 3 components, z = 0 in 2D;
 *  - full second-order tensors are 3x3 row-major arrays, A[3*a+b] = A_ab;
 *  - the velocity gradient is L_ab = d v_a / d x_b (002, Eq. 26);
 *  - symmetric tensors (stress, strain) are stored as 6 components in VTK's
 *    order: xx, yy, zz, xy, yz, xz. Tensor contractions double the shear terms.
 */
#ifndef MRN_CORE_TENSOR_H
#define MRN_CORE_TENSOR_H

#include <math.h>

enum { SXX = 0, SYY = 1, SZZ = 2, SXY = 3, SYZ = 4, SXZ = 5 };

/* index of the symmetric component (a,b) in the 6-vector */
static inline int sym_index(int a, int b) {
  static const int map[3][3] = {{SXX, SXY, SXZ}, {SXY, SYY, SYZ}, {SXZ, SYZ, SZZ}};
  return map[a][b];
}

/* s : t for symmetric tensors in 6-component storage */
static inline double sym_ddot(const double s[6], const double t[6]) {
  return s[0] * t[0] + s[1] * t[1] + s[2] * t[2] + 2.0 * (s[3] * t[3] + s[4] * t[4] + s[5] * t[5]);
}

static inline double sym_trace(const double s[6]) { return s[0] + s[1] + s[2]; }

/* deviatoric part */
static inline void sym_dev(const double s[6], double d[6]) {
  double m = sym_trace(s) / 3.0;
  d[0] = s[0] - m; d[1] = s[1] - m; d[2] = s[2] - m;
  d[3] = s[3]; d[4] = s[4]; d[5] = s[5];
}

/* sqrt(s:s) */
static inline double sym_norm(const double s[6]) { return sqrt(sym_ddot(s, s)); }

/* von Mises equivalent stress sqrt(3/2 s_dev:s_dev) */
static inline double sym_von_mises(const double s[6]) {
  double d[6];
  sym_dev(s, d);
  return sqrt(1.5 * sym_ddot(d, d));
}

/* symmetric and skew parts of a full tensor, scaled by `scale` */
static inline void mat_sym_part(const double L[9], double scale, double d[6]) {
  d[SXX] = scale * L[0];
  d[SYY] = scale * L[4];
  d[SZZ] = scale * L[8];
  d[SXY] = 0.5 * scale * (L[1] + L[3]);
  d[SYZ] = 0.5 * scale * (L[5] + L[7]);
  d[SXZ] = 0.5 * scale * (L[2] + L[6]);
}

static inline void mat_skew_part(const double L[9], double scale, double w[9]) {
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) w[3 * a + b] = 0.5 * scale * (L[3 * a + b] - L[3 * b + a]);
}

/* expand 6-component symmetric storage into a full 3x3 */
static inline void sym_to_mat(const double s[6], double m[9]) {
  m[0] = s[SXX]; m[1] = s[SXY]; m[2] = s[SXZ];
  m[3] = s[SXY]; m[4] = s[SYY]; m[5] = s[SYZ];
  m[6] = s[SXZ]; m[7] = s[SYZ]; m[8] = s[SZZ];
}

/* C = A B for 3x3 */
static inline void mat_mul(const double A[9], const double B[9], double C[9]) {
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      C[3 * a + b] = A[3 * a] * B[b] + A[3 * a + 1] * B[3 + b] + A[3 * a + 2] * B[6 + b];
}

static inline double mat_det(const double A[9]) {
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* values stored per particle for a full tensor (F, affine): the whole 3 x 3
 * in 3D, the in-plane block xx, xy, yx, yy in 2D */
static inline int mrn_tensor_stride(const int dim) { return dim == 2 ? 4 : 9; }

/* a stored tensor (mrn_tensor_stride(dim) values) as a full row-major 3 x 3,
 * with `zz` on the diagonal's z entry in 2D (1 for F, 0 for the affine
 * matrix) */
static inline void mrn_tensor_expand(const int dim, const double *stored, double zz, double full[9]) {
  if (dim == 3) {
    for (int k = 0; k < 9; k++) full[k] = stored[k];
    return;
  }
  full[0] = stored[0], full[1] = stored[1], full[2] = 0.0;
  full[3] = stored[2], full[4] = stored[3], full[5] = 0.0;
  full[6] = 0.0, full[7] = 0.0, full[8] = zz;
}

/* a full row-major 3 x 3 into its stored form; in 2D only the in-plane
 * block is kept (the rest is the plane-strain value by construction) */
static inline void mrn_tensor_pack(const int dim, const double full[9], double *stored) {
  if (dim == 3) {
    for (int k = 0; k < 9; k++) stored[k] = full[k];
    return;
  }
  stored[0] = full[0], stored[1] = full[1], stored[2] = full[3], stored[3] = full[4];
}

/* B = A^-1 for 3x3; returns 1 (B untouched) when A is singular */
static inline int mat_inverse(const double A[9], double B[9]) {
  double det = mat_det(A);
  if (!(fabs(det) > 0.0)) return 1;
  B[0] = (A[4] * A[8] - A[5] * A[7]) / det;
  B[1] = (A[2] * A[7] - A[1] * A[8]) / det;
  B[2] = (A[1] * A[5] - A[2] * A[4]) / det;
  B[3] = (A[5] * A[6] - A[3] * A[8]) / det;
  B[4] = (A[0] * A[8] - A[2] * A[6]) / det;
  B[5] = (A[2] * A[3] - A[0] * A[5]) / det;
  B[6] = (A[3] * A[7] - A[4] * A[6]) / det;
  B[7] = (A[1] * A[6] - A[0] * A[7]) / det;
  B[8] = (A[0] * A[4] - A[1] * A[3]) / det;
  return 0;
}

static inline void mat_identity(double A[9]) {
  A[0] = A[4] = A[8] = 1.0;
  A[1] = A[2] = A[3] = A[5] = A[6] = A[7] = 0.0;
}

/* Jaumann co-rotation of a symmetric tensor over one step (002, Eq. 28):
 * s <- s + (dW s - s dW), dW the spin increment (skew, full storage). */
static inline void sym_jaumann_rotate(double s[6], const double dW[9]) {
  double S[9], WS[9], SW[9];
  sym_to_mat(s, S);
  mat_mul(dW, S, WS);
  mat_mul(S, dW, SW);
  s[SXX] += WS[0] - SW[0];
  s[SYY] += WS[4] - SW[4];
  s[SZZ] += WS[8] - SW[8];
  s[SXY] += WS[1] - SW[1];
  s[SYZ] += WS[5] - SW[5];
  s[SXZ] += WS[2] - SW[2];
}

#endif
