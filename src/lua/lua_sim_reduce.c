/* moraine: sim:reduce(op, field [, options]): one number from a particle
 * quantity over all particles, a material, a region or a predicate. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/error.h"
#include "io/particle_fields.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"
#include "solver/dist.h"

static const char *const reduce_ops[] = {"min", "max", "sum", "mean", "count", NULL};
static const mrn_spec reduce_specs[] = {
    {"component", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "component index from 1, or \"norm\" (default: 1, or the norm for vectors)", NULL},
    {"material", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "only particles of this material", NULL},
    {"region", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "only particles inside this region", NULL},
    {"where", MRN_SPEC_FUNCTION, 0, 0, 0, 0, 0, 0, NULL, "only particles for which where(x, y, z) is true", NULL},
};

/* the quantity reduced: row p of data (ncomp numbers) belongs to particle p */
typedef struct reduce_values {
  const double *data;
  int ncomp;
  int comp;     /* the component reduced, from 0 ... */
  int use_norm; /* ... or the length of a vector of 3 */
} reduce_values;

/* the particles that count */
typedef struct reduce_filter {
  int material;       /* index of the material, -1: any */
  mrn_region *region; /* NULL: anywhere */
  int where;          /* stack index of the function where(x, y, z), 0: none */
} reduce_filter;

/* The values of `field`: the positions directly for x, y and z, else the
 * field computed into a buffer left on the stack (alive until the method
 * returns). Sets v->data and v->ncomp; v->comp for x, y and z. */
static void read_values(lua_State *L, sim_box *b, const char *field, const char *where, reduce_values *v) {
  const size_t n = b->sim->particles.n;
  v->ncomp = 1;
  v->comp = -1;
  if (!strcmp(field, "x") || !strcmp(field, "y") || !strcmp(field, "z")) {
    v->comp = field[0] - 'x';
    if (v->comp >= b->sim->dim) mrn_lua_error(L, where, "field '%s' does not exist in %dD", field, b->sim->dim);
    v->data = b->sim->particles.x;
    v->ncomp = 3;
    return;
  }
  static const char *const extra[] = {"x", "y", "z", NULL};
  mrn_field_ref f;
  if (!mrn_field_lookup(b->sim, field, &f)) {
    const char *hint = mrn_suggest_from(mrn_output_field_names(), field);
    if (!hint) hint = mrn_suggest_from(extra, field);
    mrn_lua_error(L, where, "unknown field '%s'%s (fields: x, y, z and those of sim:field)", field, mrn_hint(hint).s);
  }
  v->ncomp = f.ncomp;
  double *buf = lua_newuserdatauv(L, (n ? n : 1) * v->ncomp * sizeof(double), 0);
  if (f.type == MRN_VTK_FLOAT64) {
    mrn_field_fill(b->sim, &f, buf);
  } else { /* integer fields, widened */
    int64_t *tmp = lua_newuserdatauv(L, (n ? n : 1) * sizeof(int64_t), 0);
    mrn_field_fill(b->sim, &f, tmp);
    for (size_t i = 0; i < n; i++) buf[i] = f.type == MRN_VTK_INT32 ? ((int32_t *)tmp)[i] : (double)tmp[i];
    lua_pop(L, 1);
  }
  v->data = buf;
}

/* component = k | "norm" of the options at 4; x, y and z have theirs */
static void read_component(lua_State *L, int has_opts, const char *field, const char *where, reduce_values *v) {
  if (v->comp >= 0) return;
  v->comp = 0;
  v->use_norm = v->ncomp == 3; /* vectors: their length unless a component is asked for */
  if (!has_opts || !mrn_lua_has(L, 4, "component")) return;
  lua_getfield(L, 4, "component");
  if (lua_type(L, -1) == LUA_TSTRING && !strcmp(lua_tostring(L, -1), "norm")) {
    v->use_norm = 1;
  } else if (lua_isinteger(L, -1) && lua_tointeger(L, -1) >= 1 && lua_tointeger(L, -1) <= v->ncomp) {
    v->use_norm = 0;
    v->comp = (int)lua_tointeger(L, -1) - 1;
  } else {
    mrn_lua_error(L, where, "component must be 1..%d or \"norm\" for '%s'", v->ncomp, field);
  }
  lua_pop(L, 1);
}

/* material, region and where of the options at 4; the function where is left on the stack */
static void read_filter(lua_State *L, const mrn_sim *sim, int has_opts, const char *where, reduce_filter *f) {
  f->material = -1;
  f->region = NULL;
  f->where = 0;
  if (!has_opts) return;
  if (mrn_lua_has(L, 4, "material")) {
    lua_getfield(L, 4, "material");
    mrn_material *m = mrn_lua_check_material(L, -1, where);
    lua_pop(L, 1);
    for (int i = 0; i < sim->nmaterials; i++)
      if (sim->materials[i] == m) f->material = i;
    if (f->material < 0) f->material = MRN_MAX_MATERIALS; /* a material no particle has */
  }
  if (mrn_lua_has(L, 4, "region")) {
    lua_getfield(L, 4, "region");
    f->region = mrn_lua_check_region(L, -1, where);
    lua_pop(L, 1);
  }
  if (mrn_lua_has(L, 4, "where")) {
    lua_getfield(L, 4, "where");
    f->where = lua_gettop(L);
  }
}

/* whether particle p counts; region and where functions may raise */
static int keep_particle(lua_State *L, const mrn_particles *ps, size_t p, const reduce_filter *f, const char *where) {
  if (f->material >= 0 && ps->material[p] != f->material) return 0;
  const double *x = ps->x + 3 * p;
  if (f->region) {
    int in = mrn_region_contains(f->region, x);
    if (in < 0) mrn_lua_engine_error(L, where);
    if (!in) return 0;
  }
  if (f->where) {
    lua_pushvalue(L, f->where);
    for (int d = 0; d < 3; d++) lua_pushnumber(L, x[d]);
    lua_call(L, 3, 1);
    int keep = lua_toboolean(L, -1);
    lua_pop(L, 1);
    if (!keep) return 0;
  }
  return 1;
}

/* sim:reduce(op, field [, options]): min, max, sum, mean or count of a
 * particle quantity over all particles, a material, a region or a predicate.
 * field: a particle field name, or x / y / z for the positions. */
int l_sim_reduce(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *where = "reduce()";
  const char *op = luaL_checkstring(L, 2);
  mrn_lua_check_choice(L, where, "op", op, reduce_ops);
  const char *field = luaL_checkstring(L, 3);
  int has_opts = !lua_isnoneornil(L, 4);
  if (has_opts) mrn_lua_check_table(L, 4, where, reduce_specs, MRN_COUNT(reduce_specs));
  reduce_values v = {0};
  read_values(L, b, field, where, &v);
  read_component(L, has_opts, field, where, &v);
  reduce_filter f;
  read_filter(L, b->sim, has_opts, where, &f);
  const mrn_particles *ps = &b->sim->particles;
  double lo = HUGE_VAL, hi = -HUGE_VAL, sum = 0.0;
  long count = 0;
  mrn_lua_active = L;
  for (size_t p = 0; p < ps->n; p++) {
    if (!keep_particle(L, ps, p, &f, where)) continue;
    const double *row = v.data + (size_t)v.ncomp * p;
    double value = v.use_norm ? sqrt(row[0] * row[0] + row[1] * row[1] + row[2] * row[2]) : row[v.comp];
    lo = fmin(lo, value);
    hi = fmax(hi, value);
    sum += value;
    count++;
  }
  /* over every process of a distributed run (solver/dist.h; collective there) */
  double total[2] = {sum, (double)count};
  mrn_dist_reduce(b->sim, &lo, 1, MRN_COMM_MIN);
  mrn_dist_reduce(b->sim, &hi, 1, MRN_COMM_MAX);
  mrn_dist_reduce(b->sim, total, 2, MRN_COMM_SUM);
  sum = total[0];
  count = (long)total[1];
  if (!strcmp(op, "count")) lua_pushinteger(L, count);
  else if (count == 0) lua_pushnil(L); /* min, max, mean of nothing */
  else if (!strcmp(op, "min")) lua_pushnumber(L, lo);
  else if (!strcmp(op, "max")) lua_pushnumber(L, hi);
  else if (!strcmp(op, "sum")) lua_pushnumber(L, sum);
  else lua_pushnumber(L, sum / count);
  return 1;
}

const mrn_spec_group mrn_lua_reduce_group = {"reduce()", reduce_specs, MRN_COUNT(reduce_specs)};
