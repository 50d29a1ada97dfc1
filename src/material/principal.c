#include "material/principal.h"

#include <math.h>
#include <string.h>

#include "core/tensor.h"

#define MRN_ALWAYS_INLINE static inline __attribute__((always_inline))

/* The rotation J = [[c, s], [-s, c]] in the (p, q) plane that zeroes A_pq */
MRN_ALWAYS_INLINE void jacobi_angle(double app, double aqq, double apq, double *c, double *s) {
  double theta = (aqq - app) / (2.0 * apq);
  double t = fabs(theta) > 1e150 ? 0.5 / theta : (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
  *c = 1.0 / sqrt(t * t + 1.0);
  *s = t * *c;
}

/* One Jacobi rotation in the (p, q) plane zeroes A_pq; the off-diagonal mass
 * drops quadratically, so a handful of sweeps reach round-off. */
MRN_ALWAYS_INLINE void rotate(const int n, double *A, double *V, int p, int q) {
  double apq = A[n * p + q];
  if (apq == 0.0) return;
  double c, s;
  jacobi_angle(A[n * p + p], A[n * q + q], apq, &c, &s);
  for (int k = 0; k < n; k++) { /* A <- A J */
    double akp = A[n * k + p], akq = A[n * k + q];
    A[n * k + p] = c * akp - s * akq;
    A[n * k + q] = s * akp + c * akq;
  }
  for (int k = 0; k < n; k++) { /* A <- J^T A */
    double apk = A[n * p + k], aqk = A[n * q + k];
    A[n * p + k] = c * apk - s * aqk;
    A[n * q + k] = s * apk + c * aqk;
  }
  A[n * p + q] = A[n * q + p] = 0.0;
  for (int k = 0; k < n; k++) {
    double vkp = V[n * k + p], vkq = V[n * k + q];
    V[n * k + p] = c * vkp - s * vkq;
    V[n * k + q] = s * vkp + c * vkq;
  }
}

/* selection sort, descending, carrying the eigenvectors along */
MRN_ALWAYS_INLINE void sort_descending(const int n, double *lam, double *V) {
  for (int i = 0; i < n; i++) {
    int best = i;
    for (int j = i + 1; j < n; j++)
      if (lam[j] > lam[best]) best = j;
    if (best == i) continue;
    double t = lam[i];
    lam[i] = lam[best];
    lam[best] = t;
    for (int k = 0; k < n; k++) {
      t = V[n * k + i];
      V[n * k + i] = V[n * k + best];
      V[n * k + best] = t;
    }
  }
}

/* the stop rule of the sweeps: no off-diagonal mass left at round-off */
MRN_ALWAYS_INLINE int converged(double off, double diag) { return off == 0.0 || off < 1e-36 * diag; }

/* inlined with n = 3 for the principal stresses, so the loops unroll */
MRN_ALWAYS_INLINE void jacobi(const int n, const double *A_in, double *lam, double *V) {
  double A[MRN_JACOBI_MAX * MRN_JACOBI_MAX];
  memcpy(A, A_in, sizeof(double) * n * n);
  for (int i = 0; i < n * n; i++) V[i] = (i % (n + 1) == 0) ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 64; sweep++) {
    double off = 0.0, diag = 0.0;
    for (int p = 0; p < n; p++) {
      diag += A[n * p + p] * A[n * p + p];
      for (int q = p + 1; q < n; q++) off += A[n * p + q] * A[n * p + q];
    }
    if (converged(off, diag)) break;
    for (int p = 0; p < n; p++)
      for (int q = p + 1; q < n; q++) rotate(n, A, V, p, q);
  }
  for (int i = 0; i < n; i++) lam[i] = A[n * i + i];
  sort_descending(n, lam, V);
}

void mrn_jacobi_eigen(int n, const double *A_in, double *lam, double *V) { jacobi(n, A_in, lam, V); }

/* With s_xz = s_yz = 0 (every plane-strain stress) z is a principal
 * direction and the in-plane block is diagonalised by the one rotation
 * J(c, s) of the first Jacobi sweep, the later rotations and sweeps finding
 * nothing left to do: the general solver's operations without the 3x3 loops
 * (the same result to round-off; tests/unit/test_advance.c). Rotated block (A <- J^T A J):
 *   lam_1 = c (c s_xx - s s_xy) - s (c s_xy - s s_yy),
 *   lam_2 = s (s s_xx + c s_xy) + c (s s_xy + c s_yy),
 * eigenvectors (c, -s, 0) and (s, c, 0); lam_3 = s_zz along e_z. */
static void plane_eigen(const double s[6], double lam[3], double V[9]) {
  const double a00 = s[SXX], a11 = s[SYY], a01 = s[SXY], a22 = s[SZZ];
  for (int i = 0; i < 9; i++) V[i] = i % 4 == 0 ? 1.0 : 0.0;
  lam[0] = a00, lam[1] = a11, lam[2] = a22;
  const double diag = a00 * a00 + a11 * a11 + a22 * a22, off = a01 * a01;
  if (!converged(off, diag)) {
    double c, sn;
    jacobi_angle(a00, a11, a01, &c, &sn);
    const double b00 = c * a00 - sn * a01, b01 = sn * a00 + c * a01; /* A J, first row */
    const double b10 = c * a01 - sn * a11, b11 = sn * a01 + c * a11; /* A J, second row */
    lam[0] = c * b00 - sn * b10;                                      /* (J^T A J)_xx */
    lam[1] = sn * b01 + c * b11;                                      /* (J^T A J)_yy */
    V[0] = c, V[1] = sn, V[3] = -sn, V[4] = c;
  }
  sort_descending(3, lam, V);
}

void mrn_sym_eigen(const double s[6], double lam[3], double V[9]) {
  if (s[SXZ] == 0.0 && s[SYZ] == 0.0) {
    plane_eigen(s, lam, V);
    return;
  }
  double S[9];
  sym_to_mat(s, S);
  jacobi(3, S, lam, V);
}

void mrn_sym_from_principal(const double lam[3], const double V[9], double s[6]) {
  for (int a = 0; a < 3; a++)
    for (int b = a; b < 3; b++) {
      double v = 0.0;
      for (int i = 0; i < 3; i++) v += lam[i] * V[3 * a + i] * V[3 * b + i];
      s[sym_index(a, b)] = v;
    }
}

/* Through the eigen-decomposition of A^T A: A^+ b = sum_i v_i (v_i . A^T b) / mu_i
 * over the eigenpairs (mu_i, v_i) above the cut-off. Squaring the condition
 * number is harmless for the small, well-scaled systems of the driver. */
int mrn_pinv_solve(int n, const double *A, const double *b, double rcond, double *x) {
  double AtA[MRN_JACOBI_MAX * MRN_JACOBI_MAX] = {0}, Atb[MRN_JACOBI_MAX] = {0}, mu[MRN_JACOBI_MAX];
  double V[MRN_JACOBI_MAX * MRN_JACOBI_MAX];
  for (int i = 0; i < n; i++) {
    Atb[i] = 0.0;
    for (int k = 0; k < n; k++) Atb[i] += A[n * k + i] * b[k];
    for (int j = 0; j < n; j++) {
      double v = 0.0;
      for (int k = 0; k < n; k++) v += A[n * k + i] * A[n * k + j];
      AtA[n * i + j] = v;
    }
  }
  mrn_jacobi_eigen(n, AtA, mu, V);
  int rank = 0;
  for (int i = 0; i < n; i++) x[i] = 0.0;
  for (int i = 0; i < n; i++) {
    if (!(mu[i] > rcond * rcond * mu[0])) continue;
    rank++;
    double c = 0.0;
    for (int k = 0; k < n; k++) c += V[n * k + i] * Atb[k];
    c /= mu[i];
    for (int k = 0; k < n; k++) x[k] += c * V[n * k + i];
  }
  return rank;
}
