#include "material/principal.h"

#include <math.h>
#include <string.h>

#include "core/tensor.h"

/* One Jacobi rotation in the (p, q) plane zeroes A_pq; the off-diagonal mass
 * drops quadratically, so a handful of sweeps reach round-off. */
static void rotate(int n, double *A, double *V, int p, int q) {
  double apq = A[n * p + q];
  if (apq == 0.0) return;
  double theta = (A[n * q + q] - A[n * p + p]) / (2.0 * apq);
  double t = fabs(theta) > 1e150 ? 0.5 / theta : (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
  double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
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

void mrn_jacobi_eigen(int n, const double *A_in, double *lam, double *V) {
  double A[MRN_JACOBI_MAX * MRN_JACOBI_MAX];
  memcpy(A, A_in, sizeof(double) * n * n);
  for (int i = 0; i < n * n; i++) V[i] = (i % (n + 1) == 0) ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 64; sweep++) {
    double off = 0.0, diag = 0.0;
    for (int p = 0; p < n; p++) {
      diag += A[n * p + p] * A[n * p + p];
      for (int q = p + 1; q < n; q++) off += A[n * p + q] * A[n * p + q];
    }
    if (off == 0.0 || off < 1e-36 * diag) break;
    for (int p = 0; p < n; p++)
      for (int q = p + 1; q < n; q++) rotate(n, A, V, p, q);
  }
  for (int i = 0; i < n; i++) lam[i] = A[n * i + i];
  /* selection sort, descending, carrying the eigenvectors along */
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

void mrn_sym_eigen(const double s[6], double lam[3], double V[9]) {
  double S[9];
  sym_to_mat(s, S);
  mrn_jacobi_eigen(3, S, lam, V);
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
