/* moraine: the watchdog's bounds and what it saw, from Lua.
 *
 *   simulation{ watchdog = { energy = 1, dt = 4, speed = 1, every = 10 } }
 *   simulation{ watchdog = false }         -- every test off
 *   sim:set_watchdog{ energy = 0.5 }       -- the keys given change
 *   sim:watchdog()  --> { energy, dt, speed, checks }: the largest ratios seen
 *
 * The tests and their scales are described in solver/watchdog.h. */
#include <math.h>

#include "lua/lua_check.h"
#include "lua/lua_internal.h"
#include "solver/simulation.h"

static const mrn_spec watchdog_specs[] = {
    {"energy", MRN_SPEC_NUMBER, 0, 1, 0, HUGE_VAL, 0, 0, "",
     "stop when W_MPM exceeds this many times the energy scale (0: off)", NULL},
    {"dt", MRN_SPEC_NUMBER, 0, 4, 0, HUGE_VAL, 0, 0, "",
     "stop when an explicit step exceeds this many times h / max(c + |v|) (0: off)", NULL},
    {"speed", MRN_SPEC_NUMBER, 0, 1, 0, HUGE_VAL, 0, 0, "cells",
     "stop when a particle moves more than this many cells in an explicit step (0: off)", NULL},
    {"every", MRN_SPEC_INTEGER, 0, 10, 1, 1e12, 0, 0, "steps", "steps between checks", NULL},
};

void mrn_lua_read_watchdog(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  char sub[96];
  snprintf(sub, sizeof sub, "%s watchdog", where);
  mrn_watchdog *w = &sim->watchdog;
  if (lua_type(L, idx) == LUA_TBOOLEAN) {
    if (lua_toboolean(L, idx)) mrn_watchdog_default(w);
    else w->energy = w->dt = w->speed = 0.0;
    return;
  }
  mrn_lua_check_table(L, idx, sub, watchdog_specs, MRN_COUNT(watchdog_specs));
  const int n = MRN_COUNT(watchdog_specs);
  if (mrn_lua_has(L, idx, "energy")) w->energy = mrn_lua_get_number(L, idx, sub, watchdog_specs, n, "energy");
  if (mrn_lua_has(L, idx, "dt")) w->dt = mrn_lua_get_number(L, idx, sub, watchdog_specs, n, "dt");
  if (mrn_lua_has(L, idx, "speed")) w->speed = mrn_lua_get_number(L, idx, sub, watchdog_specs, n, "speed");
  if (mrn_lua_has(L, idx, "every")) w->every = mrn_lua_get_integer(L, idx, sub, watchdog_specs, n, "every");
}

static int l_sim_set_watchdog(lua_State *L) {
  mrn_lua_read_watchdog(L, 2, "set_watchdog()", mrn_lua_check_sim(L, 1));
  return 0;
}

static int l_sim_watchdog(lua_State *L) {
  const mrn_watchdog_state *s = &mrn_lua_check_sim(L, 1)->watch;
  lua_createtable(L, 0, 4);
  lua_pushnumber(L, s->peak_energy);
  lua_setfield(L, -2, "energy");
  lua_pushnumber(L, s->peak_dt);
  lua_setfield(L, -2, "dt");
  lua_pushnumber(L, s->peak_speed);
  lua_setfield(L, -2, "speed");
  lua_pushinteger(L, s->checks);
  lua_setfield(L, -2, "checks");
  return 1;
}

void mrn_lua_add_watchdog_methods(lua_State *L, int methods) {
  /* sim:NAME is l_sim_NAME, as in lua_sim.c */
  static const luaL_Reg fns[] = {
      {"set_watchdog", l_sim_set_watchdog},
      {"watchdog", l_sim_watchdog},
      {NULL, NULL},
  };
  lua_pushvalue(L, methods);
  luaL_setfuncs(L, fns, 0);
  lua_pop(L, 1);
  mrn_spec_register_group("simulation{} watchdog", watchdog_specs, MRN_COUNT(watchdog_specs));
}
