/* moraine: sim:reduce(op, field [, options]): one number from a particle
 * quantity over all particles, a material, a region or a predicate. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/error.h"
#include "io/particle_fields.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"

static const char *const reduce_ops[] = {"min", "max", "sum", "mean", "count", NULL};
static const mrn_spec reduce_specs[] = {
    {"component", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "component index from 1, or \"norm\" (default: 1, or the norm for vectors)", NULL},
    {"material", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "only particles of this material", NULL},
    {"region", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "only particles inside this region", NULL},
    {"where", MRN_SPEC_FUNCTION, 0, 0, 0, 0, 0, 0, NULL, "only particles for which where(x, y, z) is true", NULL},
};

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
  const mrn_particles *ps = &b->sim->particles;
  const size_t n = ps->n;
  /* the values: positions directly, or a field computed into a buffer */
  int ncomp = 1, axis = -1;
  const double *data = NULL;
  if (!strcmp(field, "x") || !strcmp(field, "y") || !strcmp(field, "z")) {
    axis = field[0] - 'x';
    if (axis >= b->sim->dim) mrn_lua_error(L, where, "field '%s' does not exist in %dD", field, b->sim->dim);
    data = ps->x;
    ncomp = 3;
  } else {
    static const char *const extra[] = {"x", "y", "z", NULL};
    mrn_field_ref f;
    if (!mrn_field_lookup(b->sim, field, &f)) {
      const char *hint = mrn_suggest_from(mrn_output_field_names(), field);
      if (!hint) hint = mrn_suggest_from(extra, field);
      mrn_lua_error(L, where, "unknown field '%s'%s (fields: x, y, z and those of sim:field)", field, mrn_hint(hint).s);
    }
    ncomp = f.ncomp;
    double *buf = lua_newuserdatauv(L, (n ? n : 1) * ncomp * sizeof(double), 0);
    if (f.type == MRN_VTK_FLOAT64) {
      mrn_field_fill(b->sim, &f, buf);
    } else { /* integer fields, widened */
      int64_t *tmp = lua_newuserdatauv(L, (n ? n : 1) * sizeof(int64_t), 0);
      mrn_field_fill(b->sim, &f, tmp);
      for (size_t i = 0; i < n; i++) buf[i] = f.type == MRN_VTK_INT32 ? ((int32_t *)tmp)[i] : (double)tmp[i];
      lua_pop(L, 1);
    }
    data = buf;
  }
  int use_norm = 0, comp = 0;
  if (axis >= 0) {
    comp = axis;
  } else {
    use_norm = ncomp == 3; /* vectors: their length unless a component is asked for */
    if (has_opts && mrn_lua_has(L, 4, "component")) {
      lua_getfield(L, 4, "component");
      if (lua_type(L, -1) == LUA_TSTRING && !strcmp(lua_tostring(L, -1), "norm")) {
        use_norm = 1;
      } else if (lua_isinteger(L, -1) && lua_tointeger(L, -1) >= 1 && lua_tointeger(L, -1) <= ncomp) {
        use_norm = 0;
        comp = (int)lua_tointeger(L, -1) - 1;
      } else {
        mrn_lua_error(L, where, "component must be 1..%d or \"norm\" for '%s'", ncomp, field);
      }
      lua_pop(L, 1);
    }
  }
  int mat = -1;
  mrn_region *region = NULL;
  int pred = 0;
  if (has_opts) {
    if (mrn_lua_has(L, 4, "material")) {
      lua_getfield(L, 4, "material");
      mrn_material *m = mrn_lua_check_material(L, -1, where);
      lua_pop(L, 1);
      for (int i = 0; i < b->sim->nmaterials; i++)
        if (b->sim->materials[i] == m) mat = i;
      if (mat < 0) mat = MRN_MAX_MATERIALS; /* a material no particle has */
    }
    if (mrn_lua_has(L, 4, "region")) {
      lua_getfield(L, 4, "region");
      region = mrn_lua_check_region(L, -1, where);
      lua_pop(L, 1);
    }
    if (mrn_lua_has(L, 4, "where")) {
      lua_getfield(L, 4, "where");
      pred = lua_gettop(L);
    }
  }
  double lo = HUGE_VAL, hi = -HUGE_VAL, sum = 0.0;
  long count = 0;
  mrn_lua_active = L;
  for (size_t p = 0; p < n; p++) {
    if (mat >= 0 && ps->material[p] != mat) continue;
    const double *x = ps->x + 3 * p;
    if (region) {
      int in = mrn_region_contains(region, x);
      if (in < 0) mrn_lua_engine_error(L, where);
      if (!in) continue;
    }
    if (pred) {
      lua_pushvalue(L, pred);
      for (int d = 0; d < 3; d++) lua_pushnumber(L, x[d]);
      lua_call(L, 3, 1);
      int keep = lua_toboolean(L, -1);
      lua_pop(L, 1);
      if (!keep) continue;
    }
    const double *row = data + (size_t)ncomp * p;
    double v = use_norm ? sqrt(row[0] * row[0] + row[1] * row[1] + row[2] * row[2]) : row[comp];
    lo = fmin(lo, v);
    hi = fmax(hi, v);
    sum += v;
    count++;
  }
  if (!strcmp(op, "count")) lua_pushinteger(L, count);
  else if (count == 0) lua_pushnil(L); /* min, max, mean of nothing */
  else if (!strcmp(op, "min")) lua_pushnumber(L, lo);
  else if (!strcmp(op, "max")) lua_pushnumber(L, hi);
  else if (!strcmp(op, "sum")) lua_pushnumber(L, sum);
  else lua_pushnumber(L, sum / count);
  return 1;
}

const mrn_spec_group mrn_lua_reduce_group = {"reduce()", reduce_specs, MRN_COUNT(reduce_specs)};
