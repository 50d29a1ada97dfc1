/* moraine: the implicit integrator of a deck (src/implicit, paper 001).
 *
 *   local imp = sim:implicit{ mass = "consistent", mapping = "FLIP", tol = 1e-11, dt_factor = 5 }
 *   imp:point_force{ region = mpm.box{...}, force = { 0, -5e5 } }
 *   imp:load_factor(t / 25)   -- scales every point force from the next step
 *   local h = imp:step()      -- { dt, iterations, errors = {...}, residual, cuts, rejected_iterations }
 *   local e = imp:energy()    -- { kinetic, strain, dissipated, external_work, ghost, total, momentum, angular }
 * Once made, the integrator also drives sim:run (implicit_run.c) until it is
 * freed; every option is checked against the specs below (listed by
 * `moraine --list-options`). */
#include <lauxlib.h>
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "implicit/implicit.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"

#define MRN_LUA_IMPLICIT "moraine.implicit"

static const char *const mass_choices[] = {"consistent", "lumped", "effective", NULL};
static const char *const mapping_choices[] = {"FLIP", "PIC", NULL};

static const mrn_spec implicit_specs[] = {
    {"mass", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "mass matrix: consistent (default), lumped, or effective (1 - eps) M + eps M_lumped (001 Eq. 18)", mass_choices},
    {"eps", MRN_SPEC_NUMBER, 0, 0.5, 0, 1, 0, 0, "", "lumped weight of the effective mass matrix (mass = \"effective\")",
     NULL},
    {"mapping", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "grid-to-point velocity mapping: FLIP (default) or PIC (001 Eqs. 28-29)",
     mapping_choices},
    {"tol", MRN_SPEC_NUMBER, 0, 1e-11, 0, 1, 1, 0, "", "Newton tolerance on f_err^(k) / f_err^(1) (001 §3.4)", NULL},
    {"max_iter", MRN_SPEC_INTEGER, 0, 20, 2, MRN_IMPLICIT_MAX_ITER, 0, 0, "", "Newton iterations before a step fails", NULL},
    {"cutbacks", MRN_SPEC_INTEGER, 0, 0, 0, MRN_IMPLICIT_MAX_CUTBACKS, 0, 0, "",
     "times a step not converged in max_iter iterations is tried again with half the time step (0: the run stops)",
     NULL},
    {"dt", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "fixed time step (default: adaptive, see dt_factor)", NULL},
    {"dt_factor", MRN_SPEC_NUMBER, 0, 5, 0, HUGE_VAL, 1, 0, "",
     "adaptive step: this factor times the grid-averaged CFL estimate of 001 Eq. 61", NULL},
    {"min_node_mass", MRN_SPEC_NUMBER, 0, 1e-3, 0, 1, 0, 1, "",
     "nodes lighter than this times the heaviest point are left out (MLS functions on the rest)", NULL},
    {"ghost", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 1, "",
     "ghost penalty factor gamma, times the largest Young's modulus, on the normal-gradient jumps at cut cells "
     "(0: off; linear and gimp shapes)",
     NULL},
    {"bbar", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL,
     "average the divergence of each point's step increment over the points of its cell, against volumetric "
     "locking (default false)",
     NULL},
};

typedef struct implicit_box {
  mrn_implicit *im;
} implicit_box;

static mrn_implicit *check_implicit(lua_State *L, int idx) {
  implicit_box *b = luaL_checkudata(L, idx, MRN_LUA_IMPLICIT);
  if (!b->im) luaL_error(L, "implicit integrator has been freed");
  /* the simulation (kept as user value) must still be alive */
  lua_getiuservalue(L, idx, 1);
  mrn_lua_check_sim(L, -1);
  lua_pop(L, 1);
  return b->im;
}

/* The simulation keeps its integrator object alive (a deck need not hold on
 * to it) in the registry table INTEGRATORS[sim] = imp, and the options of an
 * integrator = "implicit" simulation, until its first run, in
 * PENDING[sim] = options. Both have weak keys, so the pair goes with the
 * simulation. */
static const char *const INTEGRATORS = "moraine.integrators";
static const char *const PENDING = "moraine.pending_integrators";


/* table[key at key_idx] = value on top of the stack (popped) */
static void set_weak(lua_State *L, const char *name, int key_idx) {
  key_idx = lua_absindex(L, key_idx);
  mrn_lua_push_weak_table(L, name);
  lua_pushvalue(L, key_idx);
  lua_pushvalue(L, -3);
  lua_rawset(L, -3);
  lua_pop(L, 2);
}

/* pushes table[key at key_idx] (nil when absent) */
static int get_weak(lua_State *L, const char *name, int key_idx) {
  key_idx = lua_absindex(L, key_idx);
  mrn_lua_push_weak_table(L, name);
  lua_pushvalue(L, key_idx);
  int type = lua_rawget(L, -2);
  lua_remove(L, -2);
  return type;
}

static int l_implicit_free(lua_State *L) {
  implicit_box *b = luaL_checkudata(L, 1, MRN_LUA_IMPLICIT);
  if (!b->im) return 0;
  mrn_implicit_free(b->im);
  b->im = NULL;
  /* imp:free(): the simulation forgets it and steps explicitly again */
  if (lua_getiuservalue(L, 1, 1) == LUA_TUSERDATA) {
    if (get_weak(L, INTEGRATORS, -1) == LUA_TUSERDATA && lua_rawequal(L, -1, 1)) {
      lua_pushnil(L);
      set_weak(L, INTEGRATORS, -3);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return 0;
}

/* the options table at idx (checked against implicit_specs) */
static void read_options(lua_State *L, int idx, const char *where, mrn_implicit_options *o) {
  const int n = MRN_COUNT(implicit_specs);
  mrn_lua_check_table(L, idx, where, implicit_specs, n);
  mrn_implicit_options_default(o);
  const char *mass = mrn_lua_get_string(L, idx, where, implicit_specs, n, "mass");
  if (mass) o->mass = !strcmp(mass, "lumped") ? MRN_MASS_LUMPED : !strcmp(mass, "effective") ? MRN_MASS_EFFECTIVE
                                                                                             : MRN_MASS_CONSISTENT;
  if (mrn_lua_has(L, idx, "eps")) {
    if (o->mass != MRN_MASS_EFFECTIVE) mrn_lua_error(L, where, "eps: only used with mass = \"effective\"");
  }
  o->eps = mrn_lua_get_number(L, idx, where, implicit_specs, n, "eps");
  const char *map = mrn_lua_get_string(L, idx, where, implicit_specs, n, "mapping");
  if (map && !strcmp(map, "PIC")) o->mapping = MRN_MAPPING_PIC;
  o->tol = mrn_lua_get_number(L, idx, where, implicit_specs, n, "tol");
  o->max_iter = (int)mrn_lua_get_integer(L, idx, where, implicit_specs, n, "max_iter");
  if (mrn_lua_has(L, idx, "dt") && mrn_lua_has(L, idx, "dt_factor"))
    mrn_lua_error(L, where, "give either dt (fixed step) or dt_factor (adaptive), not both");
  if (mrn_lua_has(L, idx, "dt")) o->dt = mrn_lua_get_number(L, idx, where, implicit_specs, n, "dt");
  o->dt_factor = mrn_lua_get_number(L, idx, where, implicit_specs, n, "dt_factor");
  o->min_node_mass = mrn_lua_get_number(L, idx, where, implicit_specs, n, "min_node_mass");
  o->ghost = mrn_lua_get_number(L, idx, where, implicit_specs, n, "ghost");
  o->bbar = mrn_lua_get_boolean(L, idx, where, implicit_specs, n, "bbar", 0);
  o->cutbacks = (int)mrn_lua_get_integer(L, idx, where, implicit_specs, n, "cutbacks");
}

/* a new integrator for the simulation at sim_idx with the options table at
 * opt_idx, attached to it (sim:run steps with it) and kept by it; pushed */
static void new_integrator(lua_State *L, int sim_idx, int opt_idx, const char *where) {
  sim_idx = lua_absindex(L, sim_idx);
  mrn_sim *sim = mrn_lua_check_sim(L, sim_idx);
  mrn_implicit_options o;
  read_options(L, opt_idx, where, &o);
  implicit_box *b = lua_newuserdatauv(L, sizeof *b, 1);
  b->im = NULL;
  luaL_setmetatable(L, MRN_LUA_IMPLICIT);
  lua_pushvalue(L, sim_idx);
  lua_setiuservalue(L, -2, 1);
  b->im = mrn_implicit_new(sim, &o);
  if (!b->im) mrn_lua_engine_error(L, where);
  mrn_implicit_attach(b->im); /* sim:run now steps with it */
  lua_pushvalue(L, -1);
  set_weak(L, INTEGRATORS, sim_idx);
  lua_pushnil(L);
  set_weak(L, PENDING, sim_idx);
}

/* sim:implicit{...} */
static int l_sim_implicit(lua_State *L) {
  if (lua_isnoneornil(L, 2)) lua_newtable(L), lua_replace(L, 2);
  new_integrator(L, 1, 2, "implicit{}");
  return 1;
}

void mrn_lua_implicit_configure(lua_State *L, int sim_idx, int opt_idx, const char *where) {
  mrn_implicit_options o;
  if (opt_idx) read_options(L, opt_idx, where, &o); /* errors now, at the deck line that made the simulation */
  if (opt_idx) lua_pushvalue(L, opt_idx);
  else lua_newtable(L);
  set_weak(L, PENDING, sim_idx);
}

void mrn_lua_implicit_prepare(lua_State *L, int sim_idx, const char *where) {
  if (get_weak(L, PENDING, sim_idx) == LUA_TTABLE) {
    new_integrator(L, sim_idx, -1, where);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

/* sim:integrator(): the implicit integrator object (made now if
 * integrator = "implicit" and not yet made), or nil for the explicit step */
static int l_sim_integrator(lua_State *L) {
  mrn_lua_check_sim(L, 1);
  mrn_lua_implicit_prepare(L, 1, "integrator()");
  get_weak(L, INTEGRATORS, 1);
  return 1;
}

static void push_history(lua_State *L, const mrn_implicit_history *h) {
  lua_createtable(L, 0, 6);
  lua_pushnumber(L, h->dt), lua_setfield(L, -2, "dt");
  lua_pushinteger(L, h->cuts), lua_setfield(L, -2, "cuts");
  lua_pushinteger(L, h->rejected_iterations), lua_setfield(L, -2, "rejected_iterations");
  lua_pushinteger(L, h->iterations), lua_setfield(L, -2, "iterations");
  lua_pushnumber(L, h->residual), lua_setfield(L, -2, "residual");
  lua_createtable(L, h->iterations, 0);
  for (int k = 0; k < h->iterations; k++) lua_pushnumber(L, h->err[k]), lua_rawseti(L, -2, k + 1);
  lua_setfield(L, -2, "errors");
}

static int l_implicit_step(lua_State *L) {
  mrn_implicit *im = check_implicit(L, 1);
  mrn_implicit_history h;
  if (mrn_implicit_advance(im, HUGE_VAL, &h)) return mrn_lua_engine_error(L, NULL);
  push_history(L, &h);
  return 1;
}

/* imp:last(): the Newton history of the last step (of imp:step() or sim:run) */
static int l_implicit_last(lua_State *L) {
  push_history(L, mrn_implicit_last(check_implicit(L, 1)));
  return 1;
}

static void push_vector(lua_State *L, const double v[3]) {
  lua_createtable(L, 3, 0);
  for (int d = 0; d < 3; d++) lua_pushnumber(L, v[d]), lua_rawseti(L, -2, d + 1);
}

static int l_implicit_energy(lua_State *L) {
  mrn_implicit *im = check_implicit(L, 1);
  mrn_implicit_energy e;
  mrn_implicit_energies(im, &e);
  lua_createtable(L, 0, 10);
  lua_pushnumber(L, e.kinetic), lua_setfield(L, -2, "kinetic");
  lua_pushnumber(L, e.strain), lua_setfield(L, -2, "strain");
  lua_pushnumber(L, e.dissipated), lua_setfield(L, -2, "dissipated");
  lua_pushnumber(L, e.external_work), lua_setfield(L, -2, "external_work");
  lua_pushnumber(L, e.constraint_work), lua_setfield(L, -2, "constraint_work");
  lua_pushnumber(L, e.total), lua_setfield(L, -2, "total");
  lua_pushnumber(L, e.mapping_loss), lua_setfield(L, -2, "mapping_loss");
  lua_pushnumber(L, e.ghost), lua_setfield(L, -2, "ghost");
  push_vector(L, e.momentum), lua_setfield(L, -2, "momentum");
  push_vector(L, e.angular), lua_setfield(L, -2, "angular");
  return 1;
}

static int l_implicit_next_dt(lua_State *L) {
  mrn_implicit *im = check_implicit(L, 1);
  double dt;
  if (mrn_implicit_next_dt(im, &dt)) return mrn_lua_engine_error(L, NULL);
  lua_pushnumber(L, dt);
  return 1;
}

/* imp:point_force{ region, force | traction }: replaces the loads of the
 * points inside region (selected as sim:point_force does); returns how many */
static int set_implicit(void *ctx, size_t p, const double f[3]) { return mrn_implicit_set_point_force(ctx, p, f); }

static int l_implicit_point_force(lua_State *L) {
  mrn_implicit *im = check_implicit(L, 1);
  lua_getiuservalue(L, 1, 1);
  mrn_sim *sim = mrn_lua_check_sim(L, -1);
  lua_pop(L, 1);
  lua_pushinteger(L, mrn_lua_point_force_args(L, 2, sim, "point_force{}", set_implicit, im));
  return 1;
}

static int l_implicit_load_factor(lua_State *L) {
  mrn_implicit *im = check_implicit(L, 1);
  mrn_implicit_set_load_factor(im, mrn_lua_check_load_factor(L, 2));
  return 0;
}

static int l_implicit_clear_forces(lua_State *L) {
  mrn_implicit_clear_point_forces(check_implicit(L, 1));
  return 0;
}

void mrn_lua_open_implicit(lua_State *L, int module) {
  (void)module;
  luaL_newmetatable(L, MRN_LUA_IMPLICIT);
  /* imp:NAME is l_implicit_NAME; __gc and __close are imp:free, and
   * sim:implicit and sim:integrator (below) are l_sim_implicit and l_sim_integrator */
  static const luaL_Reg meta[] = {
      {"__gc", l_implicit_free},
      {"__close", l_implicit_free},
      {NULL, NULL},
  };
  luaL_setfuncs(L, meta, 0);
  static const luaL_Reg methods[] = {
      {"step", l_implicit_step},
      {"last", l_implicit_last},
      {"energy", l_implicit_energy},
      {"next_dt", l_implicit_next_dt},
      {"point_force", l_implicit_point_force},
      {"clear_forces", l_implicit_clear_forces},
      {"load_factor", l_implicit_load_factor},
      {"free", l_implicit_free},
      {NULL, NULL},
  };
  lua_newtable(L);
  luaL_setfuncs(L, methods, 0);
  mrn_lua_strict(L, -1, "implicit integrator", "method");
  lua_setfield(L, -2, "__index");
  lua_pop(L, 1);
  /* sim:implicit{...} joins the simulation's methods */
  luaL_getmetatable(L, MRN_LUA_SIM);
  lua_getfield(L, -1, "__index");
  lua_pushcfunction(L, l_sim_implicit);
  lua_setfield(L, -2, "implicit");
  lua_pushcfunction(L, l_sim_integrator);
  lua_setfield(L, -2, "integrator");
  lua_pop(L, 2);
  mrn_spec_register_group("implicit{}", implicit_specs, MRN_COUNT(implicit_specs));
}
