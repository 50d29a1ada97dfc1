#include "transfer/wls.h"

#include <math.h>

/* invert a small symmetric positive-definite matrix (n <= 4) by Gauss-Jordan
 * elimination with partial pivoting; returns 1 if singular */
static int invert(int n, double a[4][4], double inv[4][4]) {
  double m[4][8];
  for (int i = 0; i < n; i++)
    for (int j = 0; j < 2 * n; j++) m[i][j] = j < n ? a[i][j] : (j - n == i ? 1.0 : 0.0);
  for (int col = 0; col < n; col++) {
    int piv = col;
    for (int r = col + 1; r < n; r++)
      if (fabs(m[r][col]) > fabs(m[piv][col])) piv = r;
    if (fabs(m[piv][col]) < 1e-300) return 1;
    if (piv != col)
      for (int j = 0; j < 2 * n; j++) {
        double t = m[col][j];
        m[col][j] = m[piv][j];
        m[piv][j] = t;
      }
    double d = m[col][col];
    for (int j = 0; j < 2 * n; j++) m[col][j] /= d;
    for (int r = 0; r < n; r++) {
      if (r == col || m[r][col] == 0.0) continue;
      double f = m[r][col];
      for (int j = 0; j < 2 * n; j++) m[r][j] -= f * m[col][j];
    }
  }
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) inv[i][j] = m[i][n + j];
  return 0;
}

int mrn_wls_correct(int dim, int count, double *N, double *dN, const double *offset, int values, int gradients) {
  const int n = dim + 1;
  double M[4][4] = {{0}}, Minv[4][4];
  for (int c = 0; c < count; c++) {
    if (N[c] == 0.0) continue;
    double P[4] = {1.0, 0, 0, 0};
    for (int d = 0; d < dim; d++) P[d + 1] = offset[c * dim + d];
    for (int a = 0; a < n; a++)
      for (int b = 0; b < n; b++) M[a][b] += N[c] * P[a] * P[b]; /* (002, Eq. 55) */
  }
  if (invert(n, M, Minv)) return 1;
  for (int c = 0; c < count; c++) {
    const double *b = offset + c * dim;
    if (gradients)
      for (int d = 0; d < dim; d++) {
        double gr = Minv[d + 1][0]; /* C2 */
        for (int e = 0; e < dim; e++) gr += Minv[d + 1][e + 1] * b[e]; /* C3 b */
        dN[c * dim + d] = gr * N[c]; /* (002, Eq. 62) */
      }
  }
  if (values)
    for (int c = 0; c < count; c++) {
      const double *b = offset + c * dim;
      double f = Minv[0][0]; /* C1 */
      for (int d = 0; d < dim; d++) f += Minv[0][d + 1] * b[d]; /* C2 . b */
      N[c] *= f; /* (002, Eq. 58) */
    }
  return 0;
}
