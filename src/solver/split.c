#include "solver/split.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/tensor.h"
#include "material/principal.h"
#include "particles/domain.h"
#include "solver/dist.h"
#include "solver/simulation.h"

/* where the two fields sit in a particle's record of ps->user, or -1 */
typedef struct split_fields {
  int domain, level;
} split_fields;

static split_fields find_fields(const mrn_particles *ps) {
  const mrn_user_field *l = mrn_particles_user_field(ps, MRN_SPLIT_LEVEL_FIELD);
  split_fields f = {mrn_particle_domain_offset(ps), -1};
  if (l && l->ncomp == 1) f.level = l->offset;
  return f;
}

static int add_field(mrn_particles *ps, const char *name, int ncomp, const char *unit) {
  const mrn_user_field *u = mrn_particles_user_field(ps, name);
  if (!u) return mrn_particles_add_user_field(ps, name, ncomp, 0.0, unit);
  if (u->ncomp != ncomp)
    return mrn_error("split: the particle field '%s' has %d components, not %d: the name is the splitting's", name,
                     u->ncomp, ncomp);
  return MRN_OK;
}

int mrn_sim_set_split(mrn_sim *sim, double stretch, int max_level) {
  if (stretch != 0.0 && !(stretch > 1.0 && isfinite(stretch)))
    return mrn_error("split: stretch %g is not above 1 (or 0: no splitting)", stretch);
  if (max_level < 0 || max_level > MRN_SPLIT_MAX_LEVEL)
    return mrn_error("split: max_level %d is not in [0, %d]", max_level, MRN_SPLIT_MAX_LEVEL);
  if (stretch > 0.0 && (add_field(&sim->particles, MRN_SPLIT_DOMAIN_FIELD, 9, "m") != MRN_OK ||
                        add_field(&sim->particles, MRN_SPLIT_LEVEL_FIELD, 1, "") != MRN_OK))
    return MRN_ERR;
  sim->split_stretch = stretch;
  sim->split_max_level = max_level;
  return MRN_OK;
}

/* one particle's domain: U0 (3 x 3, the in-plane block in 2D), its image
 * A = F U0, the split count and r_ref */
typedef struct domain {
  double U0[9], A[9];
  int level;
  double r_ref;
} domain;

static void read_domain(const mrn_sim *sim, split_fields f, size_t i, domain *dm) {
  const mrn_particles *ps = &sim->particles;
  const int dim = sim->dim;
  dm->level = (int)ps->user[i * (size_t)ps->user_stride + (size_t)f.level];
  /* each split halves vol0: the ancestor's vol0 is vol0 2^level */
  dm->r_ref = 0.5 * pow(ldexp(ps->vol0[i], dm->level), 1.0 / dim);
  mrn_particle_domain(ps, dim, i, f.domain, dm->r_ref, dm->U0, dm->A);
}

/* the largest half-axis sigma of A's ellipsoid, its direction n now and the
 * unit m it comes from (A m = sigma n): the largest singular value and
 * vectors of A, from the eigenvectors of A A^T */
static double largest_axis(int dim, const double A[9], double n[3], double m[3]) {
  double B[9], lam[3], V[9];
  for (int a = 0; a < dim; a++)
    for (int b = 0; b < dim; b++) {
      double s = 0.0;
      for (int k = 0; k < dim; k++) s += A[3 * a + k] * A[3 * b + k];
      B[dim * a + b] = s;
    }
  mrn_jacobi_eigen(dim, B, lam, V);
  const double sigma = sqrt(lam[0] > 0.0 ? lam[0] : 0.0);
  for (int a = 0; a < 3; a++) n[a] = a < dim ? V[dim * a] : 0.0;
  for (int b = 0; b < 3; b++) {
    double s = 0.0;
    for (int a = 0; a < dim; a++) s += A[3 * a + b] * n[a];
    m[b] = sigma > 0.0 ? s / sigma : 0.0;
  }
  return sigma;
}

double mrn_split_stretch(const mrn_sim *sim, size_t i) {
  const split_fields f = find_fields(&sim->particles);
  if (f.domain < 0 || f.level < 0) return 0.0;
  domain dm;
  read_domain(sim, f, i, &dm);
  double n[3], m[3];
  return largest_axis(sim->dim, dm.A, n, m) / dm.r_ref;
}

/* particle i and its clone j: the two halves of i's domain across n */
static void make_children(mrn_sim *sim, split_fields f, size_t i, size_t j, const domain *dm, double sigma,
                          const double n[3], const double m[3]) {
  mrn_particles *ps = &sim->particles;
  double U[9]; /* U0 (I - m m^T / 2): the reference half-axis along m halved */
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      double um = 0.0;
      for (int k = 0; k < 3; k++) um += dm->U0[3 * a + k] * m[k];
      U[3 * a + b] = dm->U0[3 * a + b] - 0.5 * um * m[b];
    }
  for (int a = 0; a < 3; a++) {
    /* the children's centres now, +-sigma n / 2, and where they were: F^-1
     * of that, U0 m / 2 */
    double d = 0.5 * sigma * n[a], dX = 0.0;
    for (int k = 0; k < 3; k++) dX += 0.5 * dm->U0[3 * a + k] * m[k];
    ps->x[3 * i + a] += d, ps->x[3 * j + a] -= d;
    ps->x0[3 * i + a] += dX, ps->x0[3 * j + a] -= dX;
  }
  const size_t c[2] = {i, j};
  for (int k = 0; k < 2; k++) {
    const size_t p = c[k];
    ps->mass[p] *= 0.5, ps->vol0[p] *= 0.5; /* the volume J vol0 halves with vol0 */
    ps->e_elastic[p] *= 0.5, ps->w_plastic[p] *= 0.5;
    double *u = ps->user + p * (size_t)ps->user_stride;
    memcpy(u + f.domain, U, sizeof U);
    u[f.level] = dm->level + 1;
  }
}

/* a particle due to split: its id and index, its domain and the axis */
typedef struct due {
  int64_t id;
  size_t i;
  domain dm;
  double sigma, n[3], m[3];
} due;

static int by_id(const void *a, const void *b) {
  const int64_t x = ((const due *)a)->id, y = ((const due *)b)->id;
  return (x > y) - (x < y);
}

/* whether particle i is due; its domain and axis into *d */
static int is_due(const mrn_sim *sim, split_fields f, size_t i, due *d) {
  read_domain(sim, f, i, &d->dm);
  if (d->dm.level >= sim->split_max_level) return 0;
  const double limit = sim->split_stretch * d->dm.r_ref;
  double frob = 0.0; /* sigma^2 <= |A|^2: most particles stop here */
  for (int k = 0; k < 9; k++) frob += d->dm.A[k] * d->dm.A[k];
  if (frob <= limit * limit) return 0;
  d->sigma = largest_axis(sim->dim, d->dm.A, d->n, d->m);
  d->id = sim->particles.id[i];
  d->i = i;
  return d->sigma > limit;
}

/* the particles due, in the order of their ids: *count of them in *out
 * (to be freed); 0 or MRN_ERR (out of memory, message set) */
static int find_due(const mrn_sim *sim, split_fields f, due **out, size_t *count) {
  size_t cap = 0;
  due d;
  *out = NULL;
  *count = 0;
  for (size_t i = 0; i < sim->particles.n; i++) {
    if (!is_due(sim, f, i, &d)) continue;
    if (*count == cap) {
      due *grown = realloc(*out, (cap = cap ? 2 * cap : 64) * sizeof *grown);
      if (!grown) return mrn_error("split: out of memory");
      *out = grown;
    }
    (*out)[(*count)++] = d;
  }
  if (*count) qsort(*out, *count, sizeof **out, by_id);
  return MRN_OK;
}

/* The second children's ids: next_id onwards, in the order of their
 * parents' ids over every process (mrn_dist_key_places), so that each is
 * the one a run on one process gives. */
static int split_due(mrn_sim *sim, split_fields f, due *list, size_t count, int rc, int64_t *total) {
  mrn_particles *ps = &sim->particles;
  int64_t *key = malloc(2 * (count + 1) * sizeof *key), *place = key ? key + count + 1 : NULL;
  if (!key) rc = mrn_error("split: out of memory"), count = 0;
  for (size_t k = 0; k < count; k++) key[k] = list[k].id;
  rc = mrn_dist_key_places(sim, key, count, place, total, rc);
  for (size_t k = 0; rc == MRN_OK && k < count; k++) {
    const long j = mrn_particles_clone(ps, list[k].i, ps->next_id + place[k]);
    if (j < 0) rc = MRN_ERR;
    else make_children(sim, f, list[k].i, (size_t)j, &list[k].dm, list[k].sigma, list[k].n, list[k].m);
  }
  if (rc == MRN_OK) ps->next_id += *total;
  free(key);
  return rc;
}

long mrn_sim_split(mrn_sim *sim) {
  if (!(sim->split_stretch > 0.0)) return 0;
  const split_fields f = find_fields(&sim->particles);
  if (f.domain < 0 || f.level < 0) {
    mrn_error("split: the particle fields '%s' and '%s' are missing (switch splitting on with mrn_sim_set_split)",
              MRN_SPLIT_DOMAIN_FIELD, MRN_SPLIT_LEVEL_FIELD);
    return -1;
  }
  size_t count;
  due *list;
  int rc = find_due(sim, f, &list, &count);
  int64_t total = 0;
  rc = mrn_dist_agree(sim, split_due(sim, f, list, count, rc, &total));
  free(list);
  if (rc != MRN_OK) return -1;
  if (total) {
    sim->split_count += (long)total;
    mrn_sim_particles_changed(sim);
  }
  return (long)total;
}
