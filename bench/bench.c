/* moraine benchmark harness (see bench/README.md).
 *
 * Fixed problems, each run for a fixed number of steps after a warm-up, in a
 * child process of its own (so the peak resident memory belongs to that
 * problem alone); reports particle-steps per second for the whole step and
 * the share of each phase, the threads used and the memory per particle, as
 * a table on stdout and as a JSON file. With --anchors DIR it also compiles
 * the stand-alone reference kernels found in DIR (ref2d.c, ref3d.c) into a
 * temporary directory, runs them interleaved with moraine's runs (same
 * threads, same repetitions) and prints moraine's speed as a ratio to them.
 *
 *   moraine-bench [--anchors DIR] [--threads 1,2] [--reps 3] [--json FILE]
 *                 [--only a,w,b,c,l,u,q,m,k,d,det|NAME,...] [--det-steps 1000]
 *                 [--sort-every N] [--shuffle] [--steps-scale X] [--warmup N]
 *
 * Problems:
 *   a160k, a640k   2D plane-strain elastic column 1 m x 1 m on the floor of a
 *                  6 m x 1.04 m grid, quadratic B-spline, APIC, USL, gravity,
 *                  slip walls, dt = 0.05 h sqrt(rho/E), E = 12.84 MPa,
 *                  nu = 0.16, rho = 1748 kg/m^3; 1 cm cells with 4x4
 *                  particles per cell / 2.5 mm cells with 2x2 (the anchor's
 *                  `ref2d 600 4 20` and `ref2d 2400 2 10`)
 *   w160k, w640k   the same particles on a narrow 1.04 m x 1.04 m grid: the
 *                  ratio a/w is the cost of the 6x wider, mostly empty grid
 *   b160k, b640k   as a with Mohr-Coulomb (phi 30, c 1 kPa, psi 0), FLIP,
 *                  cubic B-spline, USF (linear elasticity, and a note, when
 *                  no model named mohr_coulomb is registered)
 *   c32, c50       3D elastic cube of 32^3 / 50^3 cells of 0.1 m, 8 particles
 *                  per cell, quadratic B-spline, APIC, USL (`ref3d 32 2 20`,
 *                  `ref3d 50 2 6`); c50mc: the 50^3 cube with Mohr-Coulomb
 *                  history, for the memory figure
 *   l160k, l32     a160k and c32 with linear shape functions, FLIP, USF
 *   u160k, u32     the same with uGIMP (particle half-width from its volume)
 *   q160k, q32     the same with the quadratic B-spline: the rate linear and
 *                  uGIMP are measured against, on the same particles and scheme
 *   k160k          a160k cut at mid-height into two bodies in frictional
 *                  contact (mu 0.3, the mass-gradient normal): a160k / k160k
 *                  is the cost of the per-body fields (solver/contact.h)
 *   d1m            one .vtp snapshot of 1e6 particles with every default field
 *   det            threads change nothing: a 40,000-particle column run for
 *                  --det-steps steps on 1 and on 2 threads (APIC/USL elastic
 *                  and FLIP/cubic/USF Mohr-Coulomb), particle state compared
 *                  bit for bit and diagnostics compared digit for digit
 * --sort-every N reorders the particles by block every N steps (off by
 * default, as in the engine); --shuffle puts the particles in a random order
 * after seeding, as after a long flow. */
#define _GNU_SOURCE
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "io/output.h"
#include "particles/region.h"
#include "particles/sort.h"
#include "solver/contact.h"
#include "solver/simulation.h"
#include "grid/active.h"
#include "transfer/blocks.h"
#include "transfer/profile.h"

/* ---- problems ------------------------------------------------------------ */

typedef enum { KIND_STEP, KIND_OUTPUT, KIND_DET } run_kind;

typedef struct problem {
  const char *name;
  const char *group; /* for --only */
  run_kind kind;
  int dim;
  double cell;
  int per_axis;
  double grid[3];    /* domain size */
  double body[3];    /* particle block size, from the origin (x, z offset in 3D) */
  double offset[3];
  const char *preset;
  mrn_stress_update_kind stress;
  mrn_shape_kind shape;
  int mohr_coulomb;
  int steps;
  const char *anchor; /* "ref2d 600 4 20" or NULL */
  const char *note;
  int contact; /* 1: the upper half is a second body in contact with the lower */
} problem;

#define H1 0.01
#define H2 0.0025
static const problem problems[] = {
    {"a160k", "a", KIND_STEP, 2, H1, 4, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 20, "ref2d 600 4 20", "2D elastic, APIC, quadratic, USL", 0},
    {"a640k", "a", KIND_STEP, 2, H2, 2, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 10, "ref2d 2400 2 10", "2D elastic, APIC, quadratic, USL", 0},
    {"w160k", "w", KIND_STEP, 2, H1, 4, {1.04, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 20, NULL, "a160k on a narrow 1.04 m grid", 0},
    {"w640k", "w", KIND_STEP, 2, H2, 2, {1.04, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 10, NULL, "a640k on a narrow 1.04 m grid", 0},
    {"b160k", "b", KIND_STEP, 2, H1, 4, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "FLIP", MRN_STRESS_USF,
     MRN_SHAPE_CUBIC_BSPLINE, 1, 20, "ref2d 600 4 20", "2D Mohr-Coulomb, FLIP, cubic, USF", 0},
    {"b640k", "b", KIND_STEP, 2, H2, 2, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "FLIP", MRN_STRESS_USF,
     MRN_SHAPE_CUBIC_BSPLINE, 1, 10, "ref2d 2400 2 10", "2D Mohr-Coulomb, FLIP, cubic, USF", 0},
    {"c32", "c", KIND_STEP, 3, 0.1, 2, {3.6, 3.6, 3.6}, {3.2, 3.2, 3.2}, {0.2, 0, 0.2}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 20, "ref3d 32 2 20", "3D elastic, APIC, quadratic, USL", 0},
    {"l160k", "l", KIND_STEP, 2, H1, 4, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "FLIP", MRN_STRESS_USF,
     MRN_SHAPE_LINEAR, 0, 20, NULL, "2D elastic, FLIP, linear, USF", 0},
    {"u160k", "u", KIND_STEP, 2, H1, 4, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "FLIP", MRN_STRESS_USF,
     MRN_SHAPE_GIMP, 0, 20, NULL, "2D elastic, FLIP, uGIMP, USF", 0},
    {"q160k", "q", KIND_STEP, 2, H1, 4, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "FLIP", MRN_STRESS_USF,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 20, NULL, "2D elastic, FLIP, quadratic, USF", 0},
    {"l32", "l", KIND_STEP, 3, 0.1, 2, {3.6, 3.6, 3.6}, {3.2, 3.2, 3.2}, {0.2, 0, 0.2}, "FLIP", MRN_STRESS_USF,
     MRN_SHAPE_LINEAR, 0, 20, NULL, "3D elastic, FLIP, linear, USF", 0},
    {"u32", "u", KIND_STEP, 3, 0.1, 2, {3.6, 3.6, 3.6}, {3.2, 3.2, 3.2}, {0.2, 0, 0.2}, "FLIP", MRN_STRESS_USF,
     MRN_SHAPE_GIMP, 0, 20, NULL, "3D elastic, FLIP, uGIMP, USF", 0},
    {"q32", "q", KIND_STEP, 3, 0.1, 2, {3.6, 3.6, 3.6}, {3.2, 3.2, 3.2}, {0.2, 0, 0.2}, "FLIP", MRN_STRESS_USF,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 20, NULL, "3D elastic, FLIP, quadratic, USF", 0},
    {"c50", "c", KIND_STEP, 3, 0.1, 2, {5.4, 5.4, 5.4}, {5.0, 5.0, 5.0}, {0.2, 0, 0.2}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 6, "ref3d 50 2 6", "3D elastic, APIC, quadratic, USL", 0},
    {"c50mc", "m", KIND_STEP, 3, 0.1, 2, {5.4, 5.4, 5.4}, {5.0, 5.0, 5.0}, {0.2, 0, 0.2}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 1, 3, NULL, "c50 with Mohr-Coulomb history (memory)", 0},
    {"k160k", "k", KIND_STEP, 2, H1, 4, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 20, NULL, "a160k as two bodies in contact", 1},
    {"d1m", "d", KIND_OUTPUT, 3, 0.1, 2, {5.4, 5.4, 5.4}, {5.0, 5.0, 5.0}, {0.2, 0, 0.2}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 1, NULL, "one .vtp of 1e6 particles, default fields", 0},
    {"det-apic", "det", KIND_DET, 2, 0.01, 2, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "APIC", MRN_STRESS_USL,
     MRN_SHAPE_QUADRATIC_BSPLINE, 0, 1000, NULL, "1 vs 2 threads, APIC/USL elastic", 0},
    {"det-flip", "det", KIND_DET, 2, 0.01, 2, {6, 1.04, 0}, {1, 1, 0}, {0, 0, 0}, "FLIP", MRN_STRESS_USF,
     MRN_SHAPE_CUBIC_BSPLINE, 1, 1000, NULL, "1 vs 2 threads, FLIP/cubic/USF Mohr-Coulomb", 0},
};
enum { NPROBLEMS = sizeof problems / sizeof problems[0] };

/* ---- options ------------------------------------------------------------- */

static struct {
  const char *anchors;
  int threads[8], nthreads;
  int reps;
  const char *json;
  char only[256];
  int det_steps;
  long sort_every;
  double step_scale;
  int warmup;
  int shuffle;
} opt = {NULL, {1, 2}, 2, 3, "bench-results.json", "", 1000, 0, 1.0, 2, 0};

static int selected(const problem *p) {
  char buf[256];
  snprintf(buf, sizeof buf, "%s", opt.only);
  for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ","))
    if (strcmp(tok, p->group) == 0 || strcmp(tok, p->name) == 0) return 1;
  return 0;
}

/* ---- one measured run (in a child process) -------------------------------- */

typedef struct result {
  int ok;
  char message[256];
  long particles;
  int threads;
  int steps;
  double seconds;                 /* measured steps, wall */
  double phase[MRN_PHASE_COUNT];  /* seconds per phase */
  double bytes_per_particle;      /* peak resident growth over the problem / particles */
  double engine_bytes_per_particle;
  double output_bytes;            /* KIND_OUTPUT: file size */
  char material[32];
  /* KIND_DET */
  uint64_t hash;
  double diag[16];
} result;

static long rss_bytes(void) {
  FILE *f = fopen("/proc/self/statm", "r");
  long pages = 0, res = 0;
  if (f) {
    if (fscanf(f, "%ld %ld", &pages, &res) != 2) res = 0;
    fclose(f);
  }
  return res * sysconf(_SC_PAGESIZE);
}

static long peak_rss_bytes(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss * 1024L;
}

static mrn_material *make_material(const problem *p, char *label, size_t len) {
  const mrn_material_type *type = NULL;
  if (p->mohr_coulomb) type = mrn_material_type_find("mohr_coulomb");
  snprintf(label, len, "%s", type ? "mohr_coulomb" : "linear_elastic");
  if (!type) type = &mrn_material_linear_elastic;
  mrn_material *m = mrn_material_new(type);
  if (!m) return NULL;
  int rc = mrn_material_set(m, "density", 1748) || mrn_material_set(m, "E", 12.84e6) || mrn_material_set(m, "nu", 0.16);
  if (!rc && type != &mrn_material_linear_elastic)
    rc = mrn_material_set(m, "phi", 30) || mrn_material_set(m, "cohesion", 1e3) || mrn_material_set(m, "psi", 0);
  if (rc || mrn_material_prepare(m)) {
    mrn_material_unref(m);
    return NULL;
  }
  return m;
}

/* the particles above half the block's height become the body "top", in
 * frictional contact with the rest */
static int split_bodies(mrn_sim *sim, const problem *p) {
  const int top = mrn_sim_body(sim, "top");
  if (top < 0) return -1;
  const mrn_particles *ps = &sim->particles;
  const double half = p->offset[1] + 0.5 * p->body[1];
  for (size_t i = 0; i < ps->n; i++)
    if (ps->x[3 * i + 1] > half) mrn_sim_set_body(sim, i, 1, top);
  return mrn_sim_add_contact(sim, "default", "top", MRN_CONTACT_FRICTION, 0.3, NULL);
}

static mrn_sim *make_sim(const problem *p, char *label, size_t len) {
  mrn_sim_config cfg = {.dim = p->dim, .cell = p->cell, .shape = p->shape, .kernel_boundary = MRN_KERNEL_EXTENDED};
  for (int d = 0; d < p->dim; d++) cfg.size[d] = p->grid[d];
  cfg.gravity[1] = -9.81;
  mrn_sim *sim = mrn_sim_new(&cfg);
  if (!sim) return NULL;
  if (mrn_scheme_from_preset(p->preset, &sim->scheme)) goto fail;
  sim->scheme.stress_update = p->stress;
  if (mrn_scheme_validate(&sim->scheme)) goto fail;
  mrn_scheme_describe(&sim->scheme);
  for (int f = 0; f < 2 * p->dim; f++) sim->boundary.face[f].kind = MRN_BC_SLIP;
  mrn_material *mat = make_material(p, label, len);
  if (!mat) goto fail;
  int mi = mrn_sim_add_material(sim, mat);
  mrn_material_unref(mat);
  if (mi < 0) goto fail;
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int d = 0; d < p->dim; d++) {
    lo[d] = p->offset[d];
    hi[d] = p->offset[d] + p->body[d];
  }
  mrn_region *r = mrn_region_box(lo, hi);
  long count = 0;
  /* reserve exactly, so the memory figure carries no growth slack */
  if (mrn_seed(&sim->grid, r, p->per_axis, MRN_SEED_REGULAR, NULL, NULL, &count) ||
      mrn_particles_reserve(&sim->particles, (size_t)count)) {
    mrn_region_unref(r);
    goto fail;
  }
  size_t first;
  int rc = mrn_sim_seed(sim, r, mi, p->per_axis, MRN_SEED_REGULAR, &first, &count);
  mrn_region_unref(r);
  if (rc || (p->contact && split_bodies(sim, p))) goto fail;
  if (opt.shuffle) {
    /* a random order, as after a long flow has mixed the particles */
    const size_t n = sim->particles.n;
    uint32_t *order = malloc(sizeof *order * (n ? n : 1));
    if (!order) goto fail;
    for (size_t i = 0; i < n; i++) order[i] = (uint32_t)i;
    uint64_t state = 88172645463325252ull;
    for (size_t i = n; i > 1; i--) {
      state ^= state << 13, state ^= state >> 7, state ^= state << 17;
      size_t j = (size_t)(state % i);
      uint32_t t = order[i - 1];
      order[i - 1] = order[j];
      order[j] = t;
    }
    rc = mrn_particles_permute(&sim->particles, order);
    free(order);
    if (rc) goto fail;
  }
  if (opt.sort_every > 0) mrn_sim_set_sort_every(sim, opt.sort_every);
  return sim;
fail:
  mrn_sim_free(sim);
  return NULL;
}

static uint64_t fnv(uint64_t h, const void *data, size_t n) {
  const unsigned char *c = data;
  for (size_t i = 0; i < n; i++) h = (h ^ c[i]) * 1099511628211ull;
  return h;
}

/* the particle state in id order, so any reordering by sorting compares equal */
static uint64_t state_hash(const mrn_sim *sim) {
  const mrn_particles *ps = &sim->particles;
  size_t n = ps->n;
  long *at = malloc(sizeof(long) * (n ? n : 1));
  for (size_t i = 0; i < n; i++) at[ps->id[i] - 1] = (long)i;
  uint64_t h = 1469598103934665603ull;
  const mrn_particle_field_info *F = mrn_particle_field_find("F"), *affine = mrn_particle_field_find("affine");
  for (size_t k = 0; k < n; k++) {
    size_t i = (size_t)at[k];
    h = fnv(h, ps->x + 3 * i, 3 * sizeof(double));
    h = fnv(h, ps->v + 3 * i, 3 * sizeof(double));
    h = fnv(h, ps->stress + 6 * i, 6 * sizeof(double));
    /* the full tensors as 3 x 3 whatever the storage (the hash does not depend on it) */
    double full[9];
    mrn_particle_field_export(ps, F, i, 1, full);
    h = fnv(h, full, 9 * sizeof(double));
    mrn_particle_field_export(ps, affine, i, 1, full);
    h = fnv(h, full, 9 * sizeof(double));
  }
  free(at);
  return h;
}

static void run_child(const problem *p, int threads, result *res) {
  memset(res, 0, sizeof *res);
  res->threads = threads;
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  res->threads = 1;
#endif
  long rss0 = rss_bytes();
  mrn_sim *sim = make_sim(p, res->material, sizeof res->material);
  if (!sim) {
    snprintf(res->message, sizeof res->message, "setup failed: %s", mrn_error_message());
    return;
  }
  res->particles = (long)sim->particles.n;
  double phase[MRN_PHASE_COUNT] = {0};
  if (p->kind == KIND_OUTPUT) {
    char dir[] = "/tmp/moraine-bench-vtp-XXXXXX";
    if (!mkdtemp(dir)) {
      snprintf(res->message, sizeof res->message, "mkdtemp: %s", strerror(errno));
      mrn_sim_free(sim);
      return;
    }
    mrn_output out;
    mrn_output_init(&out, dir);
    mrn_output_set_vtk(&out, "bench", 0, 0);
    double t0 = mrn_profile_now();
    int rc = mrn_output_write_vtk(&out, sim);
    res->seconds = mrn_profile_now() - t0;
    char path[512];
    snprintf(path, sizeof path, "%s/bench_000000.vtp", dir);
    struct stat st;
    if (stat(path, &st) == 0) res->output_bytes = (double)st.st_size;
    unlink(path);
    snprintf(path, sizeof path, "%s/bench.pvd", dir);
    unlink(path);
    mrn_output_free(&out);
    rmdir(dir);
    if (rc) {
      snprintf(res->message, sizeof res->message, "output failed: %s", mrn_error_message());
      mrn_sim_free(sim);
      return;
    }
    res->steps = 1;
  } else {
    int steps = p->kind == KIND_DET ? opt.det_steps : (int)lround(p->steps * opt.step_scale);
    if (steps < 1) steps = 1;
    int warm = p->kind == KIND_DET ? 0 : opt.warmup;
    for (int s = 0; s < warm; s++)
      if (mrn_sim_step(sim)) goto step_failed;
    mrn_profile_seconds = phase;
    double t0 = mrn_profile_now();
    for (int s = 0; s < steps; s++)
      if (mrn_sim_step(sim)) goto step_failed;
    res->seconds = mrn_profile_now() - t0;
    mrn_profile_seconds = NULL;
    res->steps = steps;
    if (p->kind == KIND_DET) {
      mrn_diagnostics d;
      mrn_sim_diagnostics(sim, &d);
      double v[16] = {d.kinetic, d.gravity, d.elastic, d.plastic, d.friction, d.total, d.mass, d.momentum[0],
                      d.momentum[1], d.angular[2], d.L_centroid, d.com[0], d.com[1], d.com_velocity[0],
                      d.com_velocity[1], (double)d.particles};
      memcpy(res->diag, v, sizeof v);
    }
    res->hash = state_hash(sim); /* after the clock stopped: a refactor can compare every problem */
  }
  memcpy(res->phase, phase, sizeof phase);
  long peak = peak_rss_bytes();
  res->bytes_per_particle = (double)(peak - rss0) / (double)res->particles;
  {
    const mrn_particles *ps = &sim->particles;
    double per = 0;
    for (int f = 0; f < mrn_particle_field_count(); f++)
      per += 8.0 * mrn_particle_field_stride(ps, mrn_particle_field_at(f));
    per += sizeof(int32_t) + sizeof(int64_t) + 8.0 * ps->state_stride;
    double total = per * (double)ps->cap + 8.0 * 19.0 * (double)sim->grid.n + (double)mrn_blocks_bytes(sim->blocks) +
                   (double)mrn_grid_active_bytes(&sim->grid);
    res->engine_bytes_per_particle = total / (double)res->particles;
  }
  mrn_sim_free(sim);
  res->ok = 1;
  return;
step_failed:
  mrn_profile_seconds = NULL;
  snprintf(res->message, sizeof res->message, "step failed: %s", mrn_error_message());
  mrn_sim_free(sim);
}

static int run_forked(const problem *p, int threads, result *res) {
  int fd[2];
  if (pipe(fd)) return -1;
  fflush(stdout);
  pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    close(fd[0]);
    result r;
    run_child(p, threads, &r);
    ssize_t w = write(fd[1], &r, sizeof r);
    _exit(w == (ssize_t)sizeof r ? 0 : 1);
  }
  close(fd[1]);
  size_t got = 0;
  while (got < sizeof *res) {
    ssize_t k = read(fd[0], (char *)res + got, sizeof *res - got);
    if (k <= 0) break;
    got += (size_t)k;
  }
  close(fd[0]);
  int status;
  waitpid(pid, &status, 0);
  if (got != sizeof *res) {
    memset(res, 0, sizeof *res);
    snprintf(res->message, sizeof res->message, "child died (status %d)", status);
  }
  return 0;
}

/* ---- anchors --------------------------------------------------------------- */

static char anchor_dir[256];

static int build_anchors(void) {
  snprintf(anchor_dir, sizeof anchor_dir, "/tmp/moraine-anchors-XXXXXX");
  if (!mkdtemp(anchor_dir)) return -1;
  const char *names[] = {"ref2d", "ref3d"};
  for (int i = 0; i < 2; i++) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "cc -O3 -march=native -fopenmp '%s/%s.c' -lm -o '%s/%s'", opt.anchors, names[i],
             anchor_dir, names[i]);
    if (system(cmd) != 0) {
      fprintf(stderr, "bench: cannot build the anchor %s/%s.c\n", opt.anchors, names[i]);
      return -1;
    }
  }
  return 0;
}

static void remove_anchors(void) {
  if (!anchor_dir[0]) return;
  char path[512];
  snprintf(path, sizeof path, "%s/ref2d", anchor_dir);
  unlink(path);
  snprintf(path, sizeof path, "%s/ref3d", anchor_dir);
  unlink(path);
  rmdir(anchor_dir);
}

/* particle-steps per second of one anchor run, or NAN */
static double run_anchor(const char *spec, int threads) {
  char cmd[1024];
  snprintf(cmd, sizeof cmd, "OMP_NUM_THREADS=%d %s/%s", threads, anchor_dir, spec);
  FILE *f = popen(cmd, "r");
  if (!f) return NAN;
  char line[1024];
  double rate = NAN;
  while (fgets(line, sizeof line, f)) {
    char *at = strstr(line, "particle-steps/s=");
    if (at) rate = atof(at + strlen("particle-steps/s="));
  }
  pclose(f);
  return rate;
}

/* ---- statistics and reporting ---------------------------------------------- */

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  if (n <= 0) return NAN;
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct row {
  const problem *p;
  int threads;
  int ok;
  char message[256];
  char material[32];
  long particles;
  int steps;
  double rate;                   /* particle-steps/s, median */
  double phase_rate[MRN_PHASE_COUNT + 1]; /* particle-steps/s of each phase (median), last: other */
  double phase_share[MRN_PHASE_COUNT + 1];
  double bytes_pp, engine_bytes_pp;
  double anchor_rate;            /* median, NAN without anchors */
  double output_bytes, output_seconds;
  uint64_t hash;
  double diag[16];
  double round_rate[32]; /* particle-steps/s of each round, in order */
  int rounds;
} row;

static const char *phase_names[MRN_PHASE_COUNT + 1] = {"p2g", "grid", "g2p", "stress", "sort", "other"};

/* the samples of one row, round by round */
typedef struct samples {
  double rates[32], anchors[32], shares[MRN_PHASE_COUNT + 1][32], prates[MRN_PHASE_COUNT + 1][32], secs[32];
  int nr, na;
} samples;

/* One round of a row: the anchor's run, when it has one, then moraine's.
 * A failed run marks the row failed. */
static void sample(row *out, int threads, samples *s) {
  const problem *p = out->p;
  if (opt.anchors && p->anchor) {
    double a = run_anchor(p->anchor, threads);
    if (isfinite(a)) s->anchors[s->na++] = a;
  }
  result res;
  if (run_forked(p, threads, &res) || !res.ok) {
    snprintf(out->message, sizeof out->message, "%s", res.message[0] ? res.message : "failed");
    out->ok = 0;
    return;
  }
  out->particles = res.particles;
  out->steps = res.steps;
  out->threads = res.threads;
  snprintf(out->material, sizeof out->material, "%s", res.material);
  out->bytes_pp = res.bytes_per_particle;
  out->engine_bytes_pp = res.engine_bytes_per_particle;
  out->output_bytes = res.output_bytes;
  out->hash = res.hash;
  memcpy(out->diag, res.diag, sizeof res.diag);
  const double work = (double)res.particles * res.steps;
  const int k0 = s->nr;
  s->rates[k0] = work / res.seconds;
  out->round_rate[k0] = s->rates[k0];
  out->rounds = k0 + 1;
  s->secs[k0] = res.seconds;
  double known = 0;
  for (int k = 0; k <= MRN_PHASE_COUNT; k++) {
    double sec = k < MRN_PHASE_COUNT ? res.phase[k] : res.seconds - known;
    if (k < MRN_PHASE_COUNT) known += sec;
    s->shares[k][k0] = sec / res.seconds;
    s->prates[k][k0] = sec > 0 ? work / sec : INFINITY;
  }
  s->nr++;
}

static void summarize(row *out, samples *s) {
  out->rate = median(s->rates, s->nr);
  out->output_seconds = median(s->secs, s->nr);
  for (int k = 0; k <= MRN_PHASE_COUNT; k++) {
    out->phase_share[k] = median(s->shares[k], s->nr);
    out->phase_rate[k] = median(s->prates[k], s->nr);
  }
  if (s->na) out->anchor_rate = median(s->anchors, s->na);
}

/* The rows of problem p for threads[0 .. nt), their repetitions
 * interleaved: round r runs every thread count in turn, so the rows of one
 * problem see the machine in the same minutes, and their ratio is also
 * taken round by round (round_rate; see the scaling lines). */
static void measure(const problem *p, const int *threads, int nt, row *rows) {
  samples s[8];
  const int reps = p->kind == KIND_DET ? 1 : opt.reps;
  for (int t = 0; t < nt; t++) {
    memset(&rows[t], 0, sizeof rows[t]);
    rows[t].p = p;
    rows[t].threads = threads[t];
    rows[t].anchor_rate = NAN;
    rows[t].ok = 1;
    s[t].nr = s[t].na = 0;
  }
  for (int r = 0; r < reps && r < 32; r++)
    for (int t = 0; t < nt; t++)
      if (rows[t].ok) sample(&rows[t], threads[t], &s[t]);
  for (int t = 0; t < nt; t++)
    if (rows[t].ok) summarize(&rows[t], &s[t]);
}

/* the median over the rounds of a's rate over b's (rows measured together) */
static double paired_ratio(const row *a, const row *b) {
  double q[32];
  int n = 0;
  for (int k = 0; k < a->rounds && k < b->rounds; k++) q[n++] = a->round_rate[k] / b->round_rate[k];
  return median(q, n);
}

static void json_number(FILE *f, double v) {
  if (isfinite(v)) fprintf(f, "%.6g", v);
  else fprintf(f, "null");
}

static void write_json(const row *rows, int nrows, const char *path, char derived[][160], int nderived) {
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "bench: cannot write %s: %s\n", path, strerror(errno));
    return;
  }
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) < 0) load[0] = NAN;
  fprintf(f,
          "{\n  \"machine_cpus\": %ld,\n  \"load_average_1min\": %.2f,\n  \"reps\": %d,\n  \"warmup_steps\": %d,\n"
          "  \"sort_every\": %ld,\n  \"shuffled\": %s,\n",
          sysconf(_SC_NPROCESSORS_ONLN), load[0], opt.reps, opt.warmup, opt.sort_every, opt.shuffle ? "true" : "false");
  fprintf(f, "  \"anchors\": %s%s%s,\n  \"runs\": [\n", opt.anchors ? "\"" : "", opt.anchors ? opt.anchors : "null",
          opt.anchors ? "\"" : "");
  for (int i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    fprintf(f, "    {\"problem\": \"%s\", \"description\": \"%s\", \"threads\": %d, \"ok\": %s", r->p->name, r->p->note,
            r->threads, r->ok ? "true" : "false");
    if (!r->ok) {
      fprintf(f, ", \"error\": \"%s\"}%s\n", r->message, i + 1 < nrows ? "," : "");
      continue;
    }
    fprintf(f, ", \"material\": \"%s\", \"particles\": %ld, \"steps\": %d", r->material, r->particles, r->steps);
    if (r->p->kind == KIND_OUTPUT) {
      fprintf(f, ", \"seconds\": ");
      json_number(f, r->output_seconds);
      fprintf(f, ", \"bytes\": ");
      json_number(f, r->output_bytes);
      fprintf(f, ", \"particles_per_s\": ");
      json_number(f, r->rate);
    } else if (r->p->kind == KIND_DET) {
      fprintf(f, ", \"state_hash\": \"%016llx\", \"diagnostics\": [", (unsigned long long)r->hash);
      for (int k = 0; k < 16; k++) {
        fprintf(f, "%s%.17g", k ? ", " : "", r->diag[k]);
      }
      fprintf(f, "]");
    } else {
      fprintf(f, ", \"state_hash\": \"%016llx\", \"particle_steps_per_s\": ", (unsigned long long)r->hash);
      json_number(f, r->rate);
      fprintf(f, ", \"phases\": {");
      for (int k = 0; k <= MRN_PHASE_COUNT; k++) {
        fprintf(f, "%s\"%s\": {\"share\": ", k ? ", " : "", phase_names[k]);
        json_number(f, r->phase_share[k]);
        fprintf(f, ", \"particle_steps_per_s\": ");
        json_number(f, r->phase_rate[k]);
        fprintf(f, "}");
      }
      fprintf(f, "}, \"anchor_particle_steps_per_s\": ");
      json_number(f, r->anchor_rate);
      fprintf(f, ", \"ratio_to_anchor\": ");
      json_number(f, r->anchor_rate > 0 ? r->rate / r->anchor_rate : NAN);
    }
    fprintf(f, ", \"peak_bytes_per_particle\": ");
    json_number(f, r->bytes_pp);
    fprintf(f, ", \"engine_bytes_per_particle\": ");
    json_number(f, r->engine_bytes_pp);
    fprintf(f, "}%s\n", i + 1 < nrows ? "," : "");
  }
  fprintf(f, "  ],\n  \"derived\": {");
  for (int i = 0; i < nderived; i++) fprintf(f, "%s\n    %s", i ? "," : "", derived[i]);
  fprintf(f, "\n  }\n}\n");
  fclose(f);
}

static void usage(void) {
  fprintf(stderr,
          "usage: moraine-bench [--anchors DIR] [--threads 1,2] [--reps N] [--json FILE]\n"
          "                     [--only a,w,b,c,l,u,q,m,k,d,det|NAME,...] [--det-steps N] [--sort-every N]\n"
          "                     [--steps-scale X] [--warmup N] [--shuffle]\n");
}

int main(int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--anchors") && v) opt.anchors = v, i++;
    else if (!strcmp(a, "--reps") && v) opt.reps = atoi(v), i++;
    else if (!strcmp(a, "--json") && v) opt.json = v, i++;
    else if (!strcmp(a, "--only") && v) snprintf(opt.only, sizeof opt.only, "%s", v), i++;
    else if (!strcmp(a, "--det-steps") && v) opt.det_steps = atoi(v), i++;
    else if (!strcmp(a, "--sort-every") && v) opt.sort_every = atol(v), i++;
    else if (!strcmp(a, "--steps-scale") && v) opt.step_scale = atof(v), i++;
    else if (!strcmp(a, "--warmup") && v) opt.warmup = atoi(v), i++;
    else if (!strcmp(a, "--shuffle")) opt.shuffle = 1;
    else if (!strcmp(a, "--threads") && v) {
      opt.nthreads = 0;
      char buf[128];
      snprintf(buf, sizeof buf, "%s", v);
      for (char *t = strtok(buf, ","); t && opt.nthreads < 8; t = strtok(NULL, ",")) opt.threads[opt.nthreads++] = atoi(t);
      i++;
    } else {
      usage();
      return a[2] == 'h' ? 0 : 2;
    }
  }
  if (opt.reps < 1) opt.reps = 1;
  if (opt.reps > 32) opt.reps = 32;
  if (opt.anchors && build_anchors()) return 1;
  if (!opt.only[0]) snprintf(opt.only, sizeof opt.only, "a,w,b,c,l,u,q,m,k,d,det");

  printf("moraine bench: %ld CPUs online, threads", sysconf(_SC_NPROCESSORS_ONLN));
  for (int t = 0; t < opt.nthreads; t++) printf(" %d", opt.threads[t]);
  printf(", median of %d runs, %d warm-up steps, sort every %ld steps%s%s\n\n", opt.reps, opt.warmup,
         opt.sort_every, opt.anchors ? ", anchors from " : "", opt.anchors ? opt.anchors : "");
  printf("%-7s %3s %9s %6s %9s | %6s %6s %6s %6s %6s %6s | %9s %6s | %6s %6s\n", "problem", "thr", "particles",
         "steps", "Mpst/s", "p2g%", "grid%", "g2p%", "strs%", "sort%", "other%", "anchor", "ratio", "B/p", "eng");

  row rows[64];
  int nrows = 0;
  for (int i = 0; i < NPROBLEMS; i++) {
    const problem *p = &problems[i];
    if (!selected(p)) continue;
    if (p->kind == KIND_DET) {
      row both[2];
      static const int one_two[2] = {1, 2};
      measure(p, one_two, 2, both);
      const row r1 = both[0], r2 = both[1];
      rows[nrows++] = r1;
      rows[nrows++] = r2;
      if (!r1.ok || !r2.ok) {
        printf("%-8s failed: %s\n", p->name, r1.ok ? r2.message : r1.message);
        continue;
      }
      double worst = 0;
      int worst_k = 0;
      for (int k = 0; k < 16; k++) {
        double a = r1.diag[k], b = r2.diag[k], s = fmax(fabs(a), fabs(b));
        double rel = s > 0 ? fabs(a - b) / s : 0;
        if (rel > worst) worst = rel, worst_k = k;
      }
      printf("%-8s %s, %s, %d steps: particle state %s (hash %016llx / %016llx), diagnostics max relative "
             "difference %.3g (column %d)\n",
             p->name, p->note, r1.material, r1.steps, r1.hash == r2.hash ? "bitwise identical" : "DIFFERS",
             (unsigned long long)r1.hash, (unsigned long long)r2.hash, worst, worst_k);
      fflush(stdout);
      continue;
    }
    measure(p, opt.threads, opt.nthreads, &rows[nrows]);
    for (int t = 0; t < opt.nthreads; t++) {
      row *r = &rows[nrows++];
      if (!r->ok) {
        printf("%-7s %3d failed: %s\n", p->name, opt.threads[t], r->message);
        continue;
      }
      if (p->kind == KIND_OUTPUT) {
        printf("%-7s %3d %9ld %6s %9s | write %.3f s, %.1f MB, %.1f MB/s, %.3g particles/s%24s | %6.0f %6.0f\n",
               p->name, r->threads, r->particles, "-", "-", r->output_seconds, r->output_bytes / 1e6,
               r->output_bytes / 1e6 / r->output_seconds, r->particles / r->output_seconds, "", r->bytes_pp,
               r->engine_bytes_pp);
        r->rate = r->particles / r->output_seconds;
        fflush(stdout);
        continue;
      }
      printf("%-7s %3d %9ld %6d %9.3f |", p->name, r->threads, r->particles, r->steps, r->rate / 1e6);
      for (int k = 0; k <= MRN_PHASE_COUNT; k++) printf(" %6.1f", 100 * r->phase_share[k]);
      if (isfinite(r->anchor_rate))
        printf(" | %9.3f %6.3f", r->anchor_rate / 1e6, r->rate / r->anchor_rate);
      else
        printf(" | %9s %6s", "-", "-");
      printf(" | %6.0f %6.0f%s\n", r->bytes_pp, r->engine_bytes_pp,
             p->mohr_coulomb && strcmp(r->material, "mohr_coulomb") ? "  (Mohr-Coulomb not registered: linear_elastic)"
                                                                   : "");
      fflush(stdout);
    }
  }

  /* derived figures */
  static char derived[64][160];
  int nd = 0;
  printf("\n");
  for (int i = 0; i < nrows && nd < 60; i++) {
    const row *r = &rows[i];
    if (!r->ok || r->p->kind != KIND_STEP) continue;
    if (r->threads == 1)
      for (int j = 0; j < nrows; j++) {
        const row *s = &rows[j];
        if (s->p == r->p && s->ok && s->threads > 1) {
          const double paired = paired_ratio(s, r);
          printf("%-7s %d threads / 1 thread: %.2fx (median of %d rounds' ratios; of the medians %.2fx)\n",
                 r->p->name, s->threads, paired, s->rounds < r->rounds ? s->rounds : r->rounds, s->rate / r->rate);
          snprintf(derived[nd++], 160, "\"%s_scaling_%d_over_1\": %.4g", r->p->name, s->threads, paired);
          snprintf(derived[nd++], 160, "\"%s_scaling_medians_%d_over_1\": %.4g", r->p->name, s->threads,
                   s->rate / r->rate);
        }
      }
    if (r->p->name[0] == 'a')
      for (int j = 0; j < nrows; j++) {
        const row *w = &rows[j];
        if (w->ok && w->p->name[0] == 'w' && !strcmp(w->p->name + 1, r->p->name + 1) && w->threads == r->threads) {
          printf("%-7s %d thread(s): the 6x wider grid costs %+.1f %% over the narrow grid\n", r->p->name,
                 r->threads, 100 * (w->rate / r->rate - 1));
          snprintf(derived[nd++], 160, "\"%s_wide_grid_overhead_%dt\": %.4g", r->p->name, r->threads,
                   w->rate / r->rate - 1);
        }
      }
    if (r->p->name[0] == 'a')
      for (int j = 0; j < nrows; j++) {
        const row *k = &rows[j];
        if (k->ok && k->p->contact && !strcmp(k->p->name + 1, r->p->name + 1) && k->threads == r->threads) {
          printf("%-7s %d thread(s): two bodies in contact cost %.2fx the single field's time\n", r->p->name,
                 r->threads, r->rate / k->rate);
          snprintf(derived[nd++], 160, "\"%s_contact_cost_%dt\": %.4g", r->p->name, r->threads, r->rate / k->rate);
        }
      }
    if (isfinite(r->anchor_rate))
      snprintf(derived[nd++], 160, "\"%s_ratio_to_anchor_%dt\": %.4g", r->p->name, r->threads,
               r->rate / r->anchor_rate);
  }
  write_json(rows, nrows, opt.json, derived, nd);
  printf("\nJSON written to %s\n", opt.json);
  remove_anchors();
  return 0;
}
