/* moraine: the memory estimate made before a large seeding (mrn_sim_seed). */
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "particles/region.h"
#include "solver/simulation.h"

static mrn_sim *make(int dim, double size, double cell) {
  mrn_sim_config cfg = {.dim = dim, .origin = {0, 0, 0}, .size = {size, size, dim == 3 ? size : 0}, .cell = cell};
  mrn_sim *sim = mrn_sim_new(&cfg);
  CHECK(sim != NULL);
  return sim;
}

static int add_material(mrn_sim *sim, const mrn_material_type *type) {
  mrn_material *mat = mrn_material_new(type);
  mrn_material_set(mat, "density", 1000);
  mrn_material_set(mat, "E", 1e6);
  mrn_material_set(mat, "nu", 0.3);
  if (type == &mrn_material_mohr_coulomb) mrn_material_set(mat, "phi", 30);
  CHECK(mrn_material_prepare(mat) == MRN_OK);
  int index = mrn_sim_add_material(sim, mat);
  mrn_material_unref(mat);
  return index;
}

/* a particle's bytes: every field of the list in the simulation's dimension,
 * material and id, then its history variables and registered fields */
static void test_record_bytes(void) {
  for (int dim = 2; dim <= 3; dim++) {
    mrn_sim *sim = make(dim, 1.0, 0.1);
    size_t fields = 0;
    for (int i = 0; i < mrn_particle_field_count(); i++)
      fields += sizeof(double) * (size_t)mrn_particle_field_stride(&sim->particles, mrn_particle_field_at(i));
    CHECK(fields == (dim == 3 ? 43 : 33) * sizeof(double));
    CHECK(mrn_particles_record_bytes(&sim->particles) == fields + 12);
    add_material(sim, &mrn_material_mohr_coulomb); /* history variables */
    const int stride = sim->particles.state_stride;
    CHECK(stride > 0);
    CHECK(mrn_particles_add_user_field(&sim->particles, "damage", 3, 0.0, "") == MRN_OK);
    CHECK(mrn_particles_record_bytes(&sim->particles) == fields + 12 + sizeof(double) * (size_t)(stride + 3));
    CHECK(mrn_sim_particle_bytes(sim) > mrn_particles_record_bytes(&sim->particles));
    mrn_sim_free(sim);
  }
}

/* a small seeding: the bound of its bounding box, not counted */
static void test_small(void) {
  mrn_sim *sim = make(2, 1.0, 0.1);
  int mat = add_material(sim, &mrn_material_linear_elastic);
  mrn_region *box = mrn_region_box((double[3]){0.2, 0.2, 0}, (double[3]){0.6, 0.6, 0});
  mrn_seed_estimate e;
  CHECK(mrn_sim_seed_estimate(sim, box, 2, MRN_SEED_GAUSS, &e) == MRN_OK);
  CHECK(!e.exact);
  CHECK(e.count == 64); /* 16 cells of 4 */
  CHECK(e.bytes == 64.0 * (double)mrn_sim_particle_bytes(sim));
  size_t first;
  long count;
  CHECK(mrn_sim_seed(sim, box, mat, 2, MRN_SEED_GAUSS, &first, &count) == MRN_OK);
  CHECK(count == 64);
  mrn_region_unref(box);
  mrn_sim_free(sim);
}

/* A slanted thin cylinder across a 3D grid: its bounding box holds 1e7
 * seeding points (4 GB of particles), the cylinder under 1 % of them. The
 * estimate counts them exactly, the seeding adds that many, into arrays
 * reserved for exactly that many (not grown by doubling). */
static void test_counted(void) {
  mrn_sim *sim = make(3, 0.6, 0.01);
  int mat = add_material(sim, &mrn_material_linear_elastic);
  mrn_region *rod = mrn_region_cylinder((double[3]){0.05, 0.05, 0.05}, (double[3]){0.55, 0.55, 0.55}, 0.02);
  double bound;
  CHECK(mrn_seed_candidates(&sim->grid, rod, 4, &bound) == MRN_OK);
  CHECK(bound * (double)mrn_sim_particle_bytes(sim) > MRN_SEED_REPORT_BYTES);
  mrn_seed_estimate e;
  CHECK(mrn_sim_seed_estimate(sim, rod, 4, MRN_SEED_GAUSS, &e) == MRN_OK);
  CHECK(e.exact);
  CHECK(e.count > 0 && e.count < 0.01 * bound);
  CHECK(e.bytes == e.count * (double)mrn_sim_particle_bytes(sim));
  size_t first;
  long count;
  CHECK(mrn_sim_seed(sim, rod, mat, 4, MRN_SEED_GAUSS, &first, &count) == MRN_OK);
  CHECK((double)count == e.count);
  CHECK(sim->particles.cap == sim->particles.n);
  printf("slanted cylinder: %.3g seeding points in its bounding box, %ld particles, %.1f MB\n", bound, count,
         e.bytes / 1e6);
  mrn_region_unref(rod);
  mrn_sim_free(sim);
}

/* 1.1e9 seeding points: more than one seeding counts, so the bound is
 * checked, and no machine moraine's tests run on holds its 445 GB */
static void test_refused(void) {
  mrn_sim *sim = make(3, 1.3, 0.01);
  int mat = add_material(sim, &mrn_material_linear_elastic);
  mrn_region *all = mrn_region_box((double[3]){0, 0, 0}, (double[3]){1.3, 1.3, 1.3});
  size_t first;
  long count = -1;
  CHECK(mrn_sim_seed(sim, all, mat, 8, MRN_SEED_GAUSS, &first, &count) == MRN_ERR);
  const char *msg = mrn_error_message();
  CHECK(strstr(msg, "up to 1.12e+09 particles (the seeding points of the region's bounding box) need ") == msg);
  CHECK(strstr(msg, "GB, more than this machine's ") != NULL);
  CHECK(sim->particles.n == 0);
  mrn_region_unref(all);
  mrn_sim_free(sim);
}

int main(void) {
  test_record_bytes();
  test_small();
  test_counted();
  test_refused();
  CHECK_DONE();
}
