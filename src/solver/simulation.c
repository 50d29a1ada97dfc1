#include "solver/simulation.h"
#include "solver/dist.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "grid/wall.h"
#include "solver/contact.h"
#include "core/log.h"
#include "core/memory.h"
#include "core/parallel.h"
#include "transfer/kernels.h"

/* a row's value in a new simulation (the `initial` column of sim_scalars.h) */
#define SET_INITIAL(ctype, name, kind, check, since, initial, ...) SET_INITIAL_##kind(sim->name, initial);
#define SET_INITIAL_F64(at, v) at = (v)
#define SET_INITIAL_F64X3(at, v) for (int k = 0; k < 3; k++) at[k] = (v)
#define SET_INITIAL_I32(at, v) at = (v)
#define SET_INITIAL_I64(at, v) at = (v)
#define SET_INITIAL_NAME(at, v) at = (v)

mrn_sim *mrn_sim_new(const mrn_sim_config *cfg) {
  mrn_sim *sim = calloc(1, sizeof *sim);
  if (!sim) {
    mrn_error("simulation: out of memory");
    return NULL;
  }
  if (!mrn_shape_takes_dim(cfg->shape, cfg->dim)) {
    mrn_error("shape = 'cpdi2' is 2D only (its domains are quadrilaterals); use shape = 'cpdi' in %dD", cfg->dim);
    free(sim);
    return NULL;
  }
  if (mrn_grid_init(&sim->grid, cfg->dim, cfg->origin, cfg->size, cfg->cell) != MRN_OK) {
    free(sim);
    return NULL;
  }
  MRN_SIM_SCALARS(SET_INITIAL)
  sim->dim = cfg->dim;
  mrn_particles_init(&sim->particles, cfg->dim);
  sim->shape = cfg->shape;
  sim->kernel_boundary = cfg->kernel_boundary;
  mrn_scheme_default(&sim->scheme);
  for (int d = 0; d < 3; d++) sim->gravity[d] = d < cfg->dim ? cfg->gravity[d] : 0.0;
  mrn_dt_policy_a_tau(&sim->dt_policy, 0.05);
  mrn_watchdog_default(&sim->watchdog);
  sim->sorted_step = -1;
  sim->rebalance_every = MRN_DIST_REBALANCE_EVERY;
  sim->rebalance_imbalance = MRN_DIST_IMBALANCE;
  sim->blocks = mrn_blocks_new(&sim->grid);
  if (!sim->blocks) {
    mrn_sim_free(sim);
    return NULL;
  }
  return sim;
}

mrn_kernel_options mrn_sim_kernel_options(const mrn_sim *sim) {
  mrn_kernel_options o = {sim->shape, sim->kernel_boundary, sim->scheme.mls_gradient, 0};
  for (int d = 0; d < sim->dim; d++)
    if (mrn_boundary_periodic(&sim->boundary, d)) o.periodic |= 1u << d;
  return o;
}

/* a reordering is due at this step and none was done yet */
static int sort_due(const mrn_sim *sim) {
  return sim->sort_every > 0 && sim->step % sim->sort_every == 0 && sim->sorted_step != sim->step;
}

mrn_transfer mrn_sim_transfer(mrn_sim *sim) {
  mrn_transfer tr = {.dim = sim->dim,
                     .grid = &sim->grid,
                     .particles = &sim->particles,
                     .scheme = &sim->scheme,
                     .boundary = &sim->boundary,
                     .kernel = mrn_sim_kernel_options(sim),
                     .mass_floor = sim->mass_floor,
                     .blocks = sim->blocks,
                     .sort_now = sort_due(sim),
                     .sum_nodal = sim->dist ? mrn_dist_sum_nodal : NULL,
                     .max_over = sim->dist ? mrn_dist_max_over : NULL,
                     .hold = mrn_sim_hold_velocity,
                     .sum_ctx = sim};
  return tr;
}

void mrn_sim_transfer_end(mrn_sim *sim, const mrn_transfer *tr) {
  if (sort_due(sim) && !tr->sort_now) sim->sorted_step = sim->step;
}

void mrn_sim_set_sort_every(mrn_sim *sim, long every) { sim->sort_every = every > 0 ? every : 0; }

int mrn_sim_init_affine(mrn_sim *sim) {
  mrn_transfer tr = mrn_sim_transfer(sim);
  const int it = mrn_transfer_init_affine(&tr);
  mrn_sim_transfer_end(sim, &tr);
  sim->affine_pending = 0;
  return it;
}

void mrn_sim_free(mrn_sim *sim) {
  if (!sim) return;
  if (sim->integrator.release) sim->integrator.release(sim->integrator.ctx);
  mrn_grid_free(&sim->grid);
  mrn_blocks_free(sim->blocks);
  mrn_particles_free(&sim->particles);
  for (int i = 0; i < sim->nmaterials; i++) mrn_material_unref(sim->materials[i]);
  mrn_dt_policy_release(&sim->dt_policy);
  mrn_walls_free(sim->boundary.walls);
  mrn_contact_free(sim->contact);
  mrn_dist_free(sim->dist);
  for (int i = 0; i < sim->nconstraints; i++) mrn_constraint_free(&sim->constraints[i]);
  mrn_sim_free_sources(sim);
  free(sim->constraints);
  free(sim->scratch);
  free(sim->domain);
  free(sim->fbar);
  free(sim);
}

int mrn_sim_add_material(mrn_sim *sim, mrn_material *m) {
  for (int i = 0; i < sim->nmaterials; i++)
    if (sim->materials[i] == m) return i;
  if (sim->nmaterials == MRN_MAX_MATERIALS) {
    mrn_error("simulation: more than %d materials", MRN_MAX_MATERIALS);
    return -1;
  }
  if (mrn_particles_set_state_stride(&sim->particles, m->type->nstate) != MRN_OK) return -1;
  mrn_material_ref(m);
  sim->materials[sim->nmaterials] = m;
  return sim->nmaterials++;
}

/* Sums over the particles are formed in DIAG_PIECES fixed pieces (bounds set
 * by the particle count alone), in parallel, and the pieces added in order:
 * the diagnostics are bitwise the same for any number of threads. */
enum { DIAG_PIECES = 64, DIAG_SUMS = 14 };

static void piece_bounds(long n, int k, long *lo, long *hi) {
  *lo = n * k / DIAG_PIECES;
  *hi = n * (k + 1) / DIAG_PIECES;
}

static void add_pieces(double part[DIAG_PIECES][DIAG_SUMS], int nsums, double *total) {
  for (int j = 0; j < nsums; j++) total[j] = 0.0;
  for (int k = 0; k < DIAG_PIECES; k++)
    for (int j = 0; j < nsums; j++) total[j] += part[k][j];
}

enum { S_EK, S_EG, S_EEL, S_WPL, S_MASS, S_MOM, S_ANG = S_MOM + 3, S_MX = S_ANG + 3 };

void mrn_sim_energies(const mrn_sim *sim, mrn_diagnostics *out) {
  const mrn_particles *ps = &sim->particles;
  const long n = (long)ps->n;
  double part[DIAG_PIECES][DIAG_SUMS], t[DIAG_SUMS];
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (int k = 0; k < DIAG_PIECES; k++) {
    long lo, hi;
    piece_bounds(n, k, &lo, &hi);
    double s[DIAG_SUMS] = {0};
    for (long p = lo; p < hi; p++) {
      const double m = ps->mass[p];
      const double *x = ps->x + 3 * p, *v = ps->v + 3 * p;
      s[S_EK] += mrn_sim_particle_kinetic(sim, (size_t)p);
      s[S_EG] += mrn_sim_particle_gravity(sim, (size_t)p);
      s[S_EEL] += ps->e_elastic[p];
      s[S_WPL] += ps->w_plastic[p];
      s[S_MASS] += m;
      for (int d = 0; d < 3; d++) s[S_MOM + d] += m * v[d];
      s[S_ANG] += m * (x[1] * v[2] - x[2] * v[1]);
      s[S_ANG + 1] += m * (x[2] * v[0] - x[0] * v[2]);
      s[S_ANG + 2] += m * (x[0] * v[1] - x[1] * v[0]);
      for (int d = 0; d < 3; d++) s[S_MX + d] += m * x[d];
    }
    for (int j = 0; j < DIAG_SUMS; j++) part[k][j] = s[j];
  }
  add_pieces(part, DIAG_SUMS, t);
  mrn_dist_reduce(sim, t, DIAG_SUMS, MRN_COMM_SUM); /* over the processes of a distributed run */
  mrn_books b; /* the books kept per process, summed (solver/dist.h) */
  mrn_dist_books(sim, &b);
  const double ek = t[S_EK], eg = t[S_EG], eel = t[S_EEL], wpl = t[S_WPL], mass = t[S_MASS];
  memset(out, 0, sizeof *out);
  out->kinetic = ek;
  out->gravity = eg;
  out->elastic = eel;
  out->plastic = wpl;
  out->friction = b.friction;
  out->damping = b.damping;
  out->external = b.external;
  out->walls = sim->work_walls;
  mrn_walls_body_energy(sim->boundary.walls, &out->bodies, &out->bodies_work);
  out->contact = sim->work_contact;
  out->total = ek + eg + eel;
  out->inflow = b.inflow;
  out->inflow_work = b.inflow_work;
  out->outflow = b.outflow;
  /* (000, Eq. 68) summed over the steps since the balance started, with what
   * came in and went out through sources and free faces */
  out->mpm_error = sim->energy_ref_set
                       ? out->total + out->bodies - sim->energy_ref - wpl - b.friction - b.damping - b.external -
                             sim->work_walls - out->bodies_work - sim->work_contact + b.outflow - b.inflow -
                             b.inflow_work
                       : 0.0;
  out->mass = mass;
  for (int d = 0; d < 3; d++) {
    out->momentum[d] = t[S_MOM + d];
    out->angular[d] = t[S_ANG + d];
  }
  if (mass > 0)
    for (int d = 0; d < 3; d++) {
      out->com[d] = t[S_MX + d] / mass;
      out->com_velocity[d] = out->momentum[d] / mass;
    }
  double count = (double)n;
  mrn_dist_reduce(sim, &count, 1, MRN_COMM_SUM);
  out->particles = (long)count;
}

void mrn_sim_diagnostics(const mrn_sim *sim, mrn_diagnostics *out) {
  const mrn_particles *ps = &sim->particles;
  const long n = (long)ps->n;
  mrn_sim_energies(sim, out);
  if (out->particles == 0) return; /* in every process of a distributed run */
  /* angular momentum about the unweighted centroid (000, Eqs. 54 and 56) */
  double part[DIAG_PIECES][DIAG_SUMS], c[DIAG_SUMS];
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (int k = 0; k < DIAG_PIECES; k++) {
    long lo, hi;
    piece_bounds(n, k, &lo, &hi);
    double s[3] = {0};
    for (long p = lo; p < hi; p++)
      for (int d = 0; d < 3; d++) s[d] += ps->x[3 * p + d];
    for (int d = 0; d < 3; d++) part[k][d] = s[d];
  }
  add_pieces(part, 3, c);
  mrn_dist_reduce(sim, c, 3, MRN_COMM_SUM);
  for (int d = 0; d < 3; d++) c[d] /= (double)out->particles;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (int k = 0; k < DIAG_PIECES; k++) {
    long lo, hi;
    piece_bounds(n, k, &lo, &hi);
    double s[3] = {0};
    for (long p = lo; p < hi; p++) {
      const double m = ps->mass[p], *v = ps->v + 3 * p;
      const double r0 = ps->x[3 * p] - c[0], r1 = ps->x[3 * p + 1] - c[1], r2 = ps->x[3 * p + 2] - c[2];
      s[0] += m * (r1 * v[2] - r2 * v[1]);
      s[1] += m * (r2 * v[0] - r0 * v[2]);
      s[2] += m * (r0 * v[1] - r1 * v[0]);
    }
    for (int d = 0; d < 3; d++) part[k][d] = s[d];
  }
  double l[DIAG_SUMS];
  add_pieces(part, 3, l);
  mrn_dist_reduce(sim, l, 3, MRN_COMM_SUM);
  out->L_centroid = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
}

const char *const *mrn_leave_policy_names(void) {
  static const char *const names[] = {"stop", "delete", NULL};
  return names;
}

int mrn_sim_particle_error(const mrn_sim *sim, size_t p) {
  const mrn_particles *ps = &sim->particles;
  const mrn_grid *g = &sim->grid;
  const double *x = ps->x + 3 * p, *v = ps->v + 3 * p;
  if (!mrn_sim_particle_finite(sim, p))
    return mrn_error_code(MRN_ERR_STATE,
                          "step %ld (t = %g s): particle %lld has a non-finite position, velocity or stress "
                          "(x = (%s, %s, %s), v = (%s, %s, %s)); the time step %g s is probably above the "
                          "stability limit",
                          sim->step, sim->time, (long long)ps->id[p], mrn_num(x[0]).s, mrn_num(x[1]).s,
                          mrn_num(x[2]).s, mrn_num(v[0]).s, mrn_num(v[1]).s, mrn_num(v[2]).s, sim->dt);
  return mrn_error_code(MRN_ERR_STATE,
                        "step %ld (t = %g s): particle %lld left the grid at (%g, %g, %g) with velocity "
                        "(%g, %g, %g); the domain is [%g, %g] x [%g, %g]%s",
                        sim->step, sim->time, (long long)ps->id[p], x[0], x[1], x[2], v[0], v[1], v[2],
                        g->origin[0], g->origin[0] + g->size[0], g->origin[1], g->origin[1] + g->size[1],
                        g->dim == 3 ? " x [z range]" : "");
}

int mrn_sim_check_state(const mrn_sim *sim) {
  const long n = (long)sim->particles.n;
  long first_bad = n;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS) reduction(min : first_bad)
  for (long p = 0; p < n; p++)
    if (p < first_bad && !mrn_sim_particle_ok(sim, (size_t)p)) first_bad = p;
  return first_bad < n ? mrn_sim_particle_error(sim, (size_t)first_bad) : MRN_OK;
}

double mrn_sim_slowness(const mrn_sim *sim) {
  double best = HUGE_VAL;
  for (int i = 0; i < sim->nmaterials; i++) {
    double s = sqrt(mrn_material_density(sim->materials[i]) / mrn_material_young(sim->materials[i]));
    if (s < best) best = s;
  }
  return best * sqrt(sim->mass_scaling);
}

void mrn_sim_book_inflow(mrn_sim *sim, size_t first, size_t count) {
  const mrn_particles *ps = &sim->particles;
  for (size_t p = first; p < first + count; p++) {
    sim->energy_inflow += mrn_sim_particle_kinetic(sim, p) + mrn_sim_particle_gravity(sim, p) + ps->e_elastic[p];
    sim->inflow_mass += ps->mass[p];
    sim->inflow_particles++;
  }
}

typedef struct seed_ctx {
  mrn_sim *sim;
  int material;
  double density;
} seed_ctx;

static int seed_one(void *user, const double x[3], double volume) {
  seed_ctx *c = user;
  return mrn_particles_add(&c->sim->particles, x, c->density * volume, volume, c->material) < 0 ? MRN_ERR : 0;
}

/* a step sets aside 3 doubles of scratch per particle (step.c), one for the
 * time-step estimate (timestep.c) and the block ordering, a uint32_t with an
 * eighth of margin (blocks.c) */
#define STEP_BYTES_PER_PARTICLE (4 * sizeof(double) + 2 * sizeof(uint32_t))

size_t mrn_sim_particle_bytes(const mrn_sim *sim) {
  return mrn_particles_record_bytes(&sim->particles) + STEP_BYTES_PER_PARTICLE;
}

int mrn_sim_seed_estimate(const mrn_sim *sim, const mrn_region *region, int per_axis, mrn_seed_placement placement,
                          mrn_seed_estimate *e) {
  const double per_particle = (double)mrn_sim_particle_bytes(sim), there = (double)sim->particles.n;
  double bound;
  if (mrn_seed_candidates(&sim->grid, region, per_axis, &bound) != MRN_OK) return MRN_ERR;
  *e = (mrn_seed_estimate){bound, 0, (there + bound) * per_particle};
  if (e->bytes <= MRN_SEED_REPORT_BYTES || bound > MRN_SEED_MAX_CANDIDATES) return MRN_OK;
  long count;
  if (mrn_seed(&sim->grid, region, per_axis, placement, NULL, NULL, &count) != MRN_OK) return MRN_ERR;
  *e = (mrn_seed_estimate){(double)count, 1, (there + (double)count) * per_particle};
  return MRN_OK;
}

/* the message and the print of a large seeding: refused when it cannot fit */
static int report_seed(const mrn_sim *sim, const mrn_seed_estimate *e) {
  char what[160], there[64] = "";
  if (sim->particles.n) snprintf(there, sizeof there, " and the %zu already there", sim->particles.n);
  if (e->exact) snprintf(what, sizeof what, "%.0f particles%s", e->count, there);
  else snprintf(what, sizeof what, "up to %.3g particles (the seeding points of the region's bounding box)%s", e->count,
                there);
  if (mrn_memory_check(what, e->bytes, " (fewer particles per cell, a coarser grid or a smaller region?)") != MRN_OK)
    return MRN_ERR;
  char machine[64] = "";
  if (mrn_memory_total() > 0) snprintf(machine, sizeof machine, " (this machine has %.1f GB)", mrn_memory_total() / 1e9);
  mrn_info("moraine: seeding %s: about %.1f GB of memory%s", what, e->bytes / 1e9, machine);
  return MRN_OK;
}

/* a large seeding is refused when it cannot fit, else said; once counted,
 * the room is reserved (the arrays grow by doubling otherwise, up to twice
 * what they hold) */
static int plan_seed(mrn_sim *sim, const mrn_region *region, int per_axis, mrn_seed_placement placement) {
  mrn_seed_estimate e;
  if (mrn_sim_seed_estimate(sim, region, per_axis, placement, &e) != MRN_OK) return MRN_ERR;
  if (e.bytes > MRN_SEED_REPORT_BYTES && report_seed(sim, &e) != MRN_OK) return MRN_ERR;
  return e.exact ? mrn_particles_reserve(&sim->particles, sim->particles.n + (size_t)e.count) : MRN_OK;
}

int mrn_sim_seed(mrn_sim *sim, const mrn_region *region, int material_index, int per_axis,
                 mrn_seed_placement placement, size_t *first, long *count) {
  if (material_index < 0 || material_index >= sim->nmaterials)
    return mrn_error("seed: material index %d is not registered", material_index);
  if (plan_seed(sim, region, per_axis, placement) != MRN_OK) return MRN_ERR;
  seed_ctx c = {sim, material_index, mrn_material_density(sim->materials[material_index])};
  size_t start = sim->particles.n;
  long seeded = 0;
  int rc = mrn_seed(&sim->grid, region, per_axis, placement, seed_one, &c, &seeded);
  if (rc != MRN_OK) {
    sim->particles.n = start; /* nothing half-added */
    return rc;
  }
  /* a simulation already spread keeps this process's share of the new ones */
  if (sim->dist && (rc = mrn_dist_adopt(sim, start)) != MRN_OK) return rc;
  *first = start;
  *count = (long)(sim->particles.n - start);
  mrn_sim_particles_changed(sim);
  return MRN_OK;
}

void mrn_sim_particles_changed(mrn_sim *sim) {
  double lightest = HUGE_VAL;
  for (size_t p = 0; p < sim->particles.n; p++)
    if (sim->particles.mass[p] < lightest) lightest = sim->particles.mass[p];
  /* a node touched only by the far tail of a kernel carries a mass many orders below a
   * particle's; its velocity f/m is meaningless, so such nodes count as empty */
  mrn_dist_reduce(sim, &lightest, 1, MRN_COMM_MIN); /* one floor for every process */
  sim->mass_floor = isfinite(lightest) ? 1e-12 * lightest : 0.0;
}

void mrn_sim_energy_balance_start(mrn_sim *sim) {
  mrn_diagnostics d;
  sim->energy_ref_set = 0;
  mrn_sim_diagnostics(sim, &d);
  sim->energy_ref = d.total + d.bodies - d.bodies_work - d.plastic - d.friction - d.damping + d.outflow - d.inflow -
                    d.inflow_work;
  sim->energy_ref_set = 1;
}

/* a region as the grid's point test (grid/constraint.h) */
static int region_test(void *region, const double x[3]) { return mrn_region_contains(region, x); }

int mrn_sim_add_constraint(mrn_sim *sim, const mrn_region *region, unsigned mask, const double velocity[3]) {
  mrn_constraint c;
  if (mrn_constraint_init(&c, &sim->grid, region_test, (void *)region, mask, velocity) != MRN_OK) return -1;
  mrn_constraint *grown = realloc(sim->constraints, (size_t)(sim->nconstraints + 1) * sizeof *grown);
  if (!grown) {
    mrn_constraint_free(&c);
    mrn_error("constraint: out of memory");
    return -1;
  }
  sim->constraints = grown;
  sim->constraints[sim->nconstraints] = c;
  return sim->nconstraints++;
}
