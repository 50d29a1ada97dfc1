/* moraine: the batched, dimension-specialised material-point update
 * (material/advance.c) and the plane-strain eigen-decomposition
 * (material/principal.c) against the general 3D code they replace. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/tensor.h"
#include "material/advance.h"
#include "material/material.h"
#include "material/principal.h"

static double uniform(unsigned *seed, double lo, double hi) {
  *seed = *seed * 1103515245u + 12345u;
  return lo + (hi - lo) * ((*seed >> 8) & 0xffffff) / (double)0xffffff;
}

/* With s_xz = s_yz = 0 the plane-strain path of mrn_sym_eigen must give the
 * general Jacobi solver's result (it performs the same single rotation) to
 * round-off of the tensor's size (1e-15; the compiler may fuse the
 * multiply-adds differently in the two), including diagonal and isotropic
 * stresses, whose eigenvectors must then be the same axes. */
static void test_plane_eigen(void) {
  unsigned seed = 7;
  double worst = 0.0, dlam = 0.0, dV = 0.0;
  for (int i = 0; i < 2000; i++) {
    double s[6] = {uniform(&seed, -1e5, 1e5), uniform(&seed, -1e5, 1e5), uniform(&seed, -1e5, 1e5),
                   uniform(&seed, -1e5, 1e5), 0.0, 0.0};
    if (i % 10 == 1) s[SXY] = 0.0;               /* already principal */
    if (i % 10 == 2) s[SYY] = s[SXX];             /* equal diagonal */
    if (i % 10 == 3) s[SXX] = s[SYY] = s[SZZ] = -2e4, s[SXY] = 0.0; /* isotropic */
    double lam[3], V[9], lam_ref[3], V_ref[9], S[9], back[6];
    mrn_sym_eigen(s, lam, V);
    sym_to_mat(s, S);
    mrn_jacobi_eigen(3, S, lam_ref, V_ref);
    for (int k = 0; k < 3; k++) dlam = fmax(dlam, fabs(lam[k] - lam_ref[k]) / 1e5);
    for (int k = 0; k < 9; k++) dV = fmax(dV, fabs(V[k] - V_ref[k]));
    CHECK(lam[0] >= lam[1] && lam[1] >= lam[2]);
    mrn_sym_from_principal(lam, V, back);
    for (int k = 0; k < 6; k++) worst = fmax(worst, fabs(back[k] - s[k]) / 1e5);
  }
  CHECK(dlam < 1e-15);
  CHECK(dV < 1e-15);
  CHECK(worst < 1e-14);
}

static mrn_material *material(const mrn_material_type *type) {
  mrn_material *m = mrn_material_new(type);
  CHECK(mrn_material_set(m, "density", 2000) == 0);
  CHECK(mrn_material_set(m, "E", 1e7) == 0);
  CHECK(mrn_material_set(m, "nu", 0.3) == 0);
  if (type == &mrn_material_mohr_coulomb) {
    CHECK(mrn_material_set(m, "phi", 30) == 0);
    CHECK(mrn_material_set(m, "cohesion", 1e3) == 0);
  }
  CHECK(mrn_material_prepare(m) == 0);
  return m;
}

enum { NP = 69, NSTEP = 200 }; /* NP spans two full batches and a partial one */

/* Random plane-strain histories through the 2D path (F stored as its
 * in-plane block) and through the general 3D path (batched and one point at
 * a time): the same state to round-off. */
static void test_plane_vs_general(const mrn_material_type *type) {
  mrn_material *m = material(type);
  const int ns = m->type->nstate;
  static double F2[NP][4], F3[NP][9], F1[NP][9], s2[NP][6], s3[NP][6], s1[NP][6], e2[NP][6], e3[NP][6], e1[NP][6];
  static double st2[NP][2], st3[NP][2], st1[NP][2], L[NP][9];
  mrn_point_result r2[NP], r3[NP], r1;
  unsigned seed = 11;
  for (int p = 0; p < NP; p++) {
    mat_identity(F3[p]);
    F2[p][0] = F2[p][3] = 1.0, F2[p][1] = F2[p][2] = 0.0;
    double s0[6] = {uniform(&seed, -5e4, 0), uniform(&seed, -5e4, 0), uniform(&seed, -5e4, 0),
                    uniform(&seed, -1e4, 1e4), 0.0, 0.0};
    if (p % 7 == 0) s0[SYZ] = 3e3, s0[SXZ] = -2e3; /* an initial out-of-plane shear rotates too */
    memcpy(s2[p], s0, sizeof s0);
  }
  memset(e2, 0, sizeof e2);
  memset(st2, 0, sizeof st2);
  memcpy(F1, F3, sizeof F3);
  memcpy(s3, s2, sizeof s2), memcpy(s1, s2, sizeof s2);
  memcpy(e3, e2, sizeof e2), memcpy(e1, e2, sizeof e2);
  memcpy(st3, st2, sizeof st2), memcpy(st1, st2, sizeof st2);
  const double dt = 1e-3;
  for (int step = 0; step < NSTEP; step++) {
    for (int p = 0; p < NP; p++) {
      memset(L[p], 0, sizeof L[p]);
      for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) L[p][3 * a + b] = uniform(&seed, -1.0, 1.0);
    }
    for (int kind = 0; kind < 2; kind++) {
      mrn_f_update fu = kind ? MRN_F_UPDATE_EULER : MRN_F_UPDATE_MIDPOINT;
      CHECK(mrn_material_advance_points(m, 2, fu, dt, NP, L[0], F2[0], s2[0], e2[0], ns ? st2[0] : NULL, 2, NULL, r2) < 0);
      CHECK(mrn_material_advance_points(m, 3, fu, dt, NP, L[0], F3[0], s3[0], e3[0], ns ? st3[0] : NULL, 2, NULL, r3) < 0);
      for (int p = 0; p < NP; p++) {
        CHECK(mrn_material_advance(m, L[p], dt, fu, F1[p], s1[p], e1[p], ns ? st1[p] : NULL, &r1) == 0);
        /* the batched 3D path is the one-point path, bit for bit */
        CHECK(r1.J == r3[p].J && r1.de_elastic == r3[p].de_elastic &&
              r1.dw_plastic == r3[p].dw_plastic);
        CHECK_CLOSE(r2[p].J, r3[p].J, 1e-14);
        CHECK_CLOSE(r2[p].de_elastic, r3[p].de_elastic, 1e-9);
      }
    }
  }
  double dF = 0.0, ds = 0.0, de = 0.0, dst = 0.0;
  for (int p = 0; p < NP; p++) {
    double F2_full[9];
    mrn_tensor_expand(2, F2[p], 1.0, F2_full);
    for (int k = 0; k < 9; k++) dF = fmax(dF, fabs(F2_full[k] - F3[p][k]));
    for (int k = 0; k < 6; k++) ds = fmax(ds, fabs(s2[p][k] - s3[p][k]) / 5e4);
    for (int k = 0; k < 6; k++) de = fmax(de, fabs(e2[p][k] - e3[p][k]));
    for (int k = 0; k < 2; k++) dst = fmax(dst, fabs(st2[p][k] - st3[p][k]));
  }
  CHECK(memcmp(F1, F3, sizeof F1) == 0 && memcmp(s1, s3, sizeof s1) == 0 && memcmp(e1, e3, sizeof e1) == 0);
  /* all 9 components: the general path keeps the plane-strain z row and
   * column (F_zz = 1, no z coupling) that the 2D storage leaves out */
  CHECK(dF < 1e-12);
  CHECK(ds < 1e-10);
  CHECK(de < 1e-12);
  CHECK(dst < 1e-10);
  mrn_material_unref(m);
}

/* A point whose increment would invert F is reported and left unchanged;
 * the others of its batch are advanced. */
static void test_inversion(void) {
  mrn_material *m = material(&mrn_material_linear_elastic);
  double L[3][9] = {{0}}, F[3][4] = {{1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}}; /* 2D: in-plane blocks */
  double s[3][6] = {{0}}, e[3][6] = {{0}};
  mrn_point_result r[3];
  const double dt = 1e-2;
  for (int p = 0; p < 3; p++) L[p][1] = 1.0;
  L[1][0] = -2.0 / dt; /* Euler: F_xx = 1 - 2 < 0 */
  CHECK(mrn_material_advance_points(m, 2, MRN_F_UPDATE_EULER, dt, 3, L[0], F[0], s[0], e[0], NULL, 0, NULL, r) == 1);
  CHECK(r[1].inverted && !r[0].inverted && !r[2].inverted);
  CHECK(F[1][0] == 1.0 && F[1][1] == 0.0 && s[1][SXY] == 0.0);
  CHECK(F[0][1] == dt && F[2][1] == dt && s[0][SXY] > 0.0);
  mrn_material_unref(m);
}

int main(void) {
  test_plane_eigen();
  test_plane_vs_general(&mrn_material_linear_elastic);
  test_plane_vs_general(&mrn_material_mohr_coulomb);
  test_inversion();
  CHECK_DONE();
}
