#include "solver/source.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "solver/dist.h"
#include "solver/simulation.h"

/* a coordinate within this fraction of a cell of a bound counts as on it */
#define SOURCE_TOL 1e-9

static const char *const axis_names = "xyz";

/* the flow's direction along the axis: +1 from the box's lower face, -1 from its upper */
static double flow_sign(const mrn_source_config *c) { return c->side == 0 ? 1.0 : -1.0; }

/* the plane's coordinate along the axis */
static double plane_at(const mrn_source_config *c) { return c->side == 0 ? c->lo[c->axis] : c->hi[c->axis]; }

/* v must point into the box along the axis (or be zero: the inflow stops)
 * and have no other component */
static int check_velocity(const mrn_sim *sim, const char *name, const mrn_source_config *c, const double v[3],
                          double t) {
  for (int d = 0; d < sim->dim; d++) {
    if (!isfinite(v[d]))
      return mrn_error("source '%s': velocity: the inflow velocity at t = %g s is not finite", name, t);
    if (d != c->axis && v[d] != 0.0)
      return mrn_error("source '%s': velocity: the inflow velocity has a component %g m/s along %c at t = %g s: it "
                       "must be normal to the inflow face (along %c only)", name, v[d], axis_names[d], t,
                       axis_names[c->axis]);
  }
  if (flow_sign(c) * v[c->axis] < 0.0)
    return mrn_error("source '%s': velocity: the inflow velocity %g m/s along %c at t = %g s points out of the "
                     "inlet (a negative flow)", name, v[c->axis], axis_names[c->axis], t);
  return MRN_OK;
}

/* the box inside the grid, clear of the other sources' boxes */
static int check_box(const mrn_sim *sim, const char *name, const mrn_source_config *c) {
  const mrn_grid *g = &sim->grid;
  const double tol = SOURCE_TOL * g->cell;
  for (int d = 0; d < sim->dim; d++) {
    if (!(c->hi[d] > c->lo[d])) return mrn_error("source '%s': region: the inlet box has no extent along %c", name, axis_names[d]);
    if (c->lo[d] < g->origin[d] - tol || c->hi[d] > g->origin[d] + g->size[d] + tol)
      return mrn_error("source '%s': region: the inlet box [%g, %g] along %c is outside the grid [%g, %g]", name, c->lo[d],
                       c->hi[d], axis_names[d], g->origin[d], g->origin[d] + g->size[d]);
  }
  for (int k = 0; k < sim->nsources; k++) {
    const mrn_source *o = &sim->sources[k];
    int apart = 0;
    for (int d = 0; d < sim->dim; d++) apart |= c->hi[d] <= o->cfg.lo[d] + tol || c->lo[d] >= o->cfg.hi[d] - tol;
    if (!apart) return mrn_error("source '%s': region: the inlet box overlaps that of source '%s' (sources may not overlap)", name, o->name);
  }
  return MRN_OK;
}

/* the lattice points on the plane: the sub-cell centres inside the box's
 * cross-section */
static int make_points(mrn_sim *sim, mrn_source *s) {
  const mrn_grid *g = &sim->grid;
  const mrn_source_config *c = &s->cfg;
  long lo[3] = {0, 0, 0}, count[3] = {1, 1, 1};
  size_t total = 1;
  for (int d = 0; d < sim->dim; d++) {
    if (d == c->axis) continue;
    /* points origin + (i + 1/2) Delta strictly inside (lo, hi) */
    lo[d] = (long)ceil((c->lo[d] - g->origin[d]) / s->spacing - 0.5 + SOURCE_TOL);
    long hi = (long)floor((c->hi[d] - g->origin[d]) / s->spacing - 0.5 - SOURCE_TOL);
    count[d] = hi >= lo[d] ? hi - lo[d] + 1 : 0;
    total *= (size_t)count[d];
  }
  if (total == 0)
    return mrn_error("source '%s': region: the inflow face holds no lattice point (narrower than the spacing %g m)", s->name,
                     s->spacing);
  s->points = malloc(3 * total * sizeof *s->points);
  if (!s->points) return mrn_error("source '%s': out of memory", s->name);
  for (size_t k = 0; k < total; k++) {
    size_t rest = k;
    double *x = s->points + 3 * k;
    for (int d = 0; d < 3; d++) {
      x[d] = 0.0;
      if (d >= sim->dim) continue;
      if (d == c->axis) {
        x[d] = plane_at(c);
        continue;
      }
      x[d] = g->origin[d] + ((double)(lo[d] + (long)(rest % (size_t)count[d])) + 0.5) * s->spacing;
      rest /= (size_t)count[d];
    }
  }
  s->npoints = total;
  s->area = (double)total * pow(s->spacing, sim->dim - 1);
  return MRN_OK;
}

/* The inlet nodes: those of the box, and two cells around it on the plane
 * and upstream of it (which only the new particles reach: the reservoir
 * moves with the inflow there), and beyond every side of it that lies on a
 * face of the grid (the ghost nodes the extended kernels of the particles
 * next to the face reach). */
static int inlet_node(const mrn_sim *sim, const mrn_source_config *c, const double x[3]) {
  const mrn_grid *g = &sim->grid;
  const double tol = SOURCE_TOL * g->cell, beyond = MRN_GRID_PAD * g->cell;
  const int upstream = flow_sign(c) * (x[c->axis] - plane_at(c)) <= tol;
  for (int d = 0; d < sim->dim; d++) {
    double lo = c->lo[d], hi = c->hi[d];
    if ((d == c->axis ? c->side == 0 : upstream) || fabs(lo - g->origin[d]) <= tol) lo -= beyond;
    if ((d == c->axis ? c->side == 1 : upstream) || fabs(hi - g->origin[d] - g->size[d]) <= tol) hi += beyond;
    if (x[d] < lo - tol || x[d] > hi + tol) return 0;
  }
  return 1;
}

static int make_inlet(mrn_sim *sim, mrn_source *s) {
  const mrn_grid *g = &sim->grid;
  mrn_constraint *in = &s->inlet;
  memset(in, 0, sizeof *in);
  size_t count = 0;
  for (int pass = 0; pass < 2; pass++) {
    for (size_t i = 0; i < g->n; i++) {
      double x[3];
      mrn_grid_node_position(g, i, x);
      if (!inlet_node(sim, &s->cfg, x)) continue;
      if (pass == 1) in->nodes[in->count++] = i;
      else count++;
    }
    if (pass == 0 && !(in->nodes = malloc((count ? count : 1) * sizeof *in->nodes)))
      return mrn_error("source '%s': out of memory", s->name);
  }
  in->mask = (1u << sim->dim) - 1u;
  return MRN_OK;
}

/* the state a loaded simulation kept under this name, taken up once */
static void take_state(mrn_sim *sim, mrn_source *s) {
  for (int k = 0; k < sim->nsource_states; k++) {
    mrn_source_state *kept = &sim->source_states[k];
    if (strcmp(kept->name, s->name) != 0) continue;
    s->st = *kept;
    sim->source_states[k] = sim->source_states[--sim->nsource_states];
    return;
  }
}

static int setup_source(mrn_sim *sim, mrn_source *s, const mrn_source_config *cfg) {
  s->cfg = *cfg;
  snprintf(s->name, sizeof s->name, "%s", cfg->name ? cfg->name : "source");
  s->cfg.name = NULL; /* the caller's string may go: the name is s->name */
  snprintf(s->st.name, sizeof s->st.name, "%s", s->name);
  if (cfg->material < 0 || cfg->material >= sim->nmaterials)
    return mrn_error("source '%s': material index %d is not registered", s->name, cfg->material);
  if (cfg->per_axis < 1 || cfg->per_axis > MRN_SEED_MAX_PER_AXIS)
    return mrn_error("source '%s': per_axis = %d is not in [1, %d]", s->name, cfg->per_axis, MRN_SEED_MAX_PER_AXIS);
  if (cfg->axis < 0 || cfg->axis >= sim->dim || (cfg->side != 0 && cfg->side != 1))
    return mrn_error("source '%s': no such inflow face", s->name);
  for (int k = 0; k < sim->nsources; k++)
    if (!strcmp(sim->sources[k].name, s->name)) return mrn_error("source '%s': the name is taken", s->name);
  if (check_box(sim, s->name, cfg) != MRN_OK) return MRN_ERR;
  if (!cfg->fn) {
    if (check_velocity(sim, s->name, cfg, cfg->velocity, sim->time) != MRN_OK) return MRN_ERR;
    if (!(flow_sign(cfg) * cfg->velocity[cfg->axis] > 0.0))
      return mrn_error("source '%s': velocity: the inflow velocity is zero (no flow)", s->name);
  }
  s->spacing = sim->grid.cell / cfg->per_axis;
  s->volume = pow(s->spacing, sim->dim);
  if (make_points(sim, s) != MRN_OK || make_inlet(sim, s) != MRN_OK) return MRN_ERR;
  take_state(sim, s);
  return MRN_OK;
}

static void free_source(mrn_source *s) {
  free(s->points);
  mrn_constraint_free(&s->inlet);
  if (s->cfg.release) s->cfg.release(s->cfg.ctx);
}

int mrn_sim_add_source(mrn_sim *sim, const mrn_source_config *cfg) {
  if (sim->nsources == MRN_MAX_SOURCES) {
    mrn_error("source: at most %d sources per simulation", MRN_MAX_SOURCES);
    return -1;
  }
  mrn_source s;
  memset(&s, 0, sizeof s);
  if (setup_source(sim, &s, cfg) != MRN_OK) {
    s.cfg.release = NULL; /* the caller keeps ctx when the source is refused */
    free_source(&s);
    return -1;
  }
  mrn_source *grown = realloc(sim->sources, (size_t)(sim->nsources + 1) * sizeof *grown);
  if (!grown) {
    s.cfg.release = NULL;
    free_source(&s);
    mrn_error("source: out of memory");
    return -1;
  }
  sim->sources = grown;
  sim->sources[sim->nsources] = s;
  return sim->nsources++;
}

void mrn_sim_free_sources(mrn_sim *sim) {
  for (int k = 0; k < sim->nsources; k++) free_source(&sim->sources[k]);
  free(sim->sources);
  sim->sources = NULL;
  sim->nsources = 0;
  free(sim->source_states);
  sim->source_states = NULL;
  sim->nsource_states = 0;
}

void mrn_sim_move_sources(mrn_sim *to, mrn_sim *from) {
  for (int k = 0; k < to->nsources; k++) free_source(&to->sources[k]);
  free(to->sources);
  to->sources = from->sources, to->nsources = from->nsources;
  from->sources = NULL, from->nsources = 0;
  for (int k = 0; k < to->nsources; k++) {
    memset(&to->sources[k].st, 0, sizeof to->sources[k].st);
    snprintf(to->sources[k].st.name, sizeof to->sources[k].st.name, "%s", to->sources[k].name);
    take_state(to, &to->sources[k]);
  }
}

int mrn_sim_keep_source_states(mrn_sim *sim, const mrn_source_state *states, int count) {
  if (count <= 0) return MRN_OK;
  mrn_source_state *kept = malloc((size_t)count * sizeof *kept);
  if (!kept) return mrn_error("source: out of memory");
  memcpy(kept, states, (size_t)count * sizeof *kept);
  free(sim->source_states);
  sim->source_states = kept;
  sim->nsource_states = count;
  return MRN_OK;
}

/* ---- the step's part ----------------------------------------------------- */

int mrn_sources_begin_step(mrn_sim *sim, double dt) {
  /* the velocity at the middle of the step: the progress it gives is the
   * integral of v(t) to second order */
  const double t = sim->time + 0.5 * dt;
  for (int k = 0; k < sim->nsources; k++) {
    mrn_source *s = &sim->sources[k];
    double v[3] = {0.0, 0.0, 0.0};
    if (s->cfg.fn) {
      int rc = s->cfg.fn(s->cfg.ctx, sim, t, v);
      if (rc != MRN_OK) return rc;
      if (check_velocity(sim, s->name, &s->cfg, v, t) != MRN_OK) return MRN_ERR;
    } else {
      memcpy(v, s->cfg.velocity, sizeof v);
    }
    memcpy(s->v, v, sizeof v);
    memcpy(s->inlet.velocity, v, sizeof v);
  }
  return MRN_OK;
}

void mrn_sources_apply(mrn_sim *sim, double *vel, double dt, double share) {
  for (int k = 0; k < sim->nsources; k++) {
    mrn_source *s = &sim->sources[k];
    mrn_constraint_apply(&s->inlet, &sim->grid, vel, sim->mass_floor, share > 0.0 ? dt : 0.0);
    if (!(share > 0.0)) continue;
    /* the reaction sum m (v - V) / dt times v dt: the friction faces' sum m dV . V_after */
    double work = 0.0;
    for (int d = 0; d < 3; d++) work += s->inlet.reaction[d] * s->v[d] * dt;
    s->work_step += share * work;
    sim->work_inflow += share * work;
  }
}

/* layers [st.layers, due) of source s, each at its place in front of the plane */
static int emit_layers(mrn_sim *sim, mrn_source *s, long due) {
  const mrn_source_config *c = &s->cfg;
  const double rho = mrn_material_density(sim->materials[c->material]), mass = rho * s->volume;
  mrn_particles *ps = &sim->particles;
  if (mrn_particles_reserve(ps, ps->n + (size_t)(due - s->st.layers) * s->npoints) != MRN_OK) return MRN_ERR;
  for (long k = s->st.layers; k < due; k++) {
    const double ahead = s->st.progress - ((double)k + 0.5) * s->spacing;
    for (size_t q = 0; q < s->npoints; q++) {
      double x[3];
      memcpy(x, s->points + 3 * q, sizeof x);
      x[c->axis] += flow_sign(c) * ahead;
      const long p = mrn_particles_add(ps, x, mass, s->volume, c->material);
      if (p < 0) return MRN_ERR;
      memcpy(ps->v + 3 * p, s->v, 3 * sizeof(double));
      memcpy(ps->stress + 6 * p, c->stress, 6 * sizeof(double));
      s->st.energy += mrn_sim_particle_kinetic(sim, (size_t)p) + mrn_sim_particle_gravity(sim, (size_t)p) +
                      ps->e_elastic[p];
      s->st.mass += mass;
    }
    s->st.particles += (long)s->npoints;
  }
  s->st.layers = due;
  return MRN_OK;
}

/* the inlets' work of the step, summed over the processes: each booked
 * its rows' (grid/constraint.h) */
static void book_inlet_work(mrn_sim *sim) {
  double work[MRN_MAX_SOURCES];
  for (int k = 0; k < sim->nsources; k++) work[k] = sim->sources[k].work_step;
  mrn_dist_reduce(sim, work, sim->nsources, MRN_COMM_SUM);
  for (int k = 0; k < sim->nsources; k++) {
    sim->sources[k].st.work += work[k];
    sim->sources[k].work_step = 0.0;
  }
}

int mrn_sources_emit(mrn_sim *sim, double dt) {
  book_inlet_work(sim);
  /* every process makes every new particle alike, then keeps its own */
  const size_t first = sim->particles.n;
  int rc = MRN_OK;
  for (int k = 0; k < sim->nsources && rc == MRN_OK; k++) {
    mrn_source *s = &sim->sources[k];
    s->st.progress += flow_sign(&s->cfg) * s->v[s->cfg.axis] * dt;
    const long due = (long)floor(s->st.progress / s->spacing + 0.5);
    if (due > s->st.layers) rc = emit_layers(sim, s, due);
  }
  const int made = sim->particles.n > first;
  if (rc == MRN_OK && made && sim->dist) rc = mrn_dist_adopt(sim, first);
  if (rc == MRN_OK) mrn_sim_book_inflow(sim, first, sim->particles.n - first);
  if ((rc = mrn_dist_agree(sim, rc)) == MRN_OK && made) mrn_sim_particles_changed(sim);
  return rc;
}
