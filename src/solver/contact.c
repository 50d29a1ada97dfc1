/* moraine: contact between deformable bodies (see contact.h).
 *
 * The per-body fields are scattered and gathered with the reference
 * kernels (transfer/reference.h), particle by particle (the gathers on
 * threads), each particle on its own body's view of the grid; the grid stages of the explicit step
 * (face conditions, walls, constraints, damping, mass scaling) run on each
 * view as they run on the single field. */
#include "solver/contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/parallel.h"
#include "grid/active.h"
#include "solver/dist.h"
#include "solver/point_force.h"
#include "solver/simulation.h"
#include "solver/update.h"
#include "transfer/kernels.h"
#include "transfer/reference.h"

/* ---- bodies and pairs ---------------------------------------------------------- */

static mrn_contact *contact_get(mrn_sim *sim) {
  if (!sim->contact) {
    sim->contact = calloc(1, sizeof *sim->contact);
    if (!sim->contact) return NULL;
    strcpy(sim->contact->name[0], "default");
    sim->contact->nbodies = 1;
  }
  return sim->contact;
}

int mrn_sim_body_find(const mrn_sim *sim, const char *name) {
  const mrn_contact *c = sim->contact;
  if (!c) return strcmp(name, "default") == 0 ? 0 : -1;
  for (int b = 0; b < c->nbodies; b++)
    if (strcmp(c->name[b], name) == 0) return b;
  return -1;
}

int mrn_sim_body(mrn_sim *sim, const char *name) {
  if (!name || !*name || strlen(name) >= MRN_BODY_NAME)
    return mrn_error("body: a name of 1 to %d characters is needed", MRN_BODY_NAME - 1), -1;
  mrn_contact *c = contact_get(sim);
  if (!c) return mrn_error("body: out of memory"), -1;
  if (!mrn_particles_user_field(&sim->particles, MRN_BODY_FIELD) &&
      mrn_particles_add_user_field(&sim->particles, MRN_BODY_FIELD, 1, 0.0, ""))
    return -1;
  const int found = mrn_sim_body_find(sim, name);
  if (found >= 0) return found;
  if (c->nbodies == MRN_MAX_BODIES) return mrn_error("body '%s': at most %d bodies", name, MRN_MAX_BODIES), -1;
  strcpy(c->name[c->nbodies], name);
  return c->nbodies++;
}

void mrn_sim_set_body(mrn_sim *sim, size_t first, size_t count, int body) {
  mrn_particles *ps = &sim->particles;
  const mrn_user_field *uf = mrn_particles_user_field(ps, MRN_BODY_FIELD);
  if (!uf) return; /* every particle is in the default body */
  for (size_t p = first; p < first + count; p++) ps->user[p * (size_t)ps->user_stride + (size_t)uf->offset] = body;
}

int mrn_sim_add_contact(mrn_sim *sim, const char *a, const char *b, mrn_contact_kind kind, double mu,
                        const double *normal) {
  const int ia = mrn_sim_body_find(sim, a), ib = mrn_sim_body_find(sim, b);
  const int idx[2] = {ia, ib};
  const char *names[2] = {a, b};
  for (int k = 0; k < 2; k++)
    if (idx[k] < 0)
      return mrn_error("contact: there is no body '%s' (name it in add_particles{body = \"%s\"} first; "
                       "contact needs two bodies)", names[k], names[k]);
  if (ia == ib) return mrn_error("contact: a body does not contact itself ('%s' twice; contact needs two bodies)", a);
  if (!(mu >= 0.0) || !isfinite(mu)) return mrn_error("contact: mu must be a finite number >= 0");
  mrn_contact *c = sim->contact;
  int k = 0;
  while (k < c->npairs && !((c->pair[k].a == ia && c->pair[k].b == ib) || (c->pair[k].a == ib && c->pair[k].b == ia)))
    k++;
  c->pair[k] = (mrn_contact_pair){ia, ib, kind, mu, normal != NULL, {0, 0, 0}};
  if (normal) {
    const double len = sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    if (!(len > 0.0) || !isfinite(len)) return mrn_error("contact: the normal must be a nonzero vector");
    for (int d = 0; d < 3; d++) c->pair[k].normal[d] = normal[d] / len;
  }
  if (k == c->npairs) c->npairs++;
  return MRN_OK;
}

void mrn_contact_free(mrn_contact *c) {
  if (!c) return;
  free(c->mass);
  free(c->L);
  free(c);
}

/* the law between bodies a and b: a declared pair, or NULL (bonded) */
static const mrn_contact_pair *pair_law(const mrn_contact *c, int a, int b) {
  for (int k = 0; k < c->npairs; k++)
    if ((c->pair[k].a == a && c->pair[k].b == b) || (c->pair[k].a == b && c->pair[k].b == a)) return &c->pair[k];
  return NULL;
}

/* ---- the per-body fields ---------------------------------------------------------- */

/* One block of 16 doubles per node and body (mass, momentum, velocities,
 * force, mass gradient), and each body's view of the grid onto its block. */
static int fields_alloc(mrn_contact *c, const mrn_grid *g) {
  const size_t n = g->n, nb = (size_t)c->nbodies;
  if (c->nnode != n) {
    free(c->mass);
    c->mass = calloc(16 * n * nb, sizeof(double));
    if (!c->mass) return c->nnode = 0, mrn_error("contact: out of memory for the body fields");
    c->nnode = n;
    c->mom = c->mass + n * nb;
    c->vel = c->mom + 3 * n * nb;
    c->vel_new = c->vel + 3 * n * nb;
    c->force = c->vel_new + 3 * n * nb;
    c->grad = c->force + 3 * n * nb;
  }
  for (size_t b = 0; b < nb; b++) {
    mrn_grid *v = &c->view[b];
    *v = *g; /* geometry, active spans and face state shared */
    v->mass = c->mass + b * n;
    v->mom = c->mom + 3 * b * n;
    v->vel = c->vel + 3 * b * n;
    v->vel_new = c->vel_new + 3 * b * n;
    v->force = c->force + 3 * b * n;
    /* the faces' memory of the step's holds is the single field's: a
     * body's friction on a face is bounded by its V~ alone */
    v->held = NULL;
  }
  return MRN_OK;
}

static inline int body_of(const mrn_particles *ps, const mrn_user_field *uf, size_t p) {
  return (int)ps->user[p * (size_t)ps->user_stride + (size_t)uf->offset];
}

/* P2G of body b's particles into its view (mass, momentum and the mass
 * gradient g_i = sum_p m_p grad N_i(x_p) when `momentum`; force when
 * `force`), in particle order. */
static void body_p2g(const mrn_sim *sim, const mrn_transfer *tr, int b, int momentum, int force) {
  mrn_contact *c = sim->contact;
  const mrn_particles *ps = &sim->particles;
  const mrn_user_field *uf = mrn_particles_user_field(ps, MRN_BODY_FIELD);
  const int dim = sim->dim;
  double *grad = c->grad + 3 * c->nnode * (size_t)b;
  mrn_transfer t = *tr;
  t.grid = &c->view[b];
  mrn_ref_stencil s;
  for (size_t p = 0; p < ps->n; p++) {
    if (body_of(ps, uf, p) != b) continue;
    mrn_ref_stencil_build(&t, p, &s);
    mrn_ref_p2g_add(&t, p, &s, momentum, force);
    if (!momentum) continue;
    for (int k = 0; k < s.count; k++)
      for (int d = 0; d < dim; d++) grad[3 * s.node[k] + d] += ps->mass[p] * s.dN[dim * k + d];
  }
}

/* P2G of every body into its view. Each body has its own arrays, so the
 * bodies are scattered on threads side by side, each in particle order:
 * the sums are those of one thread, whatever the thread count. The arrays
 * are cleared whole: they are small beside the particles, and the active
 * spans of the grid cover them. */
static void bodies_p2g(mrn_sim *sim, const mrn_transfer *tr, int momentum, int force) {
  mrn_contact *c = sim->contact;
  const size_t n = c->nnode * (size_t)c->nbodies;
  if (momentum) memset(c->mass, 0, 4 * n * sizeof(double)), memset(c->grad, 0, 3 * n * sizeof(double));
  if (force) memset(c->force, 0, 3 * n * sizeof(double));
  const int nb = c->nbodies;
#pragma omp parallel for schedule(dynamic, 1) if (sim->particles.n > MRN_OMP_MIN_ITEMS)
  for (int b = 0; b < nb; b++) body_p2g(sim, tr, b, momentum, force);
}

/* ---- the contact law at the nodes --------------------------------------------------- */

/* The velocity change of body b at node i, from the velocities `vel` of
 * the bodies there (`list`, `count` of them, centre-of-mass velocity vcm):
 * the normal is Nairn's average, along g_b - sum_{c != b} g_c, with
 * g_b = sum_p m_p grad N_i(x_p) over b's particles, which points from b
 * towards the node: out of b. b approaches when its velocity relative to vcm has a
 * positive component dn along it. Then dn is removed and friction takes
 * at most mu dn off the tangential part (all of it: stick), and 1 is
 * returned: the bodies are in contact. Moving apart, the share `keep` of dn
 * is removed (a node held since the last step, in V; see contact_apply). A
 * bonded pair takes vcm. With two bodies the normals are opposite, so the
 * changes conserve the node's momentum. */
static int body_change(const mrn_contact *c, size_t i, const double *vel, const int *list, int count, int k,
                       const double vcm[3], double keep, double dv[3]) {
  const size_t n = c->nnode;
  const int b = list[k];
  int other = -1;
  for (int j = 0; j < count; j++)
    if (j != k && (other < 0 || c->mass[list[j] * n + i] > c->mass[other * n + i])) other = list[j];
  const mrn_contact_pair *law = pair_law(c, b, other);
  const double *v = vel + 3 * (n * b + i);
  double rel[3], o[3] = {0, 0, 0}, on = 0.0;
  for (int d = 0; d < 3; d++) rel[d] = v[d] - vcm[d], dv[d] = 0.0;
  if (!law || law->kind == MRN_CONTACT_BONDED) {
    for (int d = 0; d < 3; d++) dv[d] = -rel[d];
    return 0;
  }
  if (law->has_normal) /* given, from a into b: out of a */
    for (int d = 0; d < 3; d++) o[d] = (b == law->a ? 1.0 : -1.0) * law->normal[d];
  else
    for (int j = 0; j < count; j++)
      for (int d = 0; d < 3; d++) o[d] += (j == k ? 1.0 : -1.0) * c->grad[3 * (n * list[j] + i) + d];
  for (int d = 0; d < 3; d++) on += o[d] * o[d];
  if (!(on > 0.0)) return 0;
  on = sqrt(on);
  double dn = 0.0, t[3], tn = 0.0;
  for (int d = 0; d < 3; d++) o[d] /= on, dn += rel[d] * o[d];
  if (!(dn > 0.0)) { /* moving apart, or no relative motion: free, but for the held part */
    if (keep > 0.0)
      for (int d = 0; d < 3; d++) dv[d] = -keep * dn * o[d];
    return 0;
  }
  for (int d = 0; d < 3; d++) t[d] = rel[d] - dn * o[d], tn += t[d] * t[d];
  tn = sqrt(tn);
  const double slip = tn > 0.0 ? fmin(law->mu * dn, tn) / tn : 0.0;
  for (int d = 0; d < 3; d++) dv[d] = -dn * o[d] - slip * t[d];
  return 1;
}

/* The contact law on every node two or more bodies share, on their
 * velocities V (`decide` 0) or V~ (`decide` 1).
 * On V~ it decides the contacts: a node where two bodies approached (not a
 * bond) gets MRN_GRID_BODIES_HELD in grid.contact, every other loses it.
 * On V (the step's, and a re-map's under MUSL and USAVG), bodies moving
 * apart at a node so marked lose the share `keep` of their normal velocity
 * relative to the node's centre of mass.
 * Returns the work of the changes sum_b m_b dV_b . (V_b - V_cm) after them
 * (000, Eq. 66, in the frame of the node's centre of mass: friction's, and
 * the bonds'; a normal change leaves no normal relative velocity, and a
 * share `keep` of it leaves (1 - keep) of it), of the nodes whose work this
 * process books (mrn_grid_owns). */
static double contact_apply(mrn_sim *sim, double *vel, int decide, double keep) {
  const mrn_contact *c = sim->contact;
  const size_t n = c->nnode;
  unsigned char *held = sim->grid.contact;
  const mrn_node_ranges r = mrn_grid_active_ranges(&sim->grid);
  double work = 0.0;
  if (decide)
    for (size_t i = 0; i < n; i++) held[i] &= (unsigned char)~MRN_GRID_BODIES_HELD;
  for (long k = 0; k < r.count; k++)
    for (long i = r.lo[k]; i < r.hi[k]; i++) {
      int list[MRN_MAX_BODIES], count = 0;
      double M = 0.0, vcm[3] = {0, 0, 0}, dv[MRN_MAX_BODIES][3];
      for (int b = 0; b < c->nbodies; b++) {
        const double m = c->mass[n * b + i];
        if (!(m > sim->mass_floor)) continue;
        list[count++] = b;
        M += m;
        for (int d = 0; d < 3; d++) vcm[d] += m * vel[3 * (n * b + i) + d];
      }
      if (count < 2) continue;
      for (int d = 0; d < 3; d++) vcm[d] /= M;
      const double kept = !decide && (held[i] & MRN_GRID_BODIES_HELD) ? keep : 0.0;
      int touching = 0;
      for (int j = 0; j < count; j++) touching |= body_change(c, (size_t)i, vel, list, count, j, vcm, kept, dv[j]);
      for (int j = 0; j < count; j++) {
        double *v = vel + 3 * (n * list[j] + i);
        const double m = c->mass[n * list[j] + i];
        const int books = mrn_grid_owns(&sim->grid, i); /* once over the processes */
        for (int d = 0; d < 3; d++) {
          v[d] += dv[j][d];
          if (books) work += m * dv[j][d] * (v[d] - vcm[d]);
        }
      }
      if (decide && touching) held[i] |= MRN_GRID_BODIES_HELD;
    }
  return work;
}

/* ---- the stages of the step on the per-body fields ----------------------------------- */

/* the contact's work, booked on each process's rows: summed over the
 * processes, the same on each (the grid stages before it end on an
 * agreement, and nothing between them fails) */
static void book_work(mrn_sim *sim, double work) {
  mrn_dist_reduce(sim, &work, 1, MRN_COMM_SUM);
  sim->work_contact += work;
}

/* V_b of every body with its face conditions, then the contact law with
 * friction: the normal impulse a body gets here is part of what holds it,
 * so Coulomb bounds its tangential part too. Its work reaches the
 * particles' momentum in the share s the velocity update takes of V (none
 * for FLIP, which takes V~ - V). A node in contact at the end of the last
 * step keeps the share 1 - s of its hold while its bodies move apart in V:
 * FLIP's V shows a separation the particles remember, not one the grid made;
 * the stress update would take it, and the impulse with which V~ undoes it
 * would do work on it (doc/numerics.md, "Contact between bodies"). */
static void bodies_velocity(mrn_sim *sim) {
  mrn_contact *c = sim->contact;
  const double share = mrn_hold_share(&sim->scheme);
  for (int b = 0; b < c->nbodies; b++) mrn_grid_velocity_on(sim, &c->view[b]);
  book_work(sim, share * contact_apply(sim, c->vel, 0, 1.0 - share));
}

/* V~_b of every body, then the contact law with friction, which decides
 * the contacts */
static void bodies_update(mrn_sim *sim, double dt) {
  mrn_contact *c = sim->contact;
  for (int b = 0; b < c->nbodies; b++) mrn_grid_update_on(sim, &c->view[b], dt);
  book_work(sim, contact_apply(sim, c->vel_new, 1, 0.0));
}

static double *gradients(mrn_contact *c, size_t np) {
  if (9 * np > c->L_cap) {
    double *L = realloc(c->L, 9 * np * sizeof(double));
    if (!L) return NULL;
    c->L = L, c->L_cap = 9 * np;
  }
  return c->L;
}

/* the stress update over dt from each particle's body velocity V_b (the
 * particles unmoved since the last P2G) */
static int bodies_material(mrn_sim *sim, const mrn_transfer *tr, double dt) {
  mrn_contact *c = sim->contact;
  const mrn_particles *ps = &sim->particles;
  const mrn_user_field *uf = mrn_particles_user_field(ps, MRN_BODY_FIELD);
  double *L = gradients(c, ps->n);
  if (!L && ps->n) return mrn_error("contact: out of memory");
  const long np = (long)ps->n;
#pragma omp parallel for schedule(static) if (np > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < np; p++) { /* each particle writes its own L only */
    mrn_transfer t = *tr;
    mrn_ref_stencil s;
    t.grid = &c->view[body_of(ps, uf, (size_t)p)];
    mrn_ref_stencil_build(&t, (size_t)p, &s);
    mrn_ref_gradient(&t, &s, t.grid->vel, L + 9 * p);
  }
  return mrn_update_from_gradients(sim, L, dt);
}

/* G2P from each particle's body field; the increments go to dx when not
 * NULL, the gradients from V~_b to L when not NULL */
static void bodies_g2p(mrn_sim *sim, const mrn_transfer *tr, double dt, double *dx, double *L) {
  mrn_contact *c = sim->contact;
  const mrn_particles *ps = &sim->particles;
  const mrn_user_field *uf = mrn_particles_user_field(ps, MRN_BODY_FIELD);
  const long np = (long)ps->n;
#pragma omp parallel for schedule(static) if (np > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < np; p++) { /* each particle writes its own state only */
    mrn_transfer t = *tr;
    t.grid = &c->view[body_of(ps, uf, (size_t)p)];
    mrn_ref_g2p_one(&t, (size_t)p, dt, dx, L);
  }
}

/* the single field the outputs and the walls' books see: the bodies'
 * centre-of-mass velocities */
static void total_field(mrn_sim *sim) {
  const mrn_contact *c = sim->contact;
  mrn_grid *g = &sim->grid;
  const size_t n = c->nnode;
  const mrn_node_ranges r = mrn_grid_active_ranges(g);
  for (long k = 0; k < r.count; k++)
    for (long i = r.lo[k]; i < r.hi[k]; i++) {
      double M = 0.0, P[3] = {0, 0, 0}, Q[3] = {0, 0, 0};
      for (int b = 0; b < c->nbodies; b++) {
        const double m = c->mass[n * b + i];
        M += m;
        for (int d = 0; d < 3; d++) P[d] += m * c->vel[3 * (n * b + i) + d], Q[d] += m * c->vel_new[3 * (n * b + i) + d];
      }
      g->mass[i] = M;
      for (int d = 0; d < 3; d++) {
        g->vel[3 * i + d] = M > sim->mass_floor ? P[d] / M : 0.0;
        g->vel_new[3 * i + d] = M > sim->mass_floor ? Q[d] / M : 0.0;
      }
    }
}

/* what the contact step cannot take yet, and fewer than two bodies */
static int contact_check(mrn_sim *sim) {
  const mrn_contact *c = sim->contact;
  const mrn_particles *ps = &sim->particles;
  const mrn_user_field *uf = mrn_particles_user_field(ps, MRN_BODY_FIELD);
  if (sim->scheme.velocity_update == MRN_VUPDATE_XPIC)
    return mrn_error("contact: XPIC is not available with contact between bodies (use PIC, FLIP, a blend or APIC)");
  if (sim->nsources) return mrn_error("contact: sources are not available with contact between bodies");
  if (sim->scheme.volumetric != MRN_VOLUMETRIC_STANDARD)
    return mrn_error("contact: scheme volumetric = '%s' is not available with contact between bodies (it would "
                     "average the volume change across the bodies)", mrn_volumetric_names()[sim->scheme.volumetric]);
  if (sim->scheme.holds != MRN_HOLDS_GRID)
    return mrn_error("contact: scheme holds = '%s' is not available with contact between bodies (each body's "
                     "velocity keeps its holds)", mrn_holds_names()[sim->scheme.holds]);
  if (mrn_particles_user_field(ps, MRN_POINT_FORCE_FIELD))
    return mrn_error("contact: point forces are not available with contact between bodies");
  /* a body's particles may all be on other processes */
  double count[MRN_MAX_BODIES] = {0};
  for (size_t p = 0; uf && p < ps->n; p++) count[body_of(ps, uf, p)] += 1.0;
  mrn_dist_reduce(sim, count, MRN_MAX_BODIES, MRN_COMM_SUM);
  unsigned used = 0;
  for (int b = 0; b < MRN_MAX_BODIES; b++) used |= (count[b] > 0.0 ? 1u : 0u) << b;
  for (int k = 0; k < c->npairs; k++)
    for (int e = 0; e < 2; e++) {
      const int b = e ? c->pair[k].b : c->pair[k].a;
      if (!(used >> b & 1u))
        return mrn_error("contact between '%s' and '%s': body '%s' has no particles (contact needs two bodies)",
                         c->name[c->pair[k].a], c->name[c->pair[k].b], c->name[b]);
    }
  return MRN_OK;
}

/* the re-mapped end of MUSL and USAVG (solver/step.c, move_remap_update) */
static int bodies_remap(mrn_sim *sim, mrn_transfer *tr, double dt, double material_dt) {
  mrn_particles *ps = &sim->particles;
  double *dx = malloc((3 * ps->n + 1) * sizeof(double));
  if (!dx) return mrn_error("contact: out of memory");
  bodies_g2p(sim, tr, dt, dx, NULL);
  bodies_p2g(sim, tr, 1, 0);
  int rc = mrn_dist_sum_bodies(sim, MRN_CLEAR_MASS_MOM, MRN_OK);
  if (rc) {
    free(dx);
    return rc;
  }
  bodies_velocity(sim);
  rc = bodies_material(sim, tr, material_dt);
  for (size_t i = 0; i < 3 * ps->n; i++) ps->x[i] += dx[i];
  free(dx);
  return rc;
}

/* In a distributed run each P2G of the bodies' fields is followed by their
 * halo sum (solver/dist.h), which agrees first on what happened since the
 * last: a stage that failed passes its code on to it. */
int mrn_contact_step(mrn_sim *sim, mrn_transfer *tr, double dt) {
  int rc = contact_check(sim); /* the same on every process */
  if (rc) return rc;
  const mrn_stress_update_kind su = sim->scheme.stress_update;
  const int first = su == MRN_STRESS_USF || su == MRN_STRESS_USAVG;
  if ((rc = fields_alloc(sim->contact, &sim->grid)) == MRN_OK) {
    mrn_p2g(tr, 1, 0); /* the single field: the active spans, the sorting */
    bodies_p2g(sim, tr, 1, !first);
  }
  if ((rc = mrn_dist_sum_bodies(sim, MRN_CLEAR_MASS_MOM | (first ? 0u : MRN_CLEAR_FORCE), rc))) return rc;
  bodies_velocity(sim);
  if (first) {
    rc = bodies_material(sim, tr, su == MRN_STRESS_USF ? dt : 0.5 * dt);
    if (rc == MRN_OK) bodies_p2g(sim, tr, 0, 1);
    if ((rc = mrn_dist_sum_bodies(sim, MRN_CLEAR_FORCE, rc))) return rc;
  }
  bodies_update(sim, dt);
  total_field(sim);
  switch (su) {
  case MRN_STRESS_USF: bodies_g2p(sim, tr, dt, NULL, NULL); return MRN_OK;
  case MRN_STRESS_USL: {
    double *L = gradients(sim->contact, sim->particles.n);
    if (!L && sim->particles.n) return mrn_error("contact: out of memory");
    bodies_g2p(sim, tr, dt, NULL, L);
    return mrn_update_from_gradients(sim, L, dt);
  }
  case MRN_STRESS_MUSL: return bodies_remap(sim, tr, dt, dt);
  case MRN_STRESS_USAVG: return bodies_remap(sim, tr, dt, 0.5 * dt);
  }
  return MRN_OK;
}
