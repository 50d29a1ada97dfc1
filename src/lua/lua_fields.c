/* moraine: per-particle values a deck registers, read and set from Lua, and
 * probes of the grid fields:
 *
 *   sim:particle_field{name = "damage", components = 1, init = 0, unit = ""}
 *   sim:value(name, i)            one particle's value (number or table)
 *   sim:set_value(name, i, v)     set it (registered fields only)
 *   sim:set_field(name, values)   every particle: flat table, number or function
 *   sim:probe{field = "velocity", x = .., y = .. [, z = ..]}
 *
 * Whole arrays are read with sim:field(name) and reduced with sim:reduce. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/error.h"
#include "io/particle_fields.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"
#include "solver/dist.h"
#include "solver/point_force.h"
#include "solver/simulation.h"
#include "transfer/probe.h"

/* ---- registering ------------------------------------------------------------ */

static const mrn_spec particle_field_specs[] = {
    {"name", MRN_SPEC_STRING, 1, 0, 0, 0, 0, 0, NULL, "field name (letters, digits, _; at most 31 characters)", NULL},
    {"components", MRN_SPEC_INTEGER, 0, 1, 1, 9, 0, 0, "", "values per particle (default 1)", NULL},
    {"init", MRN_SPEC_NUMBER, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "", "value of every component for every particle, "
                                                                   "present and future (default 0)", NULL},
    {"unit", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "unit written to checkpoints (default none, at most 15 characters)", NULL},
};

static int valid_name(const char *s) {
  if (!*s || strlen(s) >= MRN_USER_FIELD_NAME || (s[0] >= '0' && s[0] <= '9')) return 0;
  for (; *s; s++)
    if (!(*s == '_' || (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9'))) return 0;
  return 1;
}

static int l_sim_particle_field(lua_State *L) {
  mrn_sim *sim = mrn_lua_check_sim(L, 1);
  const char *where = "particle_field{}";
  mrn_lua_check_table(L, 2, where, particle_field_specs, MRN_COUNT(particle_field_specs));
#define GET(kind, key) mrn_lua_get_##kind(L, 2, where, particle_field_specs, MRN_COUNT(particle_field_specs), key)
  const char *name = GET(string, "name");
  int ncomp = (int)GET(integer, "components");
  double init = GET(number, "init");
  const char *unit = GET(string, "unit");
#undef GET
  if (!valid_name(name))
    mrn_lua_error(L, where, "name '%s' must be 1 to %d letters, digits or _, not starting with a digit", name,
                  MRN_USER_FIELD_NAME - 1);
  if (mrn_output_field_find(name) || !strcmp(name, "x") || !strcmp(name, "y") || !strcmp(name, "z"))
    mrn_lua_error(L, where, "name '%s' is a built-in particle field", name);
  if (!strcmp(name, MRN_POINT_FORCE_FIELD))
    mrn_lua_error(L, where, "name '%s' is reserved for the point forces of sim:point_force{}", name);
  if (unit && strlen(unit) >= sizeof sim->particles.user_fields[0].unit)
    mrn_lua_error(L, where, "unit '%s' is longer than %d characters", unit,
                  (int)sizeof sim->particles.user_fields[0].unit - 1);
  if (mrn_particles_add_user_field(&sim->particles, name, ncomp, init, unit) != MRN_OK)
    mrn_lua_engine_error(L, where);
  return 0;
}

/* ---- one particle ------------------------------------------------------------ */

static size_t check_index(lua_State *L, const mrn_sim *sim, int idx, const char *where) {
  lua_Integer i = luaL_checkinteger(L, idx);
  if (i < 1 || (size_t)i > sim->particles.n)
    mrn_lua_error(L, where, "particle index %lld outside 1..%zu", (long long)i, sim->particles.n);
  return (size_t)i - 1;
}

static const mrn_user_field *check_user(lua_State *L, const mrn_sim *sim, const char *name, const char *where) {
  const mrn_user_field *f = mrn_particles_user_field(&sim->particles, name);
  if (f) return f;
  if (mrn_output_field_find(name)) mrn_lua_error(L, where, "'%s' is a built-in field, which a deck cannot set", name);
  const char *names[MRN_USER_FIELDS_MAX + 1];
  for (int k = 0; k < sim->particles.nuser; k++) names[k] = sim->particles.user_fields[k].name;
  names[sim->particles.nuser] = NULL;
  return mrn_lua_error(L, where, "no particle field '%s'%s (register it with sim:particle_field{name = ...})", name,
                       mrn_hint(mrn_suggest_from(names, name)).s),
         NULL;
}

/* sim:value(name, i): a number for one component, else a table */
static int l_sim_value(lua_State *L) {
  mrn_sim *sim = mrn_lua_check_sim(L, 1);
  const char *where = "value()";
  const char *name = luaL_checkstring(L, 2);
  size_t p = check_index(L, sim, 3, where);
  mrn_field_ref f;
  if (!mrn_field_lookup(sim, name, &f)) mrn_lua_check_choice(L, where, "name", name, mrn_output_field_names());
  double v[9];
  if (f.user) {
    memcpy(v, sim->particles.user + p * sim->particles.user_stride + f.user->offset, sizeof(double) * f.ncomp);
  } else { /* a built-in field is computed for all particles */
    void *buf = lua_newuserdatauv(L, sim->particles.n * (size_t)f.ncomp * 8, 0);
    mrn_field_fill(sim, &f, buf);
    for (int k = 0; k < f.ncomp; k++)
      v[k] = f.type == MRN_VTK_FLOAT64 ? ((double *)buf)[p * f.ncomp + k]
             : f.type == MRN_VTK_INT32 ? ((int32_t *)buf)[p * f.ncomp + k]
                                       : (double)((int64_t *)buf)[p * f.ncomp + k];
    lua_pop(L, 1);
    if (f.type != MRN_VTK_FLOAT64) {
      lua_pushinteger(L, (lua_Integer)v[0]);
      return 1;
    }
  }
  if (f.ncomp == 1) {
    lua_pushnumber(L, v[0]);
    return 1;
  }
  lua_createtable(L, f.ncomp, 0);
  for (int k = 0; k < f.ncomp; k++) {
    lua_pushnumber(L, v[k]);
    lua_rawseti(L, -2, k + 1);
  }
  return 1;
}

/* component k of field f takes what particle_field{init} takes */
static void check_component(lua_State *L, const char *where, const mrn_user_field *f, int k, double v) {
  const mrn_spec *init = mrn_spec_find(particle_field_specs, MRN_COUNT(particle_field_specs), "init");
  char name[MRN_USER_FIELD_NAME + 16];
  if (f->ncomp == 1) snprintf(name, sizeof name, "%s", f->name);
  else snprintf(name, sizeof name, "%s[%d]", f->name, k + 1);
  mrn_lua_check_number(L, where, init, name, v);
}

/* the ncomp numbers of field f at idx: a number (one component) or a table of ncomp numbers */
static void read_value(lua_State *L, int idx, const mrn_user_field *f, const char *where, double *v) {
  const int ncomp = f->ncomp;
  if (ncomp == 1 && lua_type(L, idx) == LUA_TNUMBER) {
    v[0] = lua_tonumber(L, idx);
  } else if (!lua_istable(L, idx) || (int)luaL_len(L, idx) != ncomp || !mrn_lua_read_numbers(L, idx, ncomp, v)) {
    mrn_lua_error(L, where, "'%s' takes %s%d number%s, got %s", f->name, ncomp == 1 ? "" : "a table of ", ncomp,
                  ncomp == 1 ? "" : "s", luaL_typename(L, idx));
  }
  for (int k = 0; k < ncomp; k++) check_component(L, where, f, k, v[k]);
}

static int l_sim_set_value(lua_State *L) {
  mrn_sim *sim = mrn_lua_check_sim(L, 1);
  const char *where = "set_value()";
  const mrn_user_field *f = check_user(L, sim, luaL_checkstring(L, 2), where);
  size_t p = check_index(L, sim, 3, where);
  double v[9];
  read_value(L, 4, f, where, v);
  memcpy(sim->particles.user + p * sim->particles.user_stride + f->offset, v, sizeof(double) * f->ncomp);
  return 0;
}

/* ---- every particle ------------------------------------------------------------ */

/* sim:set_field(name, values): values is a number (every component of every
 * particle), a flat table of n * ncomp numbers (as sim:field gives), or a
 * function(x, y, z, i) returning the particle's value. The values are all
 * read and checked before any is stored: a refused call changes nothing. */
static int l_sim_set_field(lua_State *L) {
  mrn_sim *sim = mrn_lua_check_sim(L, 1);
  const char *where = "set_field()";
  const mrn_user_field *f = check_user(L, sim, luaL_checkstring(L, 2), where);
  const size_t n = sim->particles.n, nc = (size_t)f->ncomp;
  double *values = lua_newuserdatauv(L, (n ? n : 1) * nc * sizeof(double), 0); /* freed by the GC, even on error */
  if (lua_type(L, 3) == LUA_TNUMBER) {
    double v = lua_tonumber(L, 3);
    for (size_t k = 0; k < nc; k++) check_component(L, where, f, (int)k, v);
    for (size_t i = 0; i < n * nc; i++) values[i] = v;
  } else if (lua_istable(L, 3)) {
    if ((size_t)luaL_len(L, 3) != n * nc)
      mrn_lua_error(L, where, "'%s' needs %zu values (%zu particles x %zu), the table has %lld", f->name, n * nc, n,
                    nc, (long long)luaL_len(L, 3));
    for (size_t i = 0; i < n * nc; i++) {
      if (lua_geti(L, 3, (lua_Integer)i + 1) != LUA_TNUMBER)
        mrn_lua_error(L, where, "value %zu is %s, expected a number", i + 1, luaL_typename(L, -1));
      values[i] = lua_tonumber(L, -1);
      check_component(L, where, f, (int)(i % nc), values[i]);
      lua_pop(L, 1);
    }
  } else if (lua_isfunction(L, 3)) {
    for (size_t p = 0; p < n; p++) {
      lua_pushvalue(L, 3);
      for (int d = 0; d < 3; d++) lua_pushnumber(L, sim->particles.x[3 * p + d]);
      lua_pushinteger(L, (lua_Integer)p + 1);
      lua_call(L, 4, (int)nc);
      double *v = values + p * nc;
      if (nc == 1 && lua_type(L, -1) == LUA_TNUMBER) v[0] = lua_tonumber(L, -1);
      else if (lua_istable(L, -1)) read_value(L, -1, f, where, v);
      else if (!mrn_lua_read_numbers(L, -(int)nc, (int)nc, v))
        mrn_lua_error(L, where, "the function gave no %zu number%s for particle %zu", nc, nc == 1 ? "" : "s", p + 1);
      for (size_t k = 0; k < nc; k++) check_component(L, where, f, (int)k, v[k]);
      lua_pop(L, (int)nc);
    }
    /* the function may have freed the simulation or changed its particles */
    sim = mrn_lua_check_sim(L, 1);
    if (sim->particles.n != n)
      mrn_lua_error(L, where, "the particles changed (%zu, now %zu) while the function ran", n, sim->particles.n);
  } else {
    mrn_lua_error(L, where, "values must be a number, a table of %zu numbers or a function(x, y, z, i), got %s",
                  n * nc, luaL_typename(L, 3));
  }
  const mrn_particles *ps = &sim->particles;
  for (size_t p = 0; p < n; p++) memcpy(ps->user + p * ps->user_stride + f->offset, values + p * nc, sizeof(double) * nc);
  return 0;
}

/* ---- probes ---------------------------------------------------------------------- */

static const char *const grid_field_names[] = {"mass", "momentum", "velocity", "velocity_new", "force",
                                               "acceleration", NULL};
static const mrn_spec probe_specs[] = {
    {"field", MRN_SPEC_STRING, 1, 0, 0, 0, 0, 0, NULL, "nodal field of the last step", grid_field_names},
    {"x", MRN_SPEC_NUMBER, 1, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "point x", NULL},
    {"y", MRN_SPEC_NUMBER, 1, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "point y", NULL},
    {"z", MRN_SPEC_NUMBER, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "point z (3D only)", NULL},
};

/* sim:probe{field, x, y [, z]}: the nodal field interpolated at the point,
 * a number (mass) or a table of dim components; nil outside the grid */
static int l_sim_probe(lua_State *L) {
  mrn_sim *sim = mrn_lua_check_sim(L, 1);
  const char *where = "probe{}";
  mrn_lua_check_table(L, 2, where, probe_specs, MRN_COUNT(probe_specs));
#define GET(kind, key) mrn_lua_get_##kind(L, 2, where, probe_specs, MRN_COUNT(probe_specs), key)
  const char *field = GET(string, "field");
  double x[3] = {GET(number, "x"), GET(number, "y"), 0.0};
  if (mrn_lua_has(L, 2, "z")) {
    if (sim->dim != 3) mrn_lua_error(L, where, "z is only for a 3D simulation");
    x[2] = GET(number, "z");
  } else if (sim->dim == 3) {
    mrn_lua_error(L, where, "z is required in 3D");
  }
#undef GET
  const mrn_grid *g = &sim->grid;
  const double *arrays[] = {g->mass, g->mom, g->vel, g->vel_new, g->force, g->vel_new};
  int which = 0;
  while (strcmp(grid_field_names[which], field) != 0) which++;
  const int ncomp = which == 0 ? 1 : 3;
  double v[3], before[3];
  const mrn_transfer tr = mrn_sim_transfer(sim);
  if (mrn_probe_grid(&tr, arrays[which], ncomp, x, v) != 0) {
    lua_pushnil(L);
    return 1;
  }
  if (strcmp(field, "acceleration") == 0) {
    /* not stored: (V~ - V) / dt of the last step, interpolated */
    mrn_probe_grid(&tr, g->vel, ncomp, x, before);
    for (int d = 0; d < 3; d++) v[d] = sim->dt > 0.0 ? (v[d] - before[d]) / sim->dt : 0.0;
  }
  /* in a distributed run the process whose slab holds the point answers for all */
  if (sim->dist) {
    if (!mrn_dist_owns_point(sim, x))
      for (int d = 0; d < ncomp; d++) v[d] = 0.0;
    mrn_dist_reduce(sim, v, ncomp, MRN_COMM_SUM);
  }
  if (ncomp == 1) {
    lua_pushnumber(L, v[0]);
    return 1;
  }
  lua_createtable(L, sim->dim, 0);
  for (int d = 0; d < sim->dim; d++) {
    lua_pushnumber(L, v[d]);
    lua_rawseti(L, -2, d + 1);
  }
  return 1;
}

void mrn_lua_add_field_methods(lua_State *L, int methods) {
  /* sim:NAME is l_sim_NAME, as in lua_sim.c */
  static const luaL_Reg fns[] = {
      {"particle_field", l_sim_particle_field},
      {"value", l_sim_value},
      {"set_value", l_sim_set_value},
      {"set_field", l_sim_set_field},
      {"probe", l_sim_probe},
      {NULL, NULL},
  };
  lua_pushvalue(L, methods);
  luaL_setfuncs(L, fns, 0);
  lua_pop(L, 1);
  mrn_spec_register_group("particle_field{}", particle_field_specs, MRN_COUNT(particle_field_specs));
  mrn_spec_register_group("probe{}", probe_specs, MRN_COUNT(probe_specs));
}
