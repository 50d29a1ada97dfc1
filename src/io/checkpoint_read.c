/* moraine: reading and validating a checkpoint file (layout in
 * doc/checkpoint-format.md).
 *
 * Each section of the file is read into a ck_data and checked on the way:
 * presence, type, rank and shape come from the h5util reader; this file adds
 * the meaning — dimensions, ranges, names of kinds, counts that agree, finite
 * particle values, material indices and ids. The first problem found is the
 * message. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/tensor.h"
#include "core/warn.h"
#include "io/checkpoint.h"
#include "io/checkpoint_internal.h"
#include "io/h5util.h"

/* ---- shared tables -------------------------------------------------------- */

/* from the engine's own names, so a policy added there is known here too */
const char *const *ck_dt_kind_names(void) {
  static const char *names[32];
  int k = 0;
  for (; k < 31; k++) {
    const char *name = mrn_dt_kind_name((mrn_dt_kind)k);
    if (strcmp(name, "?") == 0) break;
    names[k] = name;
  }
  names[k] = NULL;
  return names;
}

/* ---- small checks --------------------------------------------------------- */

/* fail with the message unless `ok` */
static int require(mrn_h5r *r, int ok, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int require(mrn_h5r *r, int ok, const char *fmt, ...) {
  if (ok || r->failed) return r->failed ? MRN_ERR_IO : MRN_OK;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return mrn_h5r_fail(r, "%s", msg);
}

/* a finite double attribute of at least `min` (pass -HUGE_VAL for any) */
static void read_finite(mrn_h5r *r, const char *obj, const char *name, double min, double *out) {
  if (mrn_h5r_double(r, obj, name, out)) return;
  require(r, isfinite(*out), "attribute '%s' of %s is %s, expected a finite number", name, obj, mrn_num(*out).s);
  require(r, *out >= min, "attribute '%s' of %s is %g, expected at least %g", name, obj, *out, min);
}

static void read_int_in(mrn_h5r *r, const char *obj, const char *name, int64_t lo, int64_t hi, int64_t *out) {
  if (mrn_h5r_int(r, obj, name, out)) return;
  require(r, *out >= lo && *out <= hi, "attribute '%s' of %s is %lld, expected %lld to %lld", name, obj,
          (long long)*out, (long long)lo, (long long)hi);
}

/* pass an engine message on, prefixed with where it came from */
static void fail_with_engine_message(mrn_h5r *r, const char *where) {
  char inner[1024];
  snprintf(inner, sizeof inner, "%s", mrn_error_message());
  mrn_h5r_fail(r, "%s: %s", where, inner);
}

/* ---- / and /simulation ---------------------------------------------------- */

static void read_root(mrn_h5r *r, ck_data *d) {
  if (!mrn_h5r_has_attr(r, "/", "format")) {
    mrn_h5r_fail(r, "not a moraine checkpoint (no 'format' attribute on the root group)");
    return;
  }
  char format[64];
  if (mrn_h5r_string(r, "/", "format", format, sizeof format)) return;
  if (require(r, strcmp(format, MRN_CHECKPOINT_FORMAT) == 0, "not a moraine checkpoint (format is '%s')", format))
    return;
  int64_t version = 0;
  if (mrn_h5r_int(r, "/", "version", &version)) return;
  if (version > MRN_CHECKPOINT_VERSION)
    mrn_h5r_fail(r, "written by a newer moraine (format version %lld; this moraine reads version %d)",
                 (long long)version, MRN_CHECKPOINT_VERSION);
  require(r, version >= 1, "unknown checkpoint format version %lld", (long long)version);
  d->version = (int)version;
  mrn_h5r_string(r, "/", "moraine_version", d->moraine_version, sizeof d->moraine_version);
  /* since version 2 the table is part of the format: a file without one was
   * damaged in its first bytes, or rewritten by another program */
  require(r, d->checksums || version < 2,
          "format version %lld, but no checksum table in its first bytes: the file is damaged or was rewritten by "
          "another program",
          (long long)version);
}

/* 1 when the file predates the attribute `name` of /simulation (a version
 * before `since`) and lacks it: it loads with the row's initial value. A
 * file of a later version must hold it, and reading it says it is missing. */
static int predates(mrn_h5r *r, const ck_data *d, const char *name, int since) {
  return d->version < since && !mrn_h5r_has_attr(r, "/simulation", name);
}

/* A row of solver/sim_scalars.h: the value read and checked, or `initial`
 * when the file predates it or it failed (the message is then set). */
static double get_f64(mrn_h5r *r, const ck_data *d, const char *name, mrn_scalar_check c, int since, double initial) {
  double v;
  if (predates(r, d, name, since)) return initial;
  read_finite(r, "/simulation", name, c.min, &v);
  return r->failed ? initial : v;
}

/* a vector's components need only be finite (MRN_ANY) */
static void get_f64s(mrn_h5r *r, const ck_data *d, const char *name, int since, double initial, double *out, int n) {
  const char *g = "/simulation";
  for (int k = 0; k < n; k++) out[k] = initial;
  if (predates(r, d, name, since) || mrn_h5r_doubles(r, g, name, out, n)) return;
  for (int k = 0; k < n; k++) require(r, isfinite(out[k]), "attribute '%s' of %s has a non-finite component", name, g);
}

static int64_t get_int(mrn_h5r *r, const ck_data *d, const char *name, mrn_scalar_check c, int since,
                       int64_t initial) {
  int64_t v;
  if (predates(r, d, name, since)) return initial;
  read_int_in(r, "/simulation", name, c.lo, c.hi, &v);
  return r->failed ? initial : v;
}

static int get_name(mrn_h5r *r, const ck_data *d, const char *name, mrn_scalar_check c, int since, int initial) {
  int v;
  if (predates(r, d, name, since)) return initial;
  mrn_h5r_choice(r, "/simulation", name, c.names(), &v);
  return r->failed ? initial : v;
}

#define READ_SCALAR(ctype, name, kind, check, since, initial, ...) \
  READ_##kind(ctype, d->name, #name, ((mrn_scalar_check){check}), since, initial);
#define READ_F64(ctype, at, key, c, since, initial) at = get_f64(r, d, key, c, since, initial)
#define READ_F64X3(ctype, at, key, c, since, initial) get_f64s(r, d, key, since, initial, at, 3)
#define READ_I32(ctype, at, key, c, since, initial) at = (ctype)get_int(r, d, key, c, since, initial)
#define READ_I64(ctype, at, key, c, since, initial) at = (ctype)get_int(r, d, key, c, since, initial)
#define READ_NAME(ctype, at, key, c, since, initial) at = (ctype)get_name(r, d, key, c, since, initial)

/* every row of solver/sim_scalars.h, in its order: the first problem is the message */
static void read_simulation(mrn_h5r *r, ck_data *d) {
  if (mrn_h5r_group(r, "/simulation")) return;
  MRN_SIM_SCALARS(READ_SCALAR)
}

/* ---- /grid ------------------------------------------------------------------ */

static void read_grid_axis(mrn_h5r *r, ck_data *d, int k, const int64_t *ncell) {
  const char *g = "/grid";
  if (require(r, isfinite(d->origin[k]), "%s: origin[%d] is %s, expected a finite number", g, k + 1,
              mrn_num(d->origin[k]).s) ||
      require(r, d->size[k] > 0 && isfinite(d->size[k]), "%s: size[%d] is %s, expected > 0", g, k + 1,
              mrn_num(d->size[k]).s) ||
      require(r, ncell[k] >= 1 && ncell[k] <= 1000000, "%s: ncell[%d] is %lld, expected 1 to 1000000", g, k + 1,
              (long long)ncell[k]))
    return;
  /* the same rounding rule as the grid itself, so the rebuilt grid has these cells */
  double cells = d->size[k] / d->cell;
  require(r, lround(cells) == ncell[k] && fabs(cells - (double)ncell[k]) <= 1e-6,
          "%s: size[%d] = %g is %.6f cells of %g, but ncell[%d] is %lld", g, k + 1, d->size[k], cells, d->cell,
          k + 1, (long long)ncell[k]);
  d->ncell[k] = (int)ncell[k];
}

/* the friction faces' and the bodies' contact states; files written before
 * they were kept have none, and their first step decides every contact
 * afresh */
static void read_contacts(mrn_h5r *r, ck_data *d) {
  const char *g = "/grid";
  if (!mrn_h5r_has_attr(r, g, "contact_count")) return;
  int64_t nodes = 1;
  for (int k = 0; k < d->dim; k++) nodes *= d->ncell[k] + 1 + 2 * MRN_GRID_PAD;
  read_int_in(r, g, "contact_count", 0, nodes, &d->ncontact);
  if (r->failed) return;
  d->contact = mrn_h5r_dataset(r, "/grid/contact", MRN_H5_INT64, d->ncontact, 2);
  for (int64_t k = 0; k < d->ncontact && d->contact && !r->failed; k++)
    require(r, d->contact[2 * k] >= 0 && d->contact[2 * k] < nodes && d->contact[2 * k + 1] > 0 &&
                   d->contact[2 * k + 1] < (1 << MRN_FACE_COUNT),
            "/grid/contact: row %lld (node %lld, bits %lld) is not a node of the grid with face bits",
            (long long)k + 1, (long long)d->contact[2 * k], (long long)d->contact[2 * k + 1]);
  if (r->failed || !mrn_h5r_has_attr(r, g, "bodies_held_count")) return;
  read_int_in(r, g, "bodies_held_count", 0, nodes, &d->nbodies_held);
  if (r->failed) return;
  d->bodies_held = mrn_h5r_dataset(r, "/grid/bodies_held", MRN_H5_INT64, d->nbodies_held, MRN_H5_RANK1);
  for (int64_t k = 0; k < d->nbodies_held && d->bodies_held && !r->failed; k++)
    require(r, d->bodies_held[k] >= 0 && d->bodies_held[k] < nodes,
            "/grid/bodies_held: row %lld (node %lld) is not a node of the grid", (long long)k + 1,
            (long long)d->bodies_held[k]);
}

static void read_grid(mrn_h5r *r, ck_data *d) {
  const char *g = "/grid";
  int64_t dim = 0, ncell[3] = {0, 0, 0};
  if (mrn_h5r_group(r, g) || mrn_h5r_int(r, g, "dim", &dim)) return;
  require(r, dim == d->dim, "%s: dimension %lld, but /simulation has dimension %d", g, (long long)dim, d->dim);
  mrn_h5r_doubles(r, g, "origin", d->origin, 3);
  mrn_h5r_doubles(r, g, "size", d->size, 3);
  read_finite(r, g, "cell", 0.0, &d->cell);
  require(r, d->cell > 0, "%s: cell size %g, expected > 0", g, d->cell);
  mrn_h5r_ints(r, g, "ncell", ncell, 3);
  for (int k = 0; k < d->dim && !r->failed; k++) read_grid_axis(r, d, k, ncell);
  if (!r->failed) read_contacts(r, d);
}

/* ---- /scheme, /boundary, /dt_policy ------------------------------------------ */

static void read_scheme(mrn_h5r *r, ck_data *d) {
  const char *g = "/scheme";
  mrn_scheme *s = &d->scheme;
  int gv = 0, vu = 0, pu = 0, su = 0;
  mrn_scheme_default(s); /* anything the file does not set keeps its default */
  if (mrn_h5r_group(r, g)) return;
  mrn_h5r_string(r, g, "name", s->name, sizeof s->name);
  mrn_h5r_choice(r, g, "grid_velocity", mrn_grid_velocity_names(), &gv);
  mrn_h5r_choice(r, g, "velocity_update", mrn_velocity_update_names(), &vu);
  mrn_h5r_choice(r, g, "position_update", mrn_position_update_names(), &pu);
  mrn_h5r_choice(r, g, "stress_update", mrn_stress_update_names(), &su);
  if (!mrn_h5r_double(r, g, "flip_fraction", &s->flip_fraction))
    require(r, s->flip_fraction >= 0.0 && s->flip_fraction <= 1.0,
            "attribute 'flip_fraction' of %s is %s, expected 0 to 1", g, mrn_num(s->flip_fraction).s);
  s->grid_velocity = (mrn_grid_velocity_kind)gv;
  s->velocity_update = (mrn_velocity_update_kind)vu;
  s->position_update = (mrn_position_update_kind)pu;
  s->stress_update = (mrn_stress_update_kind)su;
  int64_t order = 0, mls = 0;
  read_int_in(r, g, "xpic_order", 1, MRN_XPIC_MAX_ORDER, &order);
  read_int_in(r, g, "mls_gradient", 0, 1, &mls);
  s->xpic_order = (int)order;
  s->mls_gradient = (int)mls;
  int vol = MRN_VOLUMETRIC_STANDARD; /* absent: standard */
  if (mrn_h5r_has_attr(r, g, "volumetric")) mrn_h5r_choice(r, g, "volumetric", mrn_volumetric_names(), &vol);
  s->volumetric = (mrn_volumetric_kind)vol;
  int holds = MRN_HOLDS_GRID; /* absent: grid */
  if (mrn_h5r_has_attr(r, g, "holds")) mrn_h5r_choice(r, g, "holds", mrn_holds_names(), &holds);
  s->holds = (mrn_holds_kind)holds;
  /* the three choices must also fit together */
  if (!r->failed && mrn_scheme_validate(s) != MRN_OK) fail_with_engine_message(r, g);
}

static void read_boundary(mrn_h5r *r, ck_data *d) {
  if (mrn_h5r_group(r, "/boundary")) return;
  for (int f = 0; f < MRN_FACE_COUNT && !r->failed; f++) {
    char g[64];
    snprintf(g, sizeof g, "/boundary/%s", mrn_face_name(f));
    int kind = 0;
    if (mrn_h5r_group(r, g) || mrn_h5r_choice(r, g, "kind", mrn_bc_kind_names(), &kind)) return;
    d->boundary.face[f].kind = (mrn_bc_kind)kind;
    read_finite(r, g, "mu", 0.0, &d->boundary.face[f].mu);
    int64_t check = 0; /* absent from older checkpoints: off */
    if (mrn_h5r_has_attr(r, g, "gap_check")) mrn_h5r_int(r, g, "gap_check", &check);
    d->boundary.face[f].gap_check = check != 0;
    double *v = d->boundary.face[f].velocity;
    if (!mrn_h5r_doubles(r, g, "velocity", v, 3))
      require(r, isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]),
              "attribute 'velocity' of %s has a non-finite component", g);
  }
  /* periodic faces come in pairs */
  if (!r->failed && mrn_boundary_validate(&d->boundary, d->dim) != MRN_OK) fail_with_engine_message(r, "/boundary");
}

static void read_dt_policy(mrn_h5r *r, ck_data *d) {
  const char *g = "/dt_policy";
  int kind = 0;
  if (mrn_h5r_group(r, g) || mrn_h5r_choice(r, g, "kind", ck_dt_kind_names(), &kind)) return;
  d->dt_kind = (mrn_dt_kind)kind;
  read_finite(r, g, "value", 0.0, &d->dt_value);
  if (d->dt_kind != MRN_DT_CALLBACK)
    require(r, d->dt_value > 0, "attribute 'value' of %s is %g, expected > 0 for the %s policy", g, d->dt_value,
            mrn_dt_kind_name(d->dt_kind));
  read_finite(r, g, "min", 0.0, &d->dt_min);
  read_finite(r, g, "max", 0.0, &d->dt_max);
}

/* ---- /materials ---------------------------------------------------------------- */

typedef struct param_check {
  mrn_h5r *r;
  const char *group;
  const mrn_material_type *type;
} param_check;

/* every stored parameter must be one the model knows */
static int known_param(void *user, const char *key) {
  param_check *c = user;
  if (mrn_spec_find(c->type->params, c->type->nparams, key)) return 0;
  mrn_h5r_fail(c->r, "%s: material type %s has no parameter '%s'", c->group, c->type->name, key);
  return 1;
}

static mrn_material *read_params(mrn_h5r *r, const char *g, const mrn_material_type *type) {
  char pg[96];
  snprintf(pg, sizeof pg, "%s/parameters", g);
  param_check check = {r, pg, type};
  if (mrn_h5r_group(r, pg) || mrn_h5r_each_attr(r, pg, known_param, &check)) return NULL;
  mrn_material *m = mrn_material_new(type);
  if (!m) {
    fail_with_engine_message(r, g);
    return NULL;
  }
  for (int i = 0; i < type->nparams && !r->failed; i++) {
    const char *key = type->params[i].key;
    double value;
    /* a parameter left out keeps its default; prepare() names a missing required one */
    if (!mrn_h5r_has_attr(r, pg, key) || mrn_h5r_double(r, pg, key, &value)) continue;
    if (mrn_material_set(m, key, value) != MRN_OK) fail_with_engine_message(r, g);
  }
  if (!r->failed && mrn_material_prepare(m) != MRN_OK) fail_with_engine_message(r, g);
  if (r->failed) {
    mrn_material_unref(m);
    return NULL;
  }
  return m;
}

static mrn_material *read_material(mrn_h5r *r, int index) {
  char g[64], type_name[64], name[sizeof ((mrn_material *)0)->name];
  snprintf(g, sizeof g, "/materials/%d", index);
  if (mrn_h5r_group(r, g) || mrn_h5r_string(r, g, "type", type_name, sizeof type_name) ||
      mrn_h5r_string(r, g, "name", name, sizeof name))
    return NULL;
  const mrn_material_type *type = mrn_material_type_find(type_name);
  if (!type) {
    char known[512] = "";
    size_t used = 0;
    for (int i = 0; i < mrn_material_type_count() && used < sizeof known; i++)
      used += (size_t)snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "",
                               mrn_material_type_at(i)->name);
    mrn_h5r_fail(r, "%s: unknown material type '%s' (this moraine knows: %s)", g, type_name, known);
    return NULL;
  }
  mrn_material *m = read_params(r, g, type);
  if (m) snprintf(m->name, sizeof m->name, "%s", name);
  return m;
}

static void read_materials(mrn_h5r *r, ck_data *d) {
  int64_t count = 0;
  if (mrn_h5r_group(r, "/materials")) return;
  read_int_in(r, "/materials", "count", 0, MRN_MAX_MATERIALS, &count);
  for (int i = 0; i < count && !r->failed; i++) {
    d->materials[i] = read_material(r, i);
    if (d->materials[i]) d->nmaterials = i + 1;
  }
}

/* ---- /particles ---------------------------------------------------------------- */

static int max_nstate(const ck_data *d) {
  int most = 0;
  for (int i = 0; i < d->nmaterials; i++)
    if (d->materials[i]->type->nstate > most) most = d->materials[i]->type->nstate;
  return most;
}

static void read_particle_arrays(mrn_h5r *r, ck_data *d) {
  char path[128];
  int nf = mrn_particle_field_count();
  d->field = calloc((size_t)nf, sizeof *d->field);
  if (!d->field) {
    mrn_h5r_fail(r, "out of memory");
    return;
  }
  for (int i = 0; i < nf && !r->failed; i++) {
    const mrn_particle_field_info *f = mrn_particle_field_at(i);
    snprintf(path, sizeof path, "/particles/%s", f->name);
    d->field[i] = mrn_h5r_dataset(r, path, MRN_H5_FLOAT64, d->n, f->ncomp == 1 ? MRN_H5_RANK1 : f->ncomp);
  }
  d->material = mrn_h5r_dataset(r, "/particles/material", MRN_H5_INT32, d->n, MRN_H5_RANK1);
  d->id = mrn_h5r_dataset(r, "/particles/id", MRN_H5_INT64, d->n, MRN_H5_RANK1);
  d->state = mrn_h5r_dataset(r, "/particles/state", MRN_H5_FLOAT64, d->n, d->state_stride);
}

/* /particles/user, when the deck registered fields (see save_user_fields) */
static void read_user_fields(mrn_h5r *r, ck_data *d) {
  const char *g = "/particles/user";
  if (mrn_h5r_exists(r, g) != 1) return;
  int64_t count = 0, comps[MRN_USER_FIELDS_MAX];
  double init[MRN_USER_FIELDS_MAX];
  char names[MRN_USER_FIELDS_MAX * MRN_USER_FIELD_NAME];
  read_int_in(r, g, "count", 0, MRN_USER_FIELDS_MAX, &count);
  if (r->failed || mrn_h5r_string(r, g, "names", names, sizeof names)) return;
  if (count > 0 && (mrn_h5r_ints(r, g, "components", comps, (int)count) ||
                    mrn_h5r_doubles(r, g, "init", init, (int)count)))
    return;
  char *save = NULL, *name = strtok_r(names, ",", &save);
  for (int i = 0; i < count && !r->failed; i++, name = strtok_r(NULL, ",", &save)) {
    if (require(r, name && strlen(name) < MRN_USER_FIELD_NAME && comps[i] >= 1 && comps[i] <= 9,
                "%s: field %d of %lld is not named or has %lld components", g, i + 1, (long long)count,
                (long long)comps[i]))
      return;
    mrn_user_field *f = &d->user[d->nuser];
    snprintf(f->name, sizeof f->name, "%s", name);
    f->ncomp = (int)comps[i];
    f->init = init[i];
    char path[128];
    snprintf(path, sizeof path, "%s/%s", g, name);
    if (mrn_h5r_has_attr(r, path, "units")) mrn_h5r_string(r, path, "units", f->unit, sizeof f->unit);
    d->user_values[d->nuser++] = mrn_h5r_dataset(r, path, MRN_H5_FLOAT64, d->n, f->ncomp == 1 ? MRN_H5_RANK1 : f->ncomp);
  }
}

static void read_particles(mrn_h5r *r, ck_data *d) {
  const char *g = "/particles";
  int64_t stride = 0;
  if (mrn_h5r_group(r, g)) return;
  read_int_in(r, g, "count", 0, INT64_MAX, &d->n);
  read_int_in(r, g, "next_id", 1, CK_MAX_COUNTER, &d->next_id);
  read_int_in(r, g, "state_stride", 0, CK_MAX_STATE_STRIDE, &stride);
  if (r->failed) return;
  d->state_stride = (int)stride;
  /* the engine sizes the history storage to the widest model */
  if (require(r, d->state_stride >= max_nstate(d),
              "%s: state_stride is %d, but the materials keep %d history variables per particle", g,
              d->state_stride, max_nstate(d)))
    return;
  read_particle_arrays(r, d);
  read_user_fields(r, d);
}

/* ---- particle values ---------------------------------------------------------- */

static int cmp_int64(const void *a, const void *b) {
  int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
  return (x > y) - (x < y);
}

/* ids are positive, below next_id (new particles must not reuse one) and unique */
static void check_ids(mrn_h5r *r, const ck_data *d) {
  for (int64_t p = 0; p < d->n && !r->failed; p++)
    require(r, d->id[p] >= 1 && d->id[p] < d->next_id,
            "/particles/id: particle %lld has id %lld, expected 1 to next_id - 1 = %lld", (long long)p,
            (long long)d->id[p], (long long)(d->next_id - 1));
  if (r->failed || d->n < 2) return;
  int64_t *sorted = malloc((size_t)d->n * sizeof *sorted);
  if (!sorted) {
    mrn_h5r_fail(r, "out of memory");
    return;
  }
  memcpy(sorted, d->id, (size_t)d->n * sizeof *sorted);
  qsort(sorted, (size_t)d->n, sizeof *sorted, cmp_int64);
  for (int64_t i = 1; i < d->n && !r->failed; i++)
    require(r, sorted[i] != sorted[i - 1], "/particles/id: id %lld appears more than once", (long long)sorted[i]);
  free(sorted);
}

/* Every particle field must be finite: a NaN position would send the
 * transfer kernels outside the grid arrays. History variables are stored as
 * the models keep them and are not judged here. */
static void check_finite(mrn_h5r *r, const ck_data *d) {
  for (int i = 0; i < mrn_particle_field_count() && !r->failed; i++) {
    const mrn_particle_field_info *f = mrn_particle_field_at(i);
    size_t count = (size_t)d->n * (size_t)f->ncomp;
    for (size_t k = 0; k < count; k++)
      if (!isfinite(d->field[i][k])) {
        size_t p = k / (size_t)f->ncomp;
        mrn_h5r_fail(r, "/particles/%s: particle %zu (id %lld) has a non-finite value %s (%s)", f->name, p,
                     (long long)d->id[p], mrn_num(d->field[i][k]).s, f->doc);
        break;
      }
  }
}

static void check_positive(mrn_h5r *r, const ck_data *d, const char *name) {
  const double *v = ck_field(d, name);
  for (int64_t p = 0; p < d->n && !r->failed; p++)
    require(r, v[p] > 0, "/particles/%s: particle %lld (id %lld) has %s = %g, expected > 0", name, (long long)p,
            (long long)d->id[p], name, v[p]);
}

/* The current volume is vol0 det F (mrn_particle_volume), so det F must be
 * positive. (Files written while the volume was a field of its own hold it
 * as /particles/vol; it is not read.) */
static void check_det_F(mrn_h5r *r, const ck_data *d) {
  const double *F = ck_field(d, "F");
  for (int64_t p = 0; p < d->n && !r->failed; p++) {
    const double J = mat_det(F + 9 * p);
    require(r, J > 0, "/particles/F: particle %lld (id %lld) has det F = %g, expected > 0 (the volume is vol0 det F)",
            (long long)p, (long long)d->id[p], J);
  }
}

/* A 2D simulation stores only the in-plane block of F and of the affine
 * matrix (mrn_tensor_stride): their z rows and columns in a 2D file must be
 * the plane-strain ones, (0, 0, 1) for F and zero for the affine matrix,
 * which every 2D run writes. */
static void check_plane_tensors(mrn_h5r *r, const ck_data *d) {
  if (d->dim != 2) return;
  static const char *const names[] = {"F", "affine"};
  for (int t = 0; t < 2 && !r->failed; t++) {
    const mrn_particle_field_info *f = mrn_particle_field_find(names[t]);
    const double *v = ck_field(d, names[t]);
    for (int64_t p = 0; p < d->n && !r->failed; p++) {
      const double *a = v + 9 * p;
      require(r, a[2] == 0.0 && a[5] == 0.0 && a[6] == 0.0 && a[7] == 0.0 && a[8] == f->zz,
              "/particles/%s: particle %lld (id %lld) has z components (%g, %g, %g, %g, zz %g) in a 2D file, "
              "expected 0, 0, 0, 0 and zz %g (plane strain)",
              names[t], (long long)p, (long long)d->id[p], a[2], a[5], a[6], a[7], a[8], f->zz);
    }
  }
}

static void check_inside_grid(mrn_h5r *r, const ck_data *d) {
  mrn_grid g = {.dim = d->dim};
  memcpy(g.origin, d->origin, sizeof g.origin);
  memcpy(g.size, d->size, sizeof g.size);
  const double *x = ck_field(d, "x");
  for (int64_t p = 0; p < d->n && !r->failed; p++)
    require(r, mrn_grid_contains(&g, x + 3 * p),
            "/particles/x: particle %lld (id %lld) at (%g, %g, %g) lies outside the grid", (long long)p,
            (long long)d->id[p], x[3 * p], x[3 * p + 1], x[3 * p + 2]);
}

static void check_particles(mrn_h5r *r, const ck_data *d) {
  for (int64_t p = 0; p < d->n && !r->failed; p++)
    require(r, d->material[p] >= 0 && d->material[p] < d->nmaterials,
            "/particles/material: particle %lld (id %lld) has material %d, but the file defines %d material%s",
            (long long)p, (long long)d->id[p], d->material[p], d->nmaterials, d->nmaterials == 1 ? "" : "s");
  check_ids(r, d);
  check_finite(r, d);
  check_positive(r, d, "mass");
  check_positive(r, d, "vol0");
  check_det_F(r, d);
  check_plane_tensors(r, d);
  check_inside_grid(r, d);
}

/* ---- the whole file ------------------------------------------------------------- */

void ck_free(ck_data *d) {
  for (int i = 0; i < d->nmaterials; i++) mrn_material_unref(d->materials[i]);
  if (d->field)
    for (int i = 0; i < mrn_particle_field_count(); i++) free(d->field[i]);
  free(d->field);
  free(d->material);
  free(d->id);
  free(d->state);
  free(d->contact);
  free(d->bodies_held);
  ck_free_walls(d);
  for (int i = 0; i < d->nuser; i++) free(d->user_values[i]);
  memset(d, 0, sizeof *d);
}

/* /sources, when the simulation had sources (files without it: none) */
static void read_sources(mrn_h5r *r, ck_data *d) {
  const char *g = "/sources";
  if (mrn_h5r_exists(r, g) != 1) return;
  int64_t count = 0;
  read_int_in(r, g, "count", 0, 2 * MRN_MAX_SOURCES, &count);
  for (int i = 0; i < count && !r->failed; i++) {
    char path[64];
    snprintf(path, sizeof path, "%s/%d", g, i);
    mrn_source_state *st = &d->sources[i];
    int64_t layers = 0, particles = 0;
    if (mrn_h5r_string(r, path, "name", st->name, sizeof st->name)) return;
    read_finite(r, path, "progress", -HUGE_VAL, &st->progress);
    read_int_in(r, path, "layers", 0, CK_MAX_COUNTER, &layers);
    read_int_in(r, path, "particles", 0, CK_MAX_COUNTER, &particles);
    read_finite(r, path, "mass", 0.0, &st->mass);
    read_finite(r, path, "energy", -HUGE_VAL, &st->energy);
    read_finite(r, path, "work", -HUGE_VAL, &st->work);
    st->layers = (long)layers;
    st->particles = (long)particles;
  }
  if (!r->failed) d->nsources = (int)count;
}

int ck_read(const char *path, ck_data *d) {
  memset(d, 0, sizeof *d);
  /* every byte against the checksums first: HDF5 then parses intact files only */
  if (ck_sum_verify(path, &d->checksums)) return MRN_ERR_IO;
  mrn_h5r r;
  if (mrn_h5r_open(&r, path)) return MRN_ERR_IO;
  read_root(&r, d);
  read_simulation(&r, d);
  read_grid(&r, d);
  read_scheme(&r, d);
  read_boundary(&r, d);
  if (!r.failed) {
    int64_t nodes = 1;
    for (int k = 0; k < d->dim; k++) nodes *= d->ncell[k] + 1 + 2 * MRN_GRID_PAD;
    ck_read_walls(&r, d, nodes);
  }
  read_dt_policy(&r, d);
  read_materials(&r, d);
  read_particles(&r, d);
  read_sources(&r, d);
  if (!r.failed) check_particles(&r, d);
  mrn_h5r_close(&r);
  if (r.failed) {
    ck_free(d);
    return MRN_ERR_IO;
  }
  if (!d->checksums)
    mrn_warning("checkpoint_no_checksums",
                "'%s' has no checksums (format version %d, written by moraine %s): damage to its values cannot be "
                "detected; saving the loaded simulation writes a file with them",
                path, d->version, d->moraine_version[0] ? d->moraine_version : "?");
  return MRN_OK;
}
