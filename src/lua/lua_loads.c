/* moraine: point forces on material points, from Lua.
 *
 *   sim:point_force{ region = R, force = {fx, fy[, fz]} }   -- or traction = {...}
 *   sim:load_factor(f)      -- every point force times f from the next step
 *   sim:clear_forces()
 *
 * The selection (which points, how a total force or a traction is shared
 * among them) is one function, mrn_lua_point_force_args, that the explicit
 * simulation and the implicit integrator (imp:point_force) both use. */
#include <math.h>

#include "core/error.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"
#include "solver/dist.h"
#include "solver/point_force.h"
#include "solver/simulation.h"

static const mrn_spec force_specs[] = {
    {"region", MRN_SPEC_ANY, 1, 0, 0, 0, 0, 0, NULL, "the material points loaded (those inside at the call)", NULL},
    {"force", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "N", "total point force, split equally (N/m in 2D)", NULL},
    {"traction", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "Pa",
     "traction: each point gets traction times its face V0^((dim-1)/dim)", NULL},
};

long mrn_lua_point_force_args(lua_State *L, int idx, const mrn_sim *sim, const char *where,
                              int (*set)(void *ctx, size_t p, const double f[3]), void *ctx) {
  mrn_lua_check_table(L, idx, where, force_specs, MRN_COUNT(force_specs));
  lua_getfield(L, idx, "region");
  mrn_region *r = mrn_lua_check_region(L, -1, where);
  lua_pop(L, 1);
  double f[3] = {0, 0, 0};
  const int n = MRN_COUNT(force_specs);
  int has_force = mrn_lua_get_vector(L, idx, where, force_specs, n, "force", sim->dim, f, 0);
  int has_traction = mrn_lua_get_vector(L, idx, where, force_specs, n, "traction", sim->dim, f, 0);
  if (has_force == has_traction) mrn_lua_error(L, where, "give exactly one of force and traction");
  const mrn_particles *ps = &sim->particles;
  double count = 0.0; /* over every process of a distributed run (collective there) */
  for (size_t p = 0; p < ps->n; p++) count += mrn_region_contains(r, ps->x + 3 * p) == 1;
  mrn_dist_reduce(sim, &count, 1, MRN_COMM_SUM);
  if (count == 0.0) mrn_lua_error(L, where, "region: holds no material point");
  for (size_t p = 0; p < ps->n; p++) {
    if (mrn_region_contains(r, ps->x + 3 * p) != 1) continue;
    double fp[3];
    double scale = has_force ? 1.0 / count : pow(ps->vol0[p], (sim->dim - 1.0) / sim->dim);
    for (int d = 0; d < 3; d++) fp[d] = f[d] * scale;
    if (set(ctx, p, fp)) mrn_lua_engine_error(L, where);
  }
  return (long)count;
}

static int set_explicit(void *ctx, size_t p, const double f[3]) { return mrn_sim_set_point_force(ctx, p, f); }

static int l_sim_point_force(lua_State *L) {
  mrn_sim *sim = mrn_lua_check_sim(L, 1);
  if (mrn_sim_add_point_forces(sim) != MRN_OK) mrn_lua_engine_error(L, "point_force{}");
  lua_pushinteger(L, mrn_lua_point_force_args(L, 2, sim, "point_force{}", set_explicit, sim));
  return 1;
}

/* any finite factor: a negative one reverses the loads */
static const mrn_spec factor_spec = {"factor", MRN_SPEC_NUMBER, 1, 1, -HUGE_VAL, HUGE_VAL, 0, 0, "",
                                     "multiplies every point force from the next step", NULL};

double mrn_lua_check_load_factor(lua_State *L, int idx) {
  double f = luaL_checknumber(L, idx);
  mrn_lua_check_number(L, "load_factor()", &factor_spec, NULL, f);
  return f;
}

static int l_sim_load_factor(lua_State *L) {
  mrn_sim *sim = mrn_lua_check_sim(L, 1);
  mrn_sim_set_load_factor(sim, mrn_lua_check_load_factor(L, 2));
  return 0;
}

static int l_sim_clear_forces(lua_State *L) {
  mrn_sim_clear_point_forces(mrn_lua_check_sim(L, 1));
  return 0;
}

void mrn_lua_add_load_methods(lua_State *L, int methods) {
  /* sim:NAME is l_sim_NAME, as in lua_sim.c */
  static const luaL_Reg fns[] = {
      {"point_force", l_sim_point_force},
      {"load_factor", l_sim_load_factor},
      {"clear_forces", l_sim_clear_forces},
      {NULL, NULL},
  };
  lua_pushvalue(L, methods);
  luaL_setfuncs(L, fns, 0);
  lua_pop(L, 1);
  mrn_spec_register_group("point_force{}", force_specs, MRN_COUNT(force_specs));
}
