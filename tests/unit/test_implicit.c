/* moraine: pieces of the implicit integrator (src/implicit): the tangent of
 * the algorithmic stress against finite differences, the discrete energy
 * identity of 001 Eq. 56, and the UMFPACK wrapper. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "implicit/emc_stress.h"
#include "implicit/linear_solver.h"

static void mat3_mul(const double A[9], const double B[9], double C[9]) {
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) C[3 * a + b] = A[3 * a] * B[b] + A[3 * a + 1] * B[3 + b] + A[3 * a + 2] * B[6 + b];
}

/* a start-of-step state: F_t given, elastic b_e = F_t F_t^T, Hencky stress */
static void make_state(const mrn_emc_material *m, const double Ft[9], mrn_emc_state *s) {
  memset(s, 0, sizeof *s);
  memcpy(s->Ft, Ft, sizeof s->Ft);
  double FtT[9];
  for (int a = 0; a < 3; a++)
    for (int c = 0; c < 3; c++) FtT[3 * a + c] = Ft[3 * c + a];
  mat3_mul(Ft, FtT, s->be);
  mrn_emc_hencky(m, s->be, s->tau, &s->psi);
}

static void real_stress(const mrn_emc_material *m, const mrn_emc_state *s, const double dF[9], double P[9],
                        mrn_emc_result *end) {
  double complex c[9], Pc[9];
  for (int k = 0; k < 9; k++) c[k] = dF[k];
  mrn_emc_stress(m, s, c, Pc, end);
  for (int k = 0; k < 9; k++) P[k] = creal(Pc[k]);
}

/* largest |D_cs - D_fd| over max |D| for central differences with step h */
static double tangent_error(const mrn_emc_material *m, const mrn_emc_state *s, const double dF[9], int dim) {
  double P[9], D[81], Pp[9], Pm[9], worst = 0.0, big = 0.0;
  mrn_emc_tangent(m, s, dF, dim, P, D, NULL);
  const double h = 1e-6;
  for (int k = 0; k < dim; k++)
    for (int l = 0; l < dim; l++) {
      double a[9], b[9];
      memcpy(a, dF, sizeof a), memcpy(b, dF, sizeof b);
      a[3 * k + l] += h, b[3 * k + l] -= h;
      real_stress(m, s, a, Pp, NULL);
      real_stress(m, s, b, Pm, NULL);
      for (int q = 0; q < 9; q++) {
        double fd = (Pp[q] - Pm[q]) / (2 * h);
        worst = fmax(worst, fabs(fd - D[9 * (3 * k + l) + q]));
        big = fmax(big, fabs(fd));
      }
    }
  return worst / big;
}

/* P : (dF - I) against psi_t+dt - psi_t + dD (001 Eq. 56) */
static double energy_error(const mrn_emc_material *m, const mrn_emc_state *s, const double dF[9], double *work) {
  double P[9];
  mrn_emc_result end;
  real_stress(m, s, dF, P, &end);
  double w = 0.0;
  for (int q = 0; q < 9; q++) w += P[q] * (dF[q] - (q % 4 == 0 ? 1.0 : 0.0));
  *work = w;
  return fabs(w - (end.psi - s->psi + end.dissipation)) / fabs(w);
}

int main(void) {
  const double E = 1e9, nu = 0.2;
  mrn_emc_material el = {E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu)), 0.0, 0.0};
  const double Ft[9] = {1.02, 0.05, 0.01, -0.03, 0.97, 0.02, 0.01, -0.02, 1.01};
  const double dF3[9] = {1.004, 0.003, -0.002, 0.001, 0.996, 0.002, 0.003, -0.001, 1.002};
  const double dF2[9] = {1.004, 0.003, 0, -0.002, 0.997, 0, 0, 0, 1};
  mrn_emc_state s;
  make_state(&el, Ft, &s);

  /* complex-step tangent vs central differences, 3D and plane strain */
  double e3 = tangent_error(&el, &s, dF3, 3), e2 = tangent_error(&el, &s, dF2, 2);
  printf("elastic tangent: relative difference to finite differences %.2e (3D), %.2e (2D)\n", e3, e2);
  CHECK(e3 < 1e-6);
  CHECK(e2 < 1e-6);

  /* elasto-plastic step: yield low enough that the step returns to the surface */
  mrn_emc_material pl = el;
  pl.yield = 2e6;
  pl.H = 1e8;
  mrn_emc_state sp;
  make_state(&pl, Ft, &sp);
  mrn_emc_result end;
  double P[9];
  real_stress(&pl, &sp, dF3, P, &end);
  CHECK(end.dissipation > 0.0);
  double ep = tangent_error(&pl, &sp, dF3, 3);
  printf("elasto-plastic tangent: relative difference %.2e, dissipation %.4g J/m^3\n", ep, end.dissipation);
  CHECK(ep < 1e-6);

  /* the discrete energy identity holds to round-off (001 Eqs. 52, 56) */
  double w, ee = energy_error(&el, &s, dF3, &w), eep = energy_error(&pl, &sp, dF3, &w);
  printf("energy identity: relative error %.2e (elastic), %.2e (plastic)\n", ee, eep);
  CHECK(ee < 1e-10);
  CHECK(eep < 1e-10);

  /* a rigid rotation increment leaves psi unchanged and does no work */
  double c = cos(0.3), sn = sin(0.3);
  const double Rz[9] = {c, -sn, 0, sn, c, 0, 0, 0, 1};
  real_stress(&el, &s, Rz, P, &end);
  CHECK_CLOSE(end.psi, s.psi, 1e-12);

  /* UMFPACK wrapper: [[4,1,0],[2,5,1],[0,1,3]] x = b */
  mrn_csc A = {0};
  CHECK(mrn_csc_reset(&A, 3) == 0);
  const int rows[3][3] = {{0, 1, -1}, {0, 1, 2}, {1, 2, -1}};
  const double vals[3][3] = {{4, 2, 0}, {1, 5, 1}, {1, 3, 0}};
  for (int col = 0; col < 3; col++) {
    for (int k = 0; k < 3; k++)
      if (rows[col][k] >= 0) CHECK(mrn_csc_push(&A, rows[col][k], vals[col][k]) == 0);
    mrn_csc_end_column(&A, col);
  }
  const double xref[3] = {1, -2, 3};
  double b[3], x[3];
  mrn_csc_multiply(&A, xref, b);
  CHECK(mrn_linear_solve(&A, b, x) == 0);
  for (int i = 0; i < 3; i++) CHECK_CLOSE(x[i], xref[i], 1e-14);
  mrn_csc_free(&A);
  CHECK_DONE();
}
