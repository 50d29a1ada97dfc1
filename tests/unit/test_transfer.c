/* moraine: P2G conserves mass and linear momentum to round-off, for every
 * shape function, in 2D and 3D, with particles everywhere in the grid
 * including the cells next to the boundary; internal forces sum to zero
 * (sum_i grad N_i = 0); the partition of unity holds at every particle. */
#include <stdlib.h>

#include "check.h"
#include "solver/simulation.h"
#include "transfer/kernels.h"

static double rnd(unsigned *state) {
  *state = *state * 1664525u + 1013904223u;
  return (*state >> 8) / 16777216.0;
}

static void run_case(int dim, mrn_shape_kind shape) {
  mrn_sim_config cfg = {.dim = dim, .origin = {-0.3, 0.7, 1.1}, .size = {1.2, 0.8, 0.6}, .cell = 0.1, .shape = shape};
  mrn_sim *sim = mrn_sim_new(&cfg);
  CHECK(sim != NULL);
  mrn_material *mat = mrn_material_new(&mrn_material_linear_elastic);
  mrn_material_set(mat, "density", 1000);
  mrn_material_set(mat, "E", 1e6);
  mrn_material_set(mat, "nu", 0.3);
  CHECK(mrn_material_prepare(mat) == 0);
  int mi = mrn_sim_add_material(sim, mat);
  unsigned seed = 12345u + (unsigned)(dim * 10 + shape);
  double mass = 0, mom[3] = {0, 0, 0};
  /* random particles everywhere, plus particles exactly on and next to every face */
  for (int i = 0; i < 3000; i++) {
    double x[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) {
      double u = rnd(&seed);
      if (i % 5 == 0) u = (i / 5) % 2 ? 1.0 - 0.01 * rnd(&seed) : 0.01 * rnd(&seed); /* boundary cells */
      if (i == 1) u = 0.0;
      if (i == 2) u = 1.0;
      x[d] = cfg.origin[d] + u * cfg.size[d];
    }
    double m = 0.5 + rnd(&seed);
    long p = mrn_particles_add(&sim->particles, x, m, m / 1000, mi);
    CHECK(p >= 0);
    for (int d = 0; d < dim; d++) {
      sim->particles.v[3 * p + d] = rnd(&seed) - 0.5;
      mom[d] += m * sim->particles.v[3 * p + d];
    }
    for (int k = 0; k < 6; k++) sim->particles.stress[6 * p + k] = 1e3 * (rnd(&seed) - 0.5);
    mass += m;
  }
  mrn_sim_particles_changed(sim);
  mrn_transfer tr = mrn_sim_transfer(sim);
  mrn_p2g(&tr, 1, 1);
  double gm = 0, gp[3] = {0, 0, 0}, gf[3] = {0, 0, 0}, fscale = 0;
  for (size_t n = 0; n < sim->grid.n; n++) {
    gm += sim->grid.mass[n];
    for (int d = 0; d < 3; d++) {
      gp[d] += sim->grid.mom[3 * n + d];
      gf[d] += sim->grid.force[3 * n + d];
      fscale += fabs(sim->grid.force[3 * n + d]);
    }
  }
  CHECK_CLOSE(gm, mass, 1e-12);
  for (int d = 0; d < dim; d++) {
    CHECK_CLOSE(gp[d], mom[d], 1e-12);
    CHECK(fabs(gf[d]) <= 1e-12 * fscale);
  }
  /* partition of unity through G2P of a uniform nodal field: every particle
   * gets exactly the uniform velocity back (PIC) */
  sim->scheme.velocity_update = MRN_VUPDATE_PIC;
  for (size_t n = 0; n < sim->grid.n; n++)
    for (int d = 0; d < 3; d++) {
      sim->grid.vel_new[3 * n + d] = d < dim ? 0.25 * (d + 1) : 0.0;
      sim->grid.vel[3 * n + d] = sim->grid.vel_new[3 * n + d]; /* no acceleration */
    }
  mrn_g2p(&tr, 1e-9, sim->particles.x0);
  double worst = 0;
  for (size_t p = 0; p < sim->particles.n; p++)
    for (int d = 0; d < dim; d++) worst = fmax(worst, fabs(sim->particles.v[3 * p + d] - 0.25 * (d + 1)));
  CHECK(worst < 1e-14);
  mrn_material_unref(mat);
  mrn_sim_free(sim);
}

int main(void) {
  for (int dim = 2; dim <= 3; dim++)
    for (int s = 0; s < MRN_SHAPE_KIND_COUNT; s++)
      if (mrn_shape_takes_dim((mrn_shape_kind)s, dim)) run_case(dim, (mrn_shape_kind)s);
  CHECK_DONE();
}
