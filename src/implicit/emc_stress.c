/* moraine: energy-momentum consistent algorithmic stress (see emc_stress.h). */
#include "implicit/emc_stress.h"

#include <math.h>
#include <string.h>

#include "core/tensor.h"
#include "material/principal.h"

typedef double complex cx;

static void cmul(const cx A[9], const cx B[9], cx C[9]) {
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) C[3 * a + b] = A[3 * a] * B[b] + A[3 * a + 1] * B[3 + b] + A[3 * a + 2] * B[6 + b];
}

static void ctrans(const cx A[9], cx T[9]) {
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) T[3 * a + b] = A[3 * b + a];
}

/* A B A^T */
static void cpush(const cx A[9], const cx B[9], cx out[9]) {
  cx AB[9], At[9];
  cmul(A, B, AB);
  ctrans(A, At);
  cmul(AB, At, out);
}

static cx cddot(const cx A[9], const cx B[9]) {
  cx s = 0;
  for (int k = 0; k < 9; k++) s += A[k] * B[k];
  return s;
}

/* inverse of A = A_r + i A_i to first order in A_i, all a complex step
 * keeps: (A_r + i A_i)^-1 = A_r^-1 - i A_r^-1 A_i A_r^-1 + O(A_i^2) */
static void cinv(const cx A[9], cx B[9]) {
  double re[9], im[9], inv[9], t[9], u[9];
  for (int k = 0; k < 9; k++) re[k] = creal(A[k]), im[k] = cimag(A[k]);
  if (mat_inverse(re, inv)) /* singular: NaN reaches the residual and the step fails */
    for (int k = 0; k < 9; k++) inv[k] = NAN;
  mat_mul(inv, im, t);
  mat_mul(t, inv, u);
  for (int k = 0; k < 9; k++) B[k] = inv[k] - I * u[k];
}

/* first divided difference of ln: (ln a - ln b) / (a - b), by the series of
 * 2 artanh(z) / (a - b), z = (a - b)/(a + b), when a and b are close */
static double dlog(double a, double b) {
  double z = (a - b) / (a + b);
  if (fabs(z) < 1e-4) return 2.0 / (a + b) * (1.0 + z * z / 3.0 + z * z * z * z / 5.0);
  return (log(a) - log(b)) / (a - b);
}

static void sym6_of(const double M[9], double s[6]) {
  s[0] = M[0], s[1] = M[4], s[2] = M[8];
  s[3] = 0.5 * (M[1] + M[3]), s[4] = 0.5 * (M[5] + M[7]), s[5] = 0.5 * (M[2] + M[6]);
}

/* ln of a symmetric positive-definite b + i h b': the real part from the
 * eigen-decomposition b = V diag(l) V^T, the imaginary part from the
 * Daleckii-Krein formula V [(V^T b' V)_ij dlog(l_i, l_j)] V^T, which is the
 * directional derivative of ln at b (first order in h is all a complex step
 * keeps). */
static void clog_sym(const cx b[9], cx L[9]) {
  double re[9], im[9], r6[6], lam[3], V[9];
  for (int k = 0; k < 9; k++) re[k] = creal(b[k]), im[k] = cimag(b[k]);
  sym6_of(re, r6);
  mrn_sym_eigen(r6, lam, V);
  double Bp[9] = {0}, Lp[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0.0;
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) s += V[3 * a + i] * 0.5 * (im[3 * a + c] + im[3 * c + a]) * V[3 * c + j];
      Bp[3 * i + j] = s;
    }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) Lp[3 * i + j] = Bp[3 * i + j] * (i == j ? 1.0 / lam[i] : dlog(lam[i], lam[j]));
  for (int a = 0; a < 3; a++)
    for (int c = 0; c < 3; c++) {
      double r = 0.0, s = 0.0;
      for (int i = 0; i < 3; i++) {
        r += V[3 * a + i] * log(lam[i]) * V[3 * c + i];
        for (int j = 0; j < 3; j++) s += V[3 * a + i] * Lp[3 * i + j] * V[3 * c + j];
      }
      L[3 * a + c] = r + I * s;
    }
}

/* b = exp(2 e) for a real symmetric e */
static void exp2_sym(const cx e[9], double b[9]) {
  double re[9], e6[6], lam[3], V[9];
  for (int k = 0; k < 9; k++) re[k] = creal(e[k]);
  sym6_of(re, e6);
  mrn_sym_eigen(e6, lam, V);
  for (int a = 0; a < 3; a++)
    for (int c = 0; c < 3; c++) {
      double s = 0.0;
      for (int i = 0; i < 3; i++) s += V[3 * a + i] * exp(2.0 * lam[i]) * V[3 * c + i];
      b[3 * a + c] = s;
    }
}

static int plastic(const mrn_emc_material *m) { return m->yield > 0.0 && isfinite(m->yield); }

void mrn_emc_stress(const mrn_emc_material *m, const mrn_emc_state *s, const double complex dF[9],
                    double complex P[9], mrn_emc_result *end) {
  const double lambda = m->lambda, G = m->G, sq23 = sqrt(2.0 / 3.0);
  cx Ft[9], F[9], be_t[9], tau_t[9], be_tr[9], eps[9];
  for (int k = 0; k < 9; k++) Ft[k] = s->Ft[k], be_t[k] = s->be[k], tau_t[k] = s->tau[k];
  cmul(dF, Ft, F); /* 001 Eq. 25 */

  /* trial elastic state and return mapping in logarithmic strains */
  cpush(dF, be_t, be_tr);
  clog_sym(be_tr, eps);
  for (int k = 0; k < 9; k++) eps[k] *= 0.5;
  cx tr = eps[0] + eps[4] + eps[8], dgam = 0, xi = s->xi;
  if (plastic(m)) {
    cx dev[9];
    for (int k = 0; k < 9; k++) dev[k] = 2.0 * G * (eps[k] - (k % 4 == 0 ? tr / 3.0 : 0));
    cx nn = cddot(dev, dev);
    if (creal(nn) > 0.0) {
      cx norm = csqrt(nn);
      cx f = norm - sq23 * (m->yield + m->H * s->xi); /* 001 Eq. 63 with q = -H xi */
      if (creal(f) > 0.0) {
        dgam = f / (2.0 * G + 2.0 / 3.0 * m->H);
        for (int k = 0; k < 9; k++) eps[k] -= dgam * dev[k] / norm; /* radial return, flow s / |s| */
        xi = s->xi + sq23 * dgam;
      }
    }
  }
  cx tau1[9];
  for (int k = 0; k < 9; k++) tau1[k] = 2.0 * G * eps[k] + (k % 4 == 0 ? lambda * tr : 0);
  cx psi1 = 0.5 * lambda * tr * tr + G * cddot(eps, eps) + 0.5 * m->H * xi * xi;
  cx dD = sq23 * (plastic(m) ? m->yield : 0.0) * dgam; /* tau:dPhi/dtau + q dPhi/dq = sqrt(2/3) sigma_y */

  /* algorithmic Kirchhoff stress (001 Eqs. 48-51, 56) */
  cx tau_pf[9], taubar[9], Ct[9], C[9], FT[9], FtT[9], dC[9], Finv[9], FinvT[9], tmp[9], dbar[9];
  cpush(dF, tau_t, tau_pf);
  for (int k = 0; k < 9; k++) taubar[k] = 0.5 * (tau_pf[k] + tau1[k]); /* 001 Eq. 49 */
  ctrans(F, FT);
  ctrans(Ft, FtT);
  cmul(FT, F, C);
  cmul(FtT, Ft, Ct);
  for (int k = 0; k < 9; k++) dC[k] = C[k] - Ct[k];
  cinv(F, Finv);
  ctrans(Finv, FinvT);
  cmul(FinvT, dC, tmp);
  cmul(tmp, Finv, dbar);
  for (int k = 0; k < 9; k++) dbar[k] *= 0.5; /* 001 Eq. 46 */
  cx taump[9];
  memcpy(taump, taubar, sizeof taump);
  cx nC = cddot(dC, dC);
  /* the correction is O(|dC|^2) relative to tau; below |dC| = 1e-8 it is
   * under round-off, while dH / |dC|^2 would only amplify round-off */
  if (creal(nC) > 1e-16) {
    cx dH = 2.0 * (psi1 - s->psi + dD) - 2.0 * cddot(taubar, dbar); /* 001 Eq. 56 (first line) */
    cx dbPF[9];
    cpush(F, dC, dbPF); /* Delta^PF b = F dC F^T, 001 Eq. 50 */
    for (int k = 0; k < 9; k++) taump[k] += dbPF[k] * (dH / nC); /* 001 Eq. 51 */
  }

  /* P = dF_theta dF^-1 tau_mp dF^-T (001 Eq. 44 on the grid of the step) */
  cx dFinv[9], dFth[9], A[9], B[9];
  cinv(dF, dFinv);
  for (int k = 0; k < 9; k++) dFth[k] = 0.5 * (dF[k] + (k % 4 == 0 ? 1.0 : 0.0)); /* 001 Eqs. 22, 42 */
  cmul(dFth, dFinv, A);
  cmul(A, taump, B);
  cx dFinvT[9];
  ctrans(dFinv, dFinvT);
  cmul(B, dFinvT, P);

  if (end) {
    exp2_sym(eps, end->be);
    for (int k = 0; k < 9; k++) end->tau[k] = creal(tau1[k]);
    end->psi = creal(psi1);
    end->xi = creal(xi);
    end->dissipation = creal(dD);
  }
}

void mrn_emc_tangent(const mrn_emc_material *m, const mrn_emc_state *s, const double dF[9], int dim,
                     double P[9], double D[81], mrn_emc_result *end) {
  const double h = 1e-30; /* complex step: no subtraction, so any small h is exact */
  int first = 1;
  for (int k = 0; k < dim; k++)
    for (int l = 0; l < dim; l++) {
      cx dFc[9], Pc[9];
      for (int q = 0; q < 9; q++) dFc[q] = dF[q];
      dFc[3 * k + l] += I * h;
      mrn_emc_stress(m, s, dFc, Pc, first ? end : NULL);
      for (int q = 0; q < 9; q++) {
        D[9 * (3 * k + l) + q] = cimag(Pc[q]) / h;
        if (first) P[q] = creal(Pc[q]);
      }
      first = 0;
    }
}

void mrn_emc_hencky(const mrn_emc_material *m, const double be[9], double tau[9], double *psi) {
  cx b[9], e[9];
  for (int k = 0; k < 9; k++) b[k] = be[k];
  clog_sym(b, e);
  double tr = 0.5 * creal(e[0] + e[4] + e[8]), ee = 0.0;
  for (int k = 0; k < 9; k++) {
    double ek = 0.5 * creal(e[k]);
    tau[k] = 2.0 * m->G * ek + (k % 4 == 0 ? m->lambda * tr : 0.0);
    ee += ek * ek;
  }
  *psi = 0.5 * m->lambda * tr * tr + m->G * ee;
}
