/* moraine: the implicit step's volumetric averaging (src/implicit/bbar.c) on
 * a small elasto-plastic body, 2D and 3D, linear, gimp and quadratic shapes:
 *  - the assembled stiffness is the derivative of the assembled internal
 *    force (central differences, relative 1e-6);
 *  - u . f_int = sum V_0 (dpsi + dD) (the energy identity of 001 Eq. 56
 *    survives the averaging) to 1e-10;
 *  - the forces sum to zero (linear momentum) to round-off;
 *  - an affine displacement gives every point its own increment. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/tensor.h"
#include "implicit/implicit_internal.h"
#include "particles/region.h"

static double frand(unsigned *state) {
  *state = *state * 1103515245u + 12345u;
  return ((*state >> 8) & 0xffff) / 65535.0 - 0.5;
}

static mrn_implicit *make(int dim, mrn_shape_kind shape, int bbar) {
  mrn_sim_config cfg = {.dim = dim, .size = {2, 2, dim == 3 ? 2 : 0}, .cell = 0.25, .shape = shape};
  mrn_sim *sim = mrn_sim_new(&cfg);
  mrn_material *m = mrn_material_new(&mrn_material_von_mises);
  mrn_material_set(m, "density", 1000);
  mrn_material_set(m, "E", 1e7);
  mrn_material_set(m, "nu", 0.3);
  mrn_material_set(m, "yield", 2e4); /* low: the test displacements yield most points */
  mrn_material_set(m, "hardening", 1e5);
  mrn_material_prepare(m);
  int mi = mrn_sim_add_material(sim, m);
  mrn_material_unref(m); /* the simulation holds it */
  const double lo[3] = {0.6, 0.55, dim == 3 ? 0.6 : 0}, hi[3] = {1.35, 1.3, dim == 3 ? 1.1 : 0};
  mrn_region *r = mrn_region_box(lo, hi);
  size_t first;
  long count;
  CHECK(mrn_sim_seed(sim, r, mi, 2, MRN_SEED_GAUSS, &first, &count) == 0);
  mrn_region_unref(r);
  mrn_implicit_options o;
  mrn_implicit_options_default(&o);
  o.dt = 1e-3;
  o.bbar = bbar;
  mrn_implicit *im = mrn_implicit_new(sim, &o);
  CHECK(im != NULL);
  CHECK(mrn_implicit_setup_step(im) == 0);
  mrn_implicit_map_to_grid(im);
  CHECK(mrn_implicit_cell_volumes(im) == 0);
  CHECK(mrn_implicit_bbar_setup(im) == 0);
  return im;
}

static void random_u(mrn_implicit *im, double amp, unsigned seed) {
  memset(im->u, 0, 3 * im->nact * sizeof(double));
  for (size_t a = 0; a < im->nact; a++)
    for (int d = 0; d < im->dim; d++) im->u[3 * a + d] = amp * frand(&seed);
}

static void check_tangent(int dim, mrn_shape_kind shape) {
  mrn_implicit *im = make(dim, shape, 1);
  const size_t nact = im->nact, NR = (size_t)im->NR;
  random_u(im, 2e-3, 7u + (unsigned)dim);
  mrn_implicit_assemble(im);
  double *K = malloc(nact * NR * 9 * sizeof(double)), *fp = malloc(3 * nact * sizeof(double));
  memcpy(K, im->Kb, nact * NR * 9 * sizeof(double));

  /* energy identity and momentum at this state */
  double uf = 0.0, work = 0.0, fsum[3] = {0, 0, 0}, fmaxabs = 0.0;
  for (size_t q = 0; q < 3 * nact; q++) uf += im->u[q] * im->fint[q];
  for (size_t a = 0; a < nact; a++)
    for (int d = 0; d < 3; d++) fsum[d] += im->fint[3 * a + d], fmaxabs = fmax(fmaxabs, fabs(im->fint[3 * a + d]));
  int plastic = 0;
  for (size_t p = 0; p < im->np; p++) {
    work += im->sim->particles.vol0[p] * (im->res[p].psi - im->st[p].psi + im->res[p].dissipation);
    plastic += im->res[p].dissipation > 0.0;
  }
  printf("%dD %s: %zu points (%d plastic), %zu nodes, %zu cells; u.f %.6e J, sum V0 (dpsi + dD) %.6e J\n", dim,
         mrn_shape_info_of(shape)->name, im->np, plastic, nact, im->bb_n, uf, work);
  CHECK(plastic > 0);
  CHECK(fabs(uf - work) <= 1e-10 * fabs(work));
  for (int d = 0; d < 3; d++) CHECK(fabs(fsum[d]) <= 1e-12 * fmaxabs * (double)nact);

  /* K column (b, k) against central differences of f_int */
  const double h = 1e-9;
  double worst = 0.0, big = 0.0;
  for (size_t b = 0; b < nact; b += 3)
    for (int k = 0; k < dim; k++) {
      const double u0 = im->u[3 * b + k];
      im->u[3 * b + k] = u0 + h;
      mrn_implicit_assemble(im);
      memcpy(fp, im->fint, 3 * nact * sizeof(double));
      im->u[3 * b + k] = u0 - h;
      mrn_implicit_assemble(im);
      im->u[3 * b + k] = u0;
      for (size_t a = 0; a < nact; a++)
        for (int i = 0; i < dim; i++) {
          double fd = (fp[3 * a + i] - im->fint[3 * a + i]) / (2 * h), an = 0.0;
          int di = im->ijk[3 * a] - im->ijk[3 * b], dj = im->ijk[3 * a + 1] - im->ijk[3 * b + 1],
              dk = im->ijk[3 * a + 2] - im->ijk[3 * b + 2];
          if (abs(di) <= im->R && abs(dj) <= im->R && abs(dk) <= im->R)
            an = K[9 * (b * NR + (size_t)mrn_implicit_pair_index(im, a, b)) + 3 * i + k];
          worst = fmax(worst, fabs(fd - an));
          big = fmax(big, fabs(fd));
        }
    }
  printf("  stiffness vs central differences: relative difference %.2e\n", worst / big);
  CHECK(worst / big < 1e-6);
  free(K), free(fp);

  /* an affine displacement: every point keeps its own increment */
  const double A[9] = {2e-3, 1e-3, -5e-4, -7e-4, 1.5e-3, 3e-4, 4e-4, -2e-4, -1e-3};
  for (size_t a = 0; a < nact; a++) {
    double x[3];
    mrn_grid_node_position(&im->sim->grid, im->act[a], x);
    for (int i = 0; i < 3; i++)
      im->u[3 * a + i] = i < dim ? A[3 * i] * x[0] + A[3 * i + 1] * x[1] + (dim == 3 ? A[3 * i + 2] * x[2] : 0) : 0;
  }
  mrn_implicit_bbar_theta(im);
  double dev = 0.0;
  for (size_t p = 0; p < im->np; p++) {
    double dFb[9], dF[9];
    mrn_implicit_point_increment(im, p, dFb);
    mrn_implicit_increment(im, &im->sten[p], dF);
    for (int q = 0; q < 9; q++) dev = fmax(dev, fabs(dFb[q] - dF[q]));
  }
  printf("  affine displacement: largest change of a point's increment %.2e\n", dev);
  CHECK(dev < 1e-14);
  mrn_sim *sim = im->sim;
  mrn_implicit_free(im);
  mrn_sim_free(sim);
}

int main(void) {
  check_tangent(2, MRN_SHAPE_LINEAR);
  check_tangent(2, MRN_SHAPE_GIMP);
  check_tangent(3, MRN_SHAPE_GIMP);
  check_tangent(3, MRN_SHAPE_QUADRATIC_BSPLINE);
  CHECK_DONE();
}
