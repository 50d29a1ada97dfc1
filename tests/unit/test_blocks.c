/* moraine: P2G binned by blocks (transfer/blocks.h) gives bitwise the same
 * nodal values on 1 and on 2 threads; every nodal array is zero outside the
 * active spans, also after the particles moved away; the grid loops' ranges
 * cover every node with mass; reordering the particles keeps every field
 * with its particle, and a run that sorts the particles every few steps ends
 * in the same state (by id) as one that does not, to round-off; a P2G that
 * reuses the previous binning gives the same nodal values as one that bins;
 * a binning patched for the particles that changed block is the binning
 * from scratch;
 * USF's fused material update and force scatter (mrn_update_force) gives
 * bitwise the particle state and nodal forces of the two passes it fuses
 * (both sum the same groups of particles in 2D, kernels_impl.h). */
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "check.h"
#include "material/advance.h"
#include "particles/sort.h"
#include "solver/simulation.h"
#include "solver/update.h"
#include "transfer/blocks.h"
#include "transfer/kernels.h"

static double rnd(unsigned *state) {
  *state = *state * 1664525u + 1013904223u;
  return (*state >> 8) / 16777216.0;
}

/* the transfers and updates on a simulation's own transfer context */
static void p2g(mrn_sim *sim, int momentum, int force) {
  mrn_transfer tr = mrn_sim_transfer(sim);
  mrn_p2g(&tr, momentum, force);
  mrn_sim_transfer_end(sim, &tr);
}
static long gradient(mrn_sim *sim, const double *gvel, const mrn_gradient_sink *sink) {
  mrn_transfer tr = mrn_sim_transfer(sim);
  return mrn_gradient(&tr, gvel, sink);
}
static long update_force(mrn_sim *sim, const double *gvel, const mrn_gradient_sink *sink) {
  mrn_transfer tr = mrn_sim_transfer(sim);
  return mrn_update_force(&tr, gvel, sink);
}
static int update_force_fused(mrn_sim *sim) {
  const mrn_transfer tr = mrn_sim_transfer(sim);
  return mrn_update_force_fused(&tr);
}
static int update_from_grid(mrn_sim *sim, const double *gvel, double dt) {
  mrn_transfer tr = mrn_sim_transfer(sim);
  return mrn_update_from_grid(sim, &tr, gvel, dt);
}
static int update_then_force(mrn_sim *sim, const double *gvel, double dt) {
  mrn_transfer tr = mrn_sim_transfer(sim);
  return mrn_update_then_force(sim, &tr, gvel, dt);
}

static void set_threads(int n) {
#ifdef _OPENMP
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

/* a block of material in a wide grid, particles in random order, random
 * velocities, affine matrices and stresses */
static mrn_sim *make(int dim, mrn_shape_kind shape, int count, unsigned seed) {
  mrn_sim_config cfg = {.dim = dim, .origin = {0, 0, 0}, .size = {4.0, 1.0, 1.0}, .cell = 0.05, .shape = shape};
  mrn_sim *sim = mrn_sim_new(&cfg);
  if (!sim) return NULL;
  mrn_scheme_from_preset("APIC", &sim->scheme);
  for (int f = 0; f < 2 * dim; f++) sim->boundary.face[f].kind = MRN_BC_SLIP;
  mrn_material *mat = mrn_material_new(&mrn_material_linear_elastic);
  mrn_material_set(mat, "density", 1000);
  mrn_material_set(mat, "E", 1e6);
  mrn_material_set(mat, "nu", 0.3);
  mrn_material_prepare(mat);
  int mi = mrn_sim_add_material(sim, mat);
  mrn_material_unref(mat);
  for (int i = 0; i < count; i++) {
    double x[3] = {0.1 + 1.2 * rnd(&seed), 0.05 + 0.5 * rnd(&seed), dim == 3 ? 0.1 + 0.5 * rnd(&seed) : 0.0};
    long p = mrn_particles_add(&sim->particles, x, 0.5 + rnd(&seed), 1e-4, mi);
    for (int d = 0; d < dim; d++) {
      sim->particles.v[3 * p + d] = rnd(&seed) - 0.5;
      for (int e = 0; e < dim; e++) sim->particles.affine[(size_t)mrn_tensor_stride(dim) * p + dim * d + e] = rnd(&seed) - 0.5;
    }
    for (int k = 0; k < 6; k++) sim->particles.stress[6 * p + k] = 1e3 * (rnd(&seed) - 0.5);
  }
  mrn_sim_particles_changed(sim);
  return sim;
}

static int same_grid(const mrn_grid *a, const mrn_grid *b) {
  return !memcmp(a->mass, b->mass, a->n * sizeof(double)) && !memcmp(a->mom, b->mom, 3 * a->n * sizeof(double)) &&
         !memcmp(a->force, b->force, 3 * a->n * sizeof(double));
}

/* every node outside the ranges holds zeros in every array; every node with
 * mass is inside */
static int ranges_hold(const mrn_grid *g) {
  mrn_node_ranges r = mrn_grid_active_ranges(g);
  unsigned char *in = calloc(g->n, 1);
  for (long k = 0; k < r.count; k++)
    for (long i = r.lo[k]; i < r.hi[k]; i++) in[i] = 1;
  int ok = 1;
  for (size_t i = 0; i < g->n && ok; i++) {
    if (in[i]) continue;
    ok &= g->mass[i] == 0.0;
    for (int d = 0; d < 3; d++)
      ok &= g->mom[3 * i + d] == 0.0 && g->force[3 * i + d] == 0.0 && g->vel[3 * i + d] == 0.0 &&
            g->vel_new[3 * i + d] == 0.0;
  }
  free(in);
  return ok;
}

static void threads_and_spans(int dim, mrn_shape_kind shape) {
  mrn_sim *one = make(dim, shape, 20000, 7u + (unsigned)dim), *two = make(dim, shape, 20000, 7u + (unsigned)dim);
  CHECK(one && two);
  set_threads(1);
  p2g(one, 1, 1);
  set_threads(2);
  p2g(two, 1, 1);
  CHECK(same_grid(&one->grid, &two->grid));
  CHECK(ranges_hold(&two->grid));
  /* a full step, then move every particle far to the right: the old spans
   * must be cleared and the result equal that of a fresh simulation */
  CHECK(mrn_sim_step_dt(two, 1e-5) == 0);
  CHECK(ranges_hold(&two->grid));
  for (size_t p = 0; p < two->particles.n; p++) {
    two->particles.x[3 * p] += 2.0;
    two->particles.x[3 * p + 1] += 0.4;
  }
  mrn_sim *fresh = make(dim, shape, 20000, 7u + (unsigned)dim);
  memcpy(fresh->particles.x, two->particles.x, 3 * two->particles.n * sizeof(double));
  memcpy(fresh->particles.v, two->particles.v, 3 * two->particles.n * sizeof(double));
  const size_t ts = (size_t)mrn_tensor_stride(dim);
  memcpy(fresh->particles.affine, two->particles.affine, ts * two->particles.n * sizeof(double));
  memcpy(fresh->particles.stress, two->particles.stress, 6 * two->particles.n * sizeof(double));
  memcpy(fresh->particles.F, two->particles.F, ts * two->particles.n * sizeof(double)); /* the volumes */
  p2g(two, 1, 1);
  set_threads(1);
  p2g(fresh, 1, 1);
  CHECK(same_grid(&fresh->grid, &two->grid));
  CHECK(ranges_hold(&two->grid));
  mrn_sim_free(one);
  mrn_sim_free(two);
  mrn_sim_free(fresh);
}

/* USF's second P2G keeps the binning of the first (mrn_blocks_reuse): the
 * nodal values are bitwise those of a P2G that bins again */
static void reused_binning(int dim) {
  mrn_sim *a = make(dim, MRN_SHAPE_QUADRATIC_BSPLINE, 20000, 11u);
  mrn_sim *b = make(dim, MRN_SHAPE_QUADRATIC_BSPLINE, 20000, 11u);
  CHECK(a && b);
  set_threads(2);
  p2g(a, 1, 0);
  mrn_blocks_reuse(a->blocks);
  p2g(a, 0, 1);
  p2g(b, 1, 0);
  p2g(b, 0, 1);
  CHECK(a->blocks->reuse == 0); /* used up */
  CHECK(same_grid(&a->grid, &b->grid));
  CHECK(ranges_hold(&a->grid));
  mrn_sim_free(a);
  mrn_sim_free(b);
}

/* After the particles moved a little and a few far (across blocks), the
 * binning patched from the previous one (blocks.c, rebin) is the binning
 * from scratch: the same order, block starts and runs, and P2G gives
 * bitwise the same nodes */
static void incremental_rebin(int dim, int threads) {
  mrn_sim *a = make(dim, MRN_SHAPE_QUADRATIC_BSPLINE, 20000, 23u);
  mrn_sim *b = make(dim, MRN_SHAPE_QUADRATIC_BSPLINE, 20000, 23u);
  CHECK(a && b);
  set_threads(threads);
  p2g(a, 1, 1);
  p2g(b, 1, 1);
  unsigned seed = 5u;
  for (int round = 0; round < 3; round++) {
    for (size_t p = 0; p < a->particles.n; p++) {
      const int far = rnd(&seed) < 0.02; /* some 400 particles, most into another block */
      for (int d = 0; d < dim; d++) {
        const double dx = far ? 0.6 * (rnd(&seed) - 0.5) : 1e-3 * (rnd(&seed) - 0.5);
        double x = a->particles.x[3 * p + d] + dx;
        x = x < 0.1 ? 0.1 : x > 0.9 ? 0.9 : x; /* well inside the grid */
        a->particles.x[3 * p + d] = b->particles.x[3 * p + d] = x;
      }
    }
    p2g(a, 1, 1);
    b->blocks->np = 0; /* no previous binning: b bins from scratch */
    p2g(b, 1, 1);
    const mrn_blocks *ba = a->blocks, *bb = b->blocks;
    size_t movers = 0;
    for (int t = 0; t < ba->found_threads; t++) movers += ba->found[t];
    CHECK(movers > 100 && movers < MRN_BLOCK_MOVERS_MAX); /* a was patched */
    CHECK(!memcmp(ba->order, bb->order, a->particles.n * sizeof *ba->order));
    CHECK(!memcmp(ba->start, bb->start, (ba->nblocks + 1) * sizeof *ba->start));
    if (threads == 1) CHECK(ba->runs == bb->runs);
    CHECK(same_grid(&a->grid, &b->grid));
  }
  mrn_sim_free(a);
  mrn_sim_free(b);
}

static void permute_keeps_fields(void) {
  mrn_sim *sim = make(2, MRN_SHAPE_QUADRATIC_BSPLINE, 1000, 3u);
  CHECK(sim != NULL);
  mrn_particles *ps = &sim->particles;
  const size_t n = ps->n;
  mrn_particles_set_state_stride(ps, 2);
  for (size_t i = 0; i < n; i++) {
    ps->F[4 * i + 1] = (double)i; /* 2D: F stored as its in-plane block */
    ps->state[2 * i + 1] = -(double)i;
    ps->material[i] = (int32_t)(i % 7);
  }
  double *x = malloc(3 * n * sizeof(double));
  memcpy(x, ps->x, 3 * n * sizeof(double));
  uint32_t *order = malloc(n * sizeof *order);
  for (size_t i = 0; i < n; i++) order[i] = (uint32_t)((i * 389) % n); /* 389 is prime to 1000 */
  CHECK(mrn_particles_permute(ps, order) == 0);
  int ok = 1;
  for (size_t i = 0; i < n; i++) {
    size_t was = order[i];
    ok &= ps->id[i] == (int64_t)was + 1 && ps->F[4 * i + 1] == (double)was && ps->state[2 * i + 1] == -(double)was &&
          ps->material[i] == (int32_t)(was % 7) && !memcmp(ps->x + 3 * i, x + 3 * was, 3 * sizeof(double));
  }
  CHECK(ok);
  free(order);
  free(x);
  mrn_sim_free(sim);
}

/* the same run with and without sorting, compared particle by particle (by id) */
static void sorted_run(int dim) {
  mrn_sim *a = make(dim, MRN_SHAPE_QUADRATIC_BSPLINE, 5000, 11u), *b = make(dim, MRN_SHAPE_QUADRATIC_BSPLINE, 5000, 11u);
  CHECK(a && b);
  for (int d = 0; d < dim; d++) a->gravity[d] = b->gravity[d] = d == 1 ? -9.81 : 0.0;
  mrn_sim_set_sort_every(b, 3);
  for (int s = 0; s < 10; s++) {
    CHECK(mrn_sim_step_dt(a, 1e-4) == 0);
    CHECK(mrn_sim_step_dt(b, 1e-4) == 0);
  }
  CHECK(b->sorted_step == 9);
  const size_t n = a->particles.n;
  size_t *at = malloc(n * sizeof *at);
  for (size_t i = 0; i < n; i++) at[b->particles.id[i] - 1] = i;
  double dv = 0, vs = 0, ds = 0, ss = 0;
  int moved = 0;
  for (size_t i = 0; i < n; i++) {
    size_t j = at[a->particles.id[i] - 1];
    moved |= j != i;
    for (int d = 0; d < 3; d++) {
      dv = fmax(dv, fabs(a->particles.v[3 * i + d] - b->particles.v[3 * j + d]));
      vs = fmax(vs, fabs(a->particles.v[3 * i + d]));
    }
    for (int k = 0; k < 6; k++) {
      ds = fmax(ds, fabs(a->particles.stress[6 * i + k] - b->particles.stress[6 * j + k]));
      ss = fmax(ss, fabs(a->particles.stress[6 * i + k]));
    }
  }
  CHECK(moved);
  CHECK(dv <= 1e-12 * vs);
  CHECK(ds <= 1e-12 * ss);
  free(at);
  mrn_sim_free(a);
  mrn_sim_free(b);
}

/* a gradient sink that advances the points of [lo, hi) (material 0) */
static long advance_sink(void *ctx, size_t lo, size_t hi, const double *L) {
  mrn_sim *sim = ctx;
  mrn_particles *ps = &sim->particles;
  mrn_point_result r[MRN_GRADIENT_CHUNK];
  long bad = mrn_material_advance_points(sim->materials[0], sim->dim, MRN_F_UPDATE_MIDPOINT, 1e-3, hi - lo, L,
                                         ps->F + (size_t)mrn_tensor_stride(sim->dim) * lo, ps->stress + 6 * lo, ps->strain + 6 * lo, NULL, 0, NULL, r);
  return bad >= 0 ? (long)lo + bad : -1;
}

static int same_state(const mrn_sim *a, const mrn_sim *b) {
  const mrn_particles *pa = &a->particles, *pb = &b->particles;
  const size_t n = pa->n;
  return !memcmp(pa->stress, pb->stress, 6 * n * sizeof(double)) && !memcmp(pa->F, pb->F, (size_t)mrn_tensor_stride(a->dim) * n * sizeof(double)) &&
         !memcmp(pa->strain, pb->strain, 6 * n * sizeof(double)) &&
         !memcmp(pa->e_elastic, pb->e_elastic, n * sizeof(double)) &&
         !memcmp(a->grid.force, b->grid.force, 3 * a->grid.n * sizeof(double));
}

/* USF's fused material update and force scatter against the two passes it
 * replaces, from the same random nodal velocities, with the particles in
 * random order (runs of one particle) or sorted by block (long runs):
 * - the kernel (mrn_update_force) with a sink of its own against
 *   mrn_gradient with that sink and a force-only P2G, in either order;
 * - the step's mrn_update_then_force against mrn_update_from_grid and a
 *   force-only P2G: it fuses for the sorted particles only (mean run >=
 *   MRN_FUSED_MIN_RUN), bitwise the same state either way. */
static void fused_update_force(int dim, mrn_shape_kind shape, int sorted, int threads) {
  mrn_sim *sim[4];
  for (int k = 0; k < 4; k++) {
    sim[k] = make(dim, shape, 20000, 5u);
    CHECK(sim[k] != NULL);
    if (sorted) mrn_sim_set_sort_every(sim[k], 1);
  }
  set_threads(threads);
  for (int k = 0; k < 4; k++) p2g(sim[k], 1, 0);
  const size_t nodes = sim[0]->grid.n;
  double *gvel = malloc(3 * nodes * sizeof(double));
  unsigned seed = 99u;
  for (size_t i = 0; i < 3 * nodes; i++) gvel[i] = (i % 3 < (size_t)dim) ? 0.02 * (rnd(&seed) - 0.5) : 0.0;
  /* the kernel */
  const mrn_gradient_sink s0 = {advance_sink, sim[0], MRN_PHASE_STRESS}, s1 = {advance_sink, sim[1], MRN_PHASE_STRESS};
  CHECK(gradient(sim[0], gvel, &s0) == -1);
  mrn_blocks_reuse(sim[0]->blocks);
  p2g(sim[0], 0, 1);
  CHECK(update_force(sim[1], gvel, &s1) == -1);
  CHECK(same_state(sim[0], sim[1]));
  CHECK(ranges_hold(&sim[1]->grid));
  /* the step's choice */
  const mrn_blocks *b = sim[3]->blocks;
  CHECK(update_force_fused(sim[3]) == (b->np >= MRN_FUSED_MIN_RUN * b->runs));
  CHECK(update_force_fused(sim[3]) == sorted);
  CHECK(update_from_grid(sim[2], gvel, 1e-3) == 0);
  mrn_blocks_reuse(sim[2]->blocks);
  p2g(sim[2], 0, 1);
  CHECK(update_then_force(sim[3], gvel, 1e-3) == 0);
  CHECK(same_state(sim[2], sim[3]));
  free(gvel);
  for (int k = 0; k < 4; k++) mrn_sim_free(sim[k]);
}

int main(void) {
  for (int dim = 2; dim <= 3; dim++) {
    threads_and_spans(dim, MRN_SHAPE_QUADRATIC_BSPLINE);
    threads_and_spans(dim, MRN_SHAPE_CUBIC_BSPLINE);
    threads_and_spans(dim, MRN_SHAPE_LINEAR);
    threads_and_spans(dim, MRN_SHAPE_GIMP);
    sorted_run(dim);
    reused_binning(dim);
    incremental_rebin(dim, 1);
    incremental_rebin(dim, 2);
    for (int sorted = 0; sorted <= 1; sorted++)
      for (int threads = 1; threads <= 2; threads++) {
        fused_update_force(dim, MRN_SHAPE_QUADRATIC_BSPLINE, sorted, threads);
        fused_update_force(dim, MRN_SHAPE_CUBIC_BSPLINE, sorted, threads);
        fused_update_force(dim, MRN_SHAPE_LINEAR, sorted, threads);
        fused_update_force(dim, MRN_SHAPE_GIMP, sorted, threads);
      }
  }
  permute_keeps_fields();
  CHECK_DONE();
}
