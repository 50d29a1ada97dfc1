/* moraine: the explicit MPM step (000 §3; 002 Fig. 1).
 *
 *   USF:  P2G mass & momentum -> V^i, BCs -> stress from V^i -> P2G force
 *         -> V~^i, BCs -> G2P
 *   USL:  P2G mass, momentum & force -> V^i, V~^i, BCs -> G2P
 *         -> stress from V~^i
 *   MUSL: as USL, then the new particle momenta are mapped back to the grid
 *         (at the start-of-step positions), BCs, and the stress is updated
 *         from that velocity before the particles move.
 *   USAVG: half the strain increment as in USF, half as in MUSL.
 * 000 §3.4 describes MUSL as USL with V~ in Eq. (45); moraine follows the
 * original definitions, in which USL already uses V~ and MUSL re-maps. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/parallel.h"
#include "core/tensor.h"
#include "solver/contact.h"
#include "solver/dist.h"
#include "solver/point_force.h"
#include "solver/simulation.h"
#include "solver/split.h"
#include "solver/update.h"
#include "grid/active.h"
#include "grid/wall.h"
#include "transfer/cpdi.h"
#include "transfer/cpdi2.h"
#include "transfer/cpgimp.h"
#include "transfer/kernels.h"
#include "transfer/profile.h"
#include "transfer/xpic.h"

/* Mass scaling: the nodal masses and momenta P2G just formed become those
 * of the inertial mass, mass_scaling m. The velocities do not change; the
 * forces accelerate the heavier nodes less, and the boundary conditions,
 * constraints and damping see the inertial mass. */
static void scale_grid_mass(mrn_sim *sim, mrn_grid *g, const mrn_node_ranges *r) {
  const double f = sim->mass_scaling;
#pragma omp parallel for schedule(static) if (r->nodes > MRN_OMP_MIN_NODES)
  for (long k = 0; k < r->count; k++)
    for (long i = r->lo[k]; i < r->hi[k]; i++) {
      g->mass[i] *= f;
      for (int d = 0; d < 3; d++) g->mom[3 * i + d] *= f;
    }
}

/* The part of the holds in V (walls, inlets) that reaches the particles' momentum:
 * PIC-like updates take V~ whole, FLIP only V~ - V (which the holds in V do
 * not change), a blend X of FLIP; XPIC takes V* + V~ - V, V* being V
 * smoothed, so with the holds. With `holds = particles` FLIP's V is the
 * velocity before its holds (release_holds): the whole of them. */
double mrn_hold_share(const mrn_scheme *s) {
  if (s->holds == MRN_HOLDS_PARTICLES) return 1.0;
  switch (s->velocity_update) {
  case MRN_VUPDATE_FLIP: return 0.0;
  case MRN_VUPDATE_BLEND: return 1.0 - s->flip_fraction;
  default: return 1.0;
  }
}

/* V = momentum / mass on the nodes above the mass floor, zero below: the
 * grid velocity as the transfer gave it, before any hold */
static void velocity_from_momentum(mrn_grid *g, double floor_mass, const mrn_node_ranges *r) {
#pragma omp parallel for schedule(static) if (r->nodes > MRN_OMP_MIN_NODES)
  for (long k = 0; k < r->count; k++)
    for (long i = r->lo[k]; i < r->hi[k]; i++) {
      const double m = g->mass[i];
      for (int d = 0; d < 3; d++) g->vel[3 * i + d] = m > floor_mass ? g->mom[3 * i + d] / m : 0.0;
    }
}

/* `holds = particles`: V as the transfer gave it, before the holds, for
 * FLIP's increment V~ - V (G2P reads it from grid.vel), once V~ is built.
 * The momentum of P2G is still on the grid. A face then stops in the
 * particles the normal velocity it stopped in V, an inelastic stop that
 * bounds friction (mrn_hold_share), where otherwise a FLIP particle on the
 * face keeps it in its memory (transfer/scheme.h). XPIC's V* already holds
 * them; PIC and APIC take no V. */
static void release_holds(mrn_sim *sim) {
  const mrn_scheme *s = &sim->scheme;
  if (s->holds != MRN_HOLDS_PARTICLES) return;
  if (s->velocity_update != MRN_VUPDATE_FLIP && s->velocity_update != MRN_VUPDATE_BLEND) return;
  const mrn_node_ranges r = mrn_grid_active_ranges(&sim->grid);
  velocity_from_momentum(&sim->grid, sim->mass_floor, &r);
}

/* the conditions on a velocity field of g: the faces, the constraints, and
 * the inlets last (an inlet opens in a face) */
static void hold_velocity(mrn_sim *sim, mrn_grid *g, double *vel) {
  mrn_boundary_apply(&sim->boundary, g, sim->mass_floor, vel, 0);
  for (int c = 0; c < sim->nconstraints; c++) mrn_constraint_apply(&sim->constraints[c], g, vel, sim->mass_floor, 0.0);
  if (sim->nsources) mrn_sources_apply(sim, vel, 0.0, 0.0);
}

/* nodal velocity from momentum, for nodes above the mass floor, then the
 * holds; `inlet_share` of the inlets' hold is booked as their work (in the
 * step's first V, the part the velocity update passes on), measured from V
 * as the transfer gave it: a face condition on the inlet's nodes (the slip
 * face an inlet opens in) is overridden there, not work of the inlet */
static void grid_velocity_held(mrn_sim *sim, mrn_grid *g, double dt, double inlet_share) {
  const double t0 = mrn_phase_begin();
  const mrn_node_ranges r = mrn_grid_active_ranges(g); /* every nodal array is zero elsewhere */
  if (sim->mass_scaling != 1.0) scale_grid_mass(sim, g, &r);
  velocity_from_momentum(g, sim->mass_floor, &r);
  if (sim->nsources && inlet_share > 0.0) mrn_sources_apply(sim, g->vel, dt, inlet_share);
  hold_velocity(sim, g, g->vel);
  mrn_phase_end(MRN_PHASE_GRID, t0);
}

void mrn_sim_hold_velocity(void *ctx, double *vel, double weight) {
  mrn_sim *sim = ctx;
  sim->boundary.pass_weight = weight;
  hold_velocity(sim, &sim->grid, vel);
  sim->boundary.pass_weight = 0.0;
}

void mrn_grid_velocity_on(mrn_sim *sim, mrn_grid *g) { grid_velocity_held(sim, g, 0.0, 0.0); }

/* `first`: the step's first V (a re-map's holds are not booked again) */
static void grid_velocity(mrn_sim *sim, double dt, int first) {
  grid_velocity_held(sim, &sim->grid, dt, first ? mrn_hold_share(&sim->scheme) : 0.0);
}

/* Damping force on a node with total force f and velocity v:
 * Cundall's local non-viscous damping, component-wise against the motion,
 * f_damp,k = -D |f_k| sign(v_k) (000, Eqs. 61-62), plus mass-proportional
 * viscous damping -alpha m v. */
static inline double damping_force(double D, double alpha, double f, double v, double m) {
  double fd = 0.0;
  if (D > 0.0 && v != 0.0) fd -= D * fabs(f) * (v > 0.0 ? 1.0 : -1.0);
  if (alpha > 0.0) fd -= alpha * m * v;
  return fd;
}

/* V~ = V + dt (f / m + g) (000, Eq. 28) with the damping force added to f,
 * and boundary conditions with friction. The acceleration the particles see,
 * (V~ - V) / dt, is not stored: G2P gathers V~ - V from both velocities.
 * The damping work is f_damp . (V + V~) / 2 dt. */
void mrn_grid_update_on(mrn_sim *sim, mrn_grid *g, double dt) {
  const double t0 = mrn_phase_begin();
  const double floor_mass = sim->mass_floor;
  const double D = sim->damping_cundall, alpha = sim->damping_viscous;
  const int damped = D > 0.0 || alpha > 0.0;
  const int bodies = D > 0.0 && mrn_walls_have_bodies(sim->boundary.walls);
  /* gravity acts on the true mass, the nodal mass over mass_scaling */
  double gravity[3];
  for (int d = 0; d < 3; d++) gravity[d] = sim->gravity[d] / sim->mass_scaling;
  const mrn_node_ranges r = mrn_grid_active_ranges(g); /* every nodal array is zero elsewhere */
#pragma omp parallel for schedule(static) if (r.nodes > MRN_OMP_MIN_NODES)
  for (long k = 0; k < r.count; k++) {
    double work = 0.0;
    for (long i = r.lo[k]; i < r.hi[k]; i++) {
      double m = g->mass[i];
      for (int d = 0; d < 3; d++) {
        if (!(m > floor_mass)) {
          g->vel_new[3 * i + d] = 0.0;
          continue;
        }
        double v = g->vel[3 * i + d];
        double f = g->force[3 * i + d] + m * gravity[d];
        /* a body's nodes move with it: Cundall's force there would act on the
         * body as a dry friction of D times their force */
        const double Dn = bodies && mrn_walls_body_holds(sim->boundary.walls, (size_t)i) ? 0.0 : D;
        double fd = damped ? damping_force(Dn, alpha, f, v, m) : 0.0;
        double v_new = v + dt * (f + fd) / m;
        g->vel_new[3 * i + d] = v_new;
        work += fd * 0.5 * (v + v_new) * dt;
      }
    }
    r.sum[k] = work;
  }
  double work = 0.0;
  /* fixed order: the same for any thread count; a row another process
   * books too (solver/dist.h) is booked by one */
  for (long k = 0; k < r.count; k++)
    if (mrn_grid_owns(g, r.lo[k])) work += r.sum[k];
  sim->work_damping += work;
  /* the inlets' work is that on the velocity the forces gave, before any
   * face condition: booked here, and the inlets held again after the faces */
  if (sim->nsources) mrn_sources_apply(sim, g->vel_new, dt, 1.0);
  sim->work_friction += mrn_boundary_apply(&sim->boundary, g, floor_mass, g->vel_new, 1);
  for (int c = 0; c < sim->nconstraints; c++) mrn_constraint_apply(&sim->constraints[c], g, g->vel_new, floor_mass, dt);
  if (sim->nsources) mrn_sources_apply(sim, g->vel_new, dt, 0.0);
  sim->work_external += mrn_point_forces_work(sim, dt);
  mrn_phase_end(MRN_PHASE_GRID, t0);
}

/* V~, and V without its holds where FLIP's increment takes them */
static void grid_update(mrn_sim *sim, double dt) {
  mrn_grid_update_on(sim, &sim->grid, dt);
  release_holds(sim);
}

static double *scratch(mrn_sim *sim, size_t count) {
  if (count > sim->scratch_cap) {
    double *s = realloc(sim->scratch, count * sizeof(double));
    if (!s) return NULL;
    sim->scratch = s;
    sim->scratch_cap = count;
  }
  return sim->scratch;
}

/* The end of the step, particle by particle:
 * - a particle that left through a periodic face re-enters through the other;
 * - a wall (fixed, slip, friction or velocity face) holds the nodes on and
 *   beyond it, but a particle moved by the interpolated grid velocity can
 *   still step a hair past it (the nodes just inside move towards it): such a
 *   particle is put back on the face, with no velocity into the wall; free
 *   faces let material leave;
 * - the state check of mrn_sim_check_state, reporting the first bad particle
 *   (the lowest index, for any thread count); with on_leave = delete, a
 *   finite particle outside the grid is marked instead and deleted after the
 *   pass (delete_leaving).
 * Where the step ends with G2P moving the particles (USF, USL) and no
 * particle is to be deleted, this runs inside G2P on each chunk of particles
 * just moved (end_chunk, a mrn_particle_pass): a separate pass would read
 * every position, velocity and stress from memory again. Otherwise it is a
 * pass of its own (end_of_step). */
typedef struct end_ctx {
  mrn_particles *ps;
  const mrn_sim *sim;
  int dim;
  int periodic[3], wall[3][2];
  double lo[3], hi[3], len[3];
} end_ctx;

static end_ctx end_setup(mrn_sim *sim) {
  const mrn_grid *g = &sim->grid;
  end_ctx e = {.ps = &sim->particles, .sim = sim, .dim = sim->dim};
  for (int d = 0; d < e.dim; d++) {
    e.periodic[d] = mrn_boundary_periodic(&sim->boundary, d);
    for (int side = 0; side < 2; side++) {
      mrn_bc_kind kind = sim->boundary.face[2 * d + side].kind;
      e.wall[d][side] = kind != MRN_BC_FREE && kind != MRN_BC_PERIODIC;
    }
    e.lo[d] = g->origin[d];
    e.len[d] = g->size[d];
    e.hi[d] = g->origin[d] + g->size[d];
  }
  return e;
}

/* the periodic wrap and the wall clamp of particle p */
static inline void wrap_and_clamp(const end_ctx *e, long p) {
  mrn_particles *ps = e->ps;
  for (int d = 0; d < e->dim; d++) {
    double *x = ps->x + 3 * p + d, *v = ps->v + 3 * p + d;
    if (e->periodic[d] && (*x < e->lo[d] || *x >= e->hi[d])) {
      double shift = e->len[d] * floor((*x - e->lo[d]) / e->len[d]);
      *x -= shift;
      ps->x0[3 * p + d] -= shift; /* the displacement stays continuous */
      if (*x >= e->hi[d]) *x = e->lo[d]; /* round-off at the seam */
    }
    if (e->wall[d][0] && *x < e->lo[d]) {
      *x = e->lo[d];
      if (*v < 0) *v = 0.0;
    }
    if (e->wall[d][1] && *x > e->hi[d]) {
      *x = e->hi[d];
      if (*v > 0) *v = 0.0;
    }
  }
}

/* Whether every particle of [lo, hi) is strictly inside the grid along each
 * axis (lo <= x < hi) with a finite position, velocity and stress: then the
 * wrap and the clamp leave it alone and it passes the state check. A chunk's
 * records of each field are one contiguous run of doubles, read here four
 * particles at a time as 4-wide vectors without regard to where a particle's
 * record starts: 12 doubles of x hold the x, y, z of 4 particles, so the
 * bounds repeat in the lanes with period 3. Along an axis beyond `dim` the
 * bounds are -DBL_MAX and DBL_MAX (the 0 of plane strain's z is inside, a NaN
 * or an infinity is not); the comparisons fail on a NaN, so the bounds test
 * also tells a finite position. Velocity and stress are finite when the sum
 * of the values times 0 is 0 (a * 0 is NaN for an infinite or NaN a). The
 * particles after the last group of 4 are tested one by one. `dim` is a
 * constant at each call. Saying "not all inside" is always safe: end_chunk
 * then checks particle by particle. */
typedef double chunk_v4 __attribute__((vector_size(32), aligned(8), may_alias));

static inline __attribute__((always_inline)) int all_inside(const end_ctx *e, long lo, long hi, const int dim) {
  const mrn_particles *ps = e->ps;
  double a[3], b[3];
  for (int d = 0; d < 3; d++) {
    a[d] = d < dim ? e->lo[d] : -DBL_MAX;
    b[d] = d < dim ? e->hi[d] : DBL_MAX;
  }
  const chunk_v4 a0 = {a[0], a[1], a[2], a[0]}, a1 = {a[1], a[2], a[0], a[1]}, a2 = {a[2], a[0], a[1], a[2]};
  const chunk_v4 b0 = {b[0], b[1], b[2], b[0]}, b1 = {b[1], b[2], b[0], b[1]}, b2 = {b[2], b[0], b[1], b[2]};
  __typeof__(a0 < b0) in = a0 <= a0; /* all lanes true */
  chunk_v4 zero = {0, 0, 0, 0};
  const long groups = (hi - lo) / 4;
  const double *x = ps->x + 3 * lo, *v = ps->v + 3 * lo, *s = ps->stress + 6 * lo;
  for (long k = 0; k < groups; k++, x += 12, v += 12, s += 24) {
    const chunk_v4 x0 = *(const chunk_v4 *)x, x1 = *(const chunk_v4 *)(x + 4), x2 = *(const chunk_v4 *)(x + 8);
    in &= (x0 >= a0) & (x0 < b0) & (x1 >= a1) & (x1 < b1) & (x2 >= a2) & (x2 < b2);
    zero += (*(const chunk_v4 *)v * 0.0 + *(const chunk_v4 *)(v + 4) * 0.0) + *(const chunk_v4 *)(v + 8) * 0.0;
    zero += (*(const chunk_v4 *)s * 0.0 + *(const chunk_v4 *)(s + 4) * 0.0) +
            (*(const chunk_v4 *)(s + 8) * 0.0 + *(const chunk_v4 *)(s + 12) * 0.0);
    zero += *(const chunk_v4 *)(s + 16) * 0.0 + *(const chunk_v4 *)(s + 20) * 0.0;
  }
  int out = !(in[0] & in[1] & in[2] & in[3]) | !((zero[0] + zero[1]) + (zero[2] + zero[3]) == 0.0);
  const double *restrict xs = e->ps->x;
  for (long p = lo + 4 * groups; p < hi; p++) {
    int inside = mrn_sim_particle_finite(e->sim, (size_t)p);
    for (int d = 0; d < dim; d++) inside &= (xs[3 * p + d] >= a[d]) & (xs[3 * p + d] < b[d]);
    out |= !inside;
  }
  return !out;
}

/* the end of the step of particles [lo, hi) without deletion: the lowest bad
 * index, or -1 (a mrn_particle_pass) */
static long end_chunk(void *ctx, size_t lo, size_t hi) {
  const end_ctx *e = ctx;
  if (e->dim == 2 ? all_inside(e, (long)lo, (long)hi, 2) : all_inside(e, (long)lo, (long)hi, 3)) return -1;
  long first_bad = -1;
  for (long p = (long)lo; p < (long)hi; p++) {
    wrap_and_clamp(e, p);
    if (first_bad < 0 && !mrn_sim_particle_ok(e->sim, (size_t)p)) first_bad = p;
  }
  return first_bad;
}

/* the end of the step as a pass of its own */
static void delete_leaving(mrn_sim *sim, const unsigned char *keep);

static int end_of_step(mrn_sim *sim) {
  const mrn_grid *g = &sim->grid;
  mrn_particles *ps = &sim->particles;
  const end_ctx e = end_setup(sim);
  const long n = (long)ps->n;
  long first_bad = n, leaving = 0;
  unsigned char *keep = NULL;
  if (sim->on_leave == MRN_LEAVE_DELETE) {
    keep = (unsigned char *)scratch(sim, (size_t)n / sizeof(double) + 1);
    if (!keep) return mrn_error("step: out of memory");
  }
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS) reduction(min : first_bad) reduction(+ : leaving)
  for (long p = 0; p < n; p++) {
    wrap_and_clamp(&e, p);
    if (keep) {
      const int finite = mrn_sim_particle_finite(sim, (size_t)p);
      keep[p] = !finite || mrn_grid_contains(g, ps->x + 3 * p);
      leaving += !keep[p];
      if (p < first_bad && !finite) first_bad = p;
    } else if (p < first_bad && !mrn_sim_particle_ok(sim, (size_t)p)) {
      first_bad = p;
    }
  }
  if (first_bad < n) return mrn_sim_particle_error(sim, (size_t)first_bad);
  if (leaving) delete_leaving(sim, keep);
  return MRN_OK;
}

/* Delete the particles with keep[p] == 0, booking their mass and their
 * E_k + E_g + E_el - W_pl as outflow so that W_MPM (000, Eq. 68) does not
 * jump when they go (mrn_sim_diagnostics adds energy_outflow back). Summed in
 * index order: the same for any thread count. */
static void delete_leaving(mrn_sim *sim, const unsigned char *keep) {
  const mrn_particles *ps = &sim->particles;
  for (size_t p = 0; p < ps->n; p++) {
    if (keep[p]) continue;
    sim->energy_outflow +=
        mrn_sim_particle_kinetic(sim, p) + mrn_sim_particle_gravity(sim, p) + ps->e_elastic[p] - ps->w_plastic[p];
    sim->outflow_mass += ps->mass[p];
    sim->outflow_particles++;
  }
  mrn_particles_compact(&sim->particles, keep);
}

/* grid velocity from the particles, and XPIC's smoothed velocity when needed */
static int grid_velocity_stage(mrn_sim *sim, mrn_transfer *tr, double dt) {
  grid_velocity(sim, dt, 1);
  if (sim->scheme.velocity_update == MRN_VUPDATE_XPIC) {
    double *ps = scratch(sim, 3 * sim->particles.n);
    if (!ps && sim->particles.n) return mrn_error("step: out of memory");
    mrn_xpic_smooth(tr, ps);
  }
  return MRN_OK;
}

/* The stages of a step by stress update scheme, on the step's transfer
 * context. Each pass over the particles names the stages it chains
 * (mrn_particle_stages, solver/update.h), in the order they run on each
 * chunk of particles. `end` is the end-of-step check the last G2P runs on
 * each chunk it moved (end->bad: what it rejected first); a scheme that
 * moves the particles after G2P sets end->pass to NULL, and the step then
 * ends with a pass of its own. */
typedef struct step_end {
  const mrn_particle_pass *pass;
  long bad;
} step_end;

enum {
  UPDATE_FORCE = MRN_STAGE_GRADIENT | MRN_STAGE_MATERIAL | MRN_STAGE_FORCE,
  MOVE_END = MRN_STAGE_MOVE | MRN_STAGE_END,
  MOVE_UPDATE_END = MRN_STAGE_MOVE | MRN_STAGE_GRADIENT | MRN_STAGE_MATERIAL | MRN_STAGE_END
};

/* the last pass of a step: G2P -> [gradient from V~ -> material update over
 * material_dt ->] end-of-step check */
static int move_pass(mrn_sim *sim, mrn_transfer *tr, unsigned stages, double dt, double material_dt, step_end *end) {
  mrn_particle_stages move = {stages, .gvel = sim->grid.vel_new, .move_dt = dt, .material_dt = material_dt,
                              .end = end->pass};
  const int rc = mrn_particle_stages_run(sim, tr, &move);
  end->bad = move.end_bad;
  return rc;
}

/* In a distributed run each P2G is followed by the halo sum
 * (solver/dist.h), which first agrees on what happened since the last:
 * a stage that failed here passes its code on to it rather than return,
 * so that every process meets the same exchanges. */

/* the internal force's halo sum (`what` holds MRN_CLEAR_FORCE), the point
 * forces spread to the nodes first: the sum then holds them too */
static int force_sum_halo(mrn_sim *sim, unsigned what, int rc) {
  if (rc == MRN_OK) mrn_point_forces_to_grid(sim);
  return mrn_dist_sum_halo(sim, what, rc);
}

/* USF: the stress from V^i, before the internal force is found from it */
static int step_usf(mrn_sim *sim, mrn_transfer *tr, double dt, step_end *end) {
  mrn_p2g(tr, 1, 0);                                                    /* mass, momentum */
  int rc = mrn_dist_sum_halo(sim, MRN_CLEAR_MASS_MOM, MRN_OK);
  if (rc == MRN_OK) rc = grid_velocity_stage(sim, tr, dt);              /* V^i */
  mrn_particle_stages update = {UPDATE_FORCE, .gvel = sim->grid.vel, .material_dt = dt};
  if (rc == MRN_OK) rc = mrn_particle_stages_run(sim, tr, &update);     /* gradient -> material update -> force */
  if ((rc = force_sum_halo(sim, MRN_CLEAR_FORCE, rc))) return rc;
  grid_update(sim, dt);                                                 /* V~^i */
  return move_pass(sim, tr, MOVE_END, dt, 0.0, end);              /* move -> end-of-step check */
}

/* USL: the forces from the stress of the last step; the stress from V~^i */
static int step_usl(mrn_sim *sim, mrn_transfer *tr, double dt, step_end *end) {
  int rc;
  mrn_p2g(tr, 1, 1);                                   /* mass, momentum, internal force */
  if ((rc = force_sum_halo(sim, MRN_CLEAR_MASS_MOM | MRN_CLEAR_FORCE, MRN_OK))) return rc;
  if ((rc = grid_velocity_stage(sim, tr, dt))) return rc; /* V^i */
  grid_update(sim, dt);                                /* V~^i */
  return move_pass(sim, tr, MOVE_UPDATE_END, dt, dt, end); /* move -> gradient -> material update -> check */
}

/* The end of MUSL's and USAVG's step: G2P gives the particles their new
 * velocities with the positions held back, the new momenta are mapped back
 * to the grid at the start-of-step positions, and the stress is updated over
 * material_dt from that velocity before the particles move. The re-mapped
 * velocity is the one the next step starts from, so the strain sees the
 * same velocity as the momentum: USL's strain from V~ does not, and loses
 * energy every step (000 §3.4; App. A). */
static int move_remap_update(mrn_sim *sim, mrn_transfer *tr, double dt, double material_dt, step_end *end) {
  int rc;
  /* the XPIC smoothing used the scratch; the position increments take it now */
  double *dx = scratch(sim, 3 * sim->particles.n);
  if (!dx && sim->particles.n) return mrn_error("step: out of memory");
  mrn_particle_stages move = {MRN_STAGE_MOVE, .move_dt = dt, .dx = dx};
  rc = mrn_particle_stages_run(sim, tr, &move); /* new velocities; positions held back */
  if (rc == MRN_OK) {
    mrn_blocks_reuse(tr->blocks);
    mrn_p2g(tr, 1, 0); /* re-map the new momenta */
  }
  if ((rc = mrn_dist_sum_halo(sim, MRN_CLEAR_MASS_MOM, rc))) return rc;
  grid_velocity(sim, dt, 0);
  mrn_particle_stages update = {MRN_STAGE_GRADIENT | MRN_STAGE_MATERIAL, .gvel = sim->grid.vel, .material_dt = material_dt};
  if ((rc = mrn_particle_stages_run(sim, tr, &update))) return rc; /* gradient -> material update */
  mrn_particles *ps = &sim->particles;
  for (size_t i = 0; i < 3 * ps->n; i++) ps->x[i] += dx[i];
  end->pass = NULL; /* the particles moved after G2P: the end of the step is a pass of its own */
  return MRN_OK;
}

/* MUSL: as USL, but the stress from the new particle momenta mapped back to
 * the grid (at the start-of-step positions) before the particles move */
static int step_musl(mrn_sim *sim, mrn_transfer *tr, double dt, step_end *end) {
  int rc;
  mrn_p2g(tr, 1, 1);                                   /* mass, momentum, internal force */
  if ((rc = force_sum_halo(sim, MRN_CLEAR_MASS_MOM | MRN_CLEAR_FORCE, MRN_OK))) return rc;
  if ((rc = grid_velocity_stage(sim, tr, dt))) return rc; /* V^i */
  grid_update(sim, dt);                                /* V~^i */
  return move_remap_update(sim, tr, dt, dt, end);
}

/* USAVG (Nairn's, after which 000 §3.4 names it): half the strain increment
 * from V^i before the forces, which then come from the half-updated stress,
 * and half from the re-mapped new momenta as in MUSL. In the stress and the
 * velocity this is the leapfrog drift-kick-drift: second order in dt. */
static int step_usavg(mrn_sim *sim, mrn_transfer *tr, double dt, step_end *end) {
  mrn_p2g(tr, 1, 0);                                                    /* mass, momentum */
  int rc = mrn_dist_sum_halo(sim, MRN_CLEAR_MASS_MOM, MRN_OK);
  if (rc == MRN_OK) rc = grid_velocity_stage(sim, tr, dt);              /* V^i */
  mrn_particle_stages update = {UPDATE_FORCE, .gvel = sim->grid.vel, .material_dt = 0.5 * dt};
  if (rc == MRN_OK) rc = mrn_particle_stages_run(sim, tr, &update);     /* gradient -> material update -> force */
  if ((rc = force_sum_halo(sim, MRN_CLEAR_FORCE, rc))) return rc;
  grid_update(sim, dt);                                           /* V~^i */
  return move_remap_update(sim, tr, dt, 0.5 * dt, end);
}

/* cpGIMP: the particle whose box the freeze refused (transfer/cpgimp.h) */
static int cpgimp_refused(const mrn_sim *sim, size_t p) {
  const mrn_particles *ps = &sim->particles;
  const int dim = sim->dim;
  const double *x = ps->x + 3 * p;
  double l[3] = {0, 0, 0}, F[9];
  mrn_cpgimp_box(sim->domain + 9 * p, dim, sim->grid.inv_cell, l);
  mrn_tensor_expand(dim, ps->F + (size_t)mrn_tensor_stride(dim) * p, 1.0, F);
  for (int d = 0; d < dim; d++)
    if (!(l[d] > 0.0) || !isfinite(l[d]))
      return mrn_error("step %ld: particle %lld at (%s, %s, %s): shape = 'cpgimp' sizes its box along %c by "
                       "F_%c%c = %s: the box has collapsed or turned over (a shear or rotation an axis-aligned box "
                       "does not follow; shape = 'cpdi' follows them)", sim->step + 1, (long long)ps->id[p],
                       mrn_num(x[0]).s, mrn_num(x[1]).s, mrn_num(x[2]).s, "xyz"[d], "xyz"[d], "xyz"[d],
                       mrn_num(F[4 * d]).s);
  char widths[96];
  snprintf(widths, sizeof widths, dim == 3 ? "%s, %s, %s" : "%s, %s", mrn_num(l[0]).s, mrn_num(l[1]).s,
           mrn_num(l[2]).s);
  return mrn_error("step %ld: particle %lld at (%s, %s, %s): shape = 'cpgimp': its box has stretched to half-widths "
                   "(%s) cells, whose shape functions reach more than the %d nodes a stencil holds (split the "
                   "stretched particles: mpm.simulation{split = {stretch = ...}})", sim->step + 1, (long long)ps->id[p],
                   mrn_num(x[0]).s, mrn_num(x[1]).s, mrn_num(x[2]).s, widths, MRN_REF_STENCIL_MAX);
}

/* The shapes with a tracked domain (CPDI, CPDI2, cpGIMP): refuse what they
 * do not combine with, then freeze the domains (CPDI2: the corners) for
 * every transfer of the step
 * (P2G, force and G2P see the same S_ip, so mass and momentum are
 * conserved to round-off), and set *reach (cells) to how far the shape
 * functions reach for the walls, the friction faces and the halo bands:
 * the grid's hat functions, one cell beyond the domain's extent */
static int domain_begin(mrn_sim *sim, double *reach) {
  const char *name = mrn_shape_info_of(sim->shape)->name;
  if (sim->kernel_boundary != MRN_KERNEL_EXTENDED)
    return mrn_error("shape = '%s' takes shape_boundary = 'extended' only, not '%s'", name,
                     mrn_kernel_boundary_names()[sim->kernel_boundary]);
  if (sim->scheme.mls_gradient)
    return mrn_error("shape = '%s' does not take scheme gradient = 'mls' (its gradients are domain averages)", name);
  if (sim->contact && sim->contact->npairs)
    return mrn_error("shape = '%s' does not take contact between bodies (sim:add_contact)", name);
  if (sim->shape == MRN_SHAPE_CPDI2 && sim->split_stretch > 0.0)
    return mrn_error("shape = 'cpdi2' does not take split (splitting halves the parallelogram F U0, not the "
                     "tracked corners): use shape = 'cpdi' with split, or cpdi2 without");
  const size_t need = 9 * sim->particles.n;
  if (need > sim->domain_cap) {
    double *d = realloc(sim->domain, need * sizeof(double));
    if (!d) return mrn_error("step: out of memory for the particles' domains");
    sim->domain = d, sim->domain_cap = need;
  }
  double extent = 0.0;
  int rc = MRN_OK;
  if (sim->shape == MRN_SHAPE_CPDI2) {
    rc = mrn_cpdi2_begin(&sim->particles, sim->grid.inv_cell, sim->domain, &extent);
  } else if (sim->shape == MRN_SHAPE_CPDI) {
    extent = mrn_cpdi_domains(&sim->particles, sim->dim, sim->grid.inv_cell, sim->domain);
  } else {
    const long bad = mrn_cpgimp_domains(&sim->particles, sim->dim, sim->grid.inv_cell, sim->domain, &extent);
    if (bad >= 0) return cpgimp_refused(sim, (size_t)bad);
  }
  *reach = 1.0 + extent;
  return rc;
}

/* the walls' reactions and works, and the rigid bodies moved on */
static int walls_step_end(mrn_sim *sim, double dt) {
  mrn_walls *ws = sim->boundary.walls;
  double work;
  ws->cundall = sim->damping_cundall;
  const int rc = mrn_walls_step_end(ws, dt, mrn_hold_share(&sim->scheme), sim->gravity, &work);
  sim->work_walls += work;
  /* the same on every process: a book of one (solver/dist.h) */
  sim->work_damping += mrn_dist_once(sim, ws->damping_work);
  return rc;
}

int mrn_sim_step_dt(mrn_sim *sim, double dt) {
  if (!(dt > 0.0) || !isfinite(dt)) return mrn_error("step %ld: invalid time step %s", sim->step + 1, mrn_num(dt).s);
  sim->dt = dt;
  sim->boundary.hold_share = mrn_hold_share(&sim->scheme); /* the friction bound's (grid/boundary.h) */
  int rc = mrn_dist_start(sim);
  if (rc == MRN_OK && sim->nsources) rc = mrn_dist_agree(sim, mrn_sources_begin_step(sim, dt));
  if (rc) return rc;
  /* the end of the step inside G2P, chunk by chunk (see end_ctx) */
  end_ctx e = end_setup(sim);
  const mrn_particle_pass end_pass = {end_chunk, &e};
  step_end end = {sim->on_leave == MRN_LEAVE_DELETE ? NULL : &end_pass, -1};
  double reach = 0.5 * mrn_shape_support(sim->shape); /* cells from a particle its shape functions reach */
  if (mrn_shape_tracks_domain(sim->shape)) rc = domain_begin(sim, &reach);
  if ((rc = mrn_dist_halo(sim, reach, rc)) != MRN_OK) return rc; /* the halo bands that reach needs */
  if ((rc = mrn_boundary_touch(&sim->boundary, &sim->grid, reach, sim->particles.x, sim->particles.vol0,
                               sim->particles.n, sim->dist ? mrn_dist_or_marks : NULL, sim)) != MRN_OK)
    return rc;
  mrn_dist_touch(sim);
  mrn_dist_walls_attach(sim);
  if (sim->boundary.walls && (rc = mrn_walls_touch(sim->boundary.walls, &sim->grid, sim->time + 0.5 * dt, reach,
                                                   sim->particles.x, sim->particles.vol0, sim->particles.n)))
    return rc;
  mrn_transfer tr = mrn_sim_transfer(sim);
  if (mrn_shape_tracks_domain(sim->shape)) tr.domain = sim->domain;
  if (sim->contact && sim->contact->npairs) {
    rc = mrn_contact_step(sim, &tr, dt);
    end.pass = NULL; /* the contact step's G2P has no end-of-step stage */
  } else switch (sim->scheme.stress_update) {
  case MRN_STRESS_USF: rc = step_usf(sim, &tr, dt, &end); break;
  case MRN_STRESS_USL: rc = step_usl(sim, &tr, dt, &end); break;
  case MRN_STRESS_USAVG: rc = step_usavg(sim, &tr, dt, &end); break;
  case MRN_STRESS_MUSL: rc = step_musl(sim, &tr, dt, &end); break;
  }
  /* CPDI2's corners move with this step's V~ (transfer/cpdi2.h) */
  if (rc == MRN_OK && sim->shape == MRN_SHAPE_CPDI2) mrn_cpdi2_move_corners(&tr, sim->domain, dt);
  mrn_sim_transfer_end(sim, &tr);
  /* the walls' reactions are summed over the processes: they meet there first */
  if (sim->boundary.walls) rc = mrn_dist_agree(sim, rc);
  if (rc == MRN_OK && sim->boundary.walls) rc = walls_step_end(sim, dt);
  if (rc) return mrn_dist_migrate(sim, rc); /* agreed by every process */
  sim->time += dt;
  sim->step++;
  rc = !end.pass ? end_of_step(sim) : end.bad >= 0 ? mrn_sim_particle_error(sim, (size_t)end.bad) : MRN_OK;
  /* the sources' new particles join the state the step ended on, and so
   * do the children of the particles split (solver/split.h): both take
   * every process, which first agree on the step */
  if (sim->nsources || sim->split_stretch > 0.0) rc = mrn_dist_agree(sim, rc);
  if (rc == MRN_OK && sim->nsources) rc = mrn_sources_emit(sim, dt);
  if (rc == MRN_OK && sim->split_stretch > 0.0 && mrn_sim_split(sim) < 0) rc = MRN_ERR;
  /* and the particles that left this process's slab go to their new one */
  return mrn_dist_migrate(sim, rc);
}

int mrn_sim_step(mrn_sim *sim) {
  double dt;
  int rc = mrn_dt_compute(sim, &dt);
  if (rc) return rc;
  return mrn_sim_step_dt(sim, dt);
}
