/* moraine: the methods that change a simulation between runs — gravity,
 * boundary, scheme, dt, damping, outputs — and the velocity constraints. */
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"
#include "lua/lua_safe.h"
#include "solver/dist.h"
#include "solver/split.h"

/* the checks of simulation{gravity}, on the value given alone */
int l_sim_set_gravity(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const mrn_spec_group *opts = &mrn_lua_simulation_group;
  double g[3] = {0, 0, 0};
  mrn_lua_to_vector(L, 2, "set_gravity()", mrn_spec_find(opts->specs, opts->count, "gravity"), b->sim->dim, g);
  memcpy(b->sim->gravity, g, sizeof g);
  return 0;
}

int l_sim_set_boundary(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  mrn_lua_read_boundary(L, 2, "set_boundary()", b->sim);
  return 0;
}

int l_sim_set_scheme(lua_State *L) {
  sim_box *b = mrn_lua_sim_check_idle(L, 1, "set_scheme()");
  mrn_lua_read_scheme(L, 2, "set_scheme()", b->sim);
  return 0;
}

int l_sim_set_dt(lua_State *L) {
  sim_box *b = mrn_lua_sim_check_idle(L, 1, "set_dt()");
  mrn_lua_read_dt(L, 2, "set_dt()", b->sim);
  return 0;
}

int l_sim_set_damping(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  mrn_lua_read_damping(L, 2, "set_damping()", b->sim);
  return 0;
}

int l_sim_set_split(lua_State *L) {
  sim_box *b = mrn_lua_sim_check_idle(L, 1, "set_split()");
  mrn_lua_read_split(L, 2, "set_split()", b->sim);
  return 0;
}

/* sim:split() -> the number of particles split now (those due by the splitting's settings) */
int l_sim_split(lua_State *L) {
  sim_box *b = mrn_lua_sim_check_idle(L, 1, "split()");
  mrn_lua_active = L;
  const long made = mrn_sim_split(b->sim);
  if (made < 0) mrn_lua_engine_error(L, "split()");
  lua_pushinteger(L, made);
  return 1;
}

int l_sim_output(lua_State *L) {
  sim_box *b = mrn_lua_sim_check_idle(L, 1, "output()");
  mrn_lua_read_output(L, 2, "output()", b);
  mrn_lua_check_outputs(L, "output()", &b->out, b->name);
  return 0;
}

/* ------------------------------------------------------- constraints */

static const mrn_spec constrain_specs[] = {
    {"region", MRN_SPEC_ANY, 1, 0, 0, 0, 0, 0, NULL, "the grid nodes inside this region are constrained", NULL},
    {"vx", MRN_SPEC_NUMBER, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s", "prescribed x velocity (absent: free)", NULL},
    {"vy", MRN_SPEC_NUMBER, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s", "prescribed y velocity (absent: free)", NULL},
    {"vz", MRN_SPEC_NUMBER, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s", "prescribed z velocity, 3D (absent: free)", NULL},
};

/* reads vx, vy, vz into v and mask; returns the number given */
static int read_components(lua_State *L, int idx, const char *where, int dim, double v[3], unsigned *mask) {
  static const char *keys[] = {"vx", "vy", "vz"};
  int given = 0;
  for (int d = 0; d < 3; d++) {
    if (!mrn_lua_has(L, idx, keys[d])) continue;
    if (d >= dim) mrn_lua_error(L, where, "%s is not a component in %dD", keys[d], dim);
    v[d] = mrn_lua_get_number(L, idx, where, constrain_specs, MRN_COUNT(constrain_specs), keys[d]);
    *mask |= 1u << d;
    given++;
  }
  return given;
}

/* sim:constrain{region = r, vx = ..., vy = ...} -> index */
int l_sim_constrain(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *where = "constrain{}";
  mrn_lua_check_table(L, 2, where, constrain_specs, MRN_COUNT(constrain_specs));
  lua_getfield(L, 2, "region");
  mrn_region *region = mrn_lua_check_region(L, -1, where);
  lua_pop(L, 1);
  double v[3] = {0, 0, 0};
  unsigned mask = 0;
  if (!read_components(L, 2, where, b->sim->dim, v, &mask)) mrn_lua_error(L, where, "give at least one of vx, vy, vz");
  mrn_lua_active = L;
  int i = mrn_sim_add_constraint(b->sim, region, mask, v);
  if (i < 0) mrn_lua_engine_error(L, where);
  lua_pushinteger(L, i + 1);
  return 1;
}

static mrn_constraint *check_constraint(lua_State *L, sim_box *b, int idx, const char *where) {
  lua_Integer i = luaL_checkinteger(L, idx);
  if (i < 1 || i > b->sim->nconstraints)
    mrn_lua_error(L, where, "no constraint %d (the simulation has %d)", (int)i, b->sim->nconstraints);
  return &b->sim->constraints[i - 1];
}

/* sim:reaction(i) -> force the constraint exerted on the material in the
 * last step (summed over the processes of a distributed run: collective) */
int l_sim_reaction(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  mrn_constraint *c = check_constraint(L, b, 2, "reaction()");
  double r[3];
  memcpy(r, c->reaction, sizeof r);
  mrn_dist_reduce(b->sim, r, 3, MRN_COMM_SUM);
  mrn_lua_push_vector(L, r, b->sim->dim);
  return 1;
}

/* sim:set_constraint(i, {vx = ..., ...}): new prescribed values for the components given */
int l_sim_set_constraint(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *where = "set_constraint()";
  mrn_constraint *c = check_constraint(L, b, 2, where);
  mrn_lua_check_table(L, 3, where, constrain_specs + 1, MRN_COUNT(constrain_specs) - 1);
  double v[3] = {c->velocity[0], c->velocity[1], c->velocity[2]};
  unsigned mask = c->mask;
  read_components(L, 3, where, b->sim->dim, v, &mask);
  memcpy(c->velocity, v, sizeof v);
  c->mask = mask;
  return 0;
}

const mrn_spec_group mrn_lua_constrain_group = {"constrain{}", constrain_specs, MRN_COUNT(constrain_specs)};
