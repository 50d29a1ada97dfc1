/* moraine: the thermo settings of simulation{}, mpm.load() and run{}.
 *
 *   thermo = 500                                   a line every 500 steps
 *   thermo = { every = 500, columns = { "step", "time", "W_plastic", "W_MPM" } }
 *
 * The columns are those of solver/run.h (mrn_thermo_column). */
#include <string.h>

#include "lua/lua_check.h"
#include "lua/lua_sim.h"

static const mrn_spec thermo_specs[] = {
    {"every", MRN_SPEC_INTEGER, 0, 100, 0, 1e12, 0, 0, "steps", "a thermo line every N steps (0: none)", NULL},
    {"columns", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL,
     "names of the columns: step, time, dt, steps_per_s or any diagnostics column", NULL},
};

/* the number form, checked as simulation{} checked it before the table form came */
static const mrn_spec number_form[] = {
    {"thermo", MRN_SPEC_INTEGER, 0, 100, 0, 1e12, 0, 0, "steps", "a thermo line every N steps (0: none)", NULL},
};

/* columns = {...} at idx into t */
static void read_columns(lua_State *L, int idx, const char *where, mrn_lua_thermo *t) {
  const lua_Integer n = luaL_len(L, idx);
  if (n < 1 || n > MRN_THERMO_MAX_COLUMNS)
    mrn_lua_error(L, where, "columns must list 1 to %d column names, got %lld", MRN_THERMO_MAX_COLUMNS, (long long)n);
  const char *names[128];
  const int count = mrn_thermo_column_count() < 127 ? mrn_thermo_column_count() : 127;
  for (int i = 0; i < count; i++) names[i] = mrn_thermo_column_name(i);
  names[count] = NULL;
  for (int i = 0; i < (int)n; i++) {
    lua_geti(L, idx, i + 1);
    if (lua_type(L, -1) != LUA_TSTRING)
      mrn_lua_error(L, where, "columns[%d] must be a column name, got %s", i + 1, luaL_typename(L, -1));
    char key[32];
    snprintf(key, sizeof key, "columns[%d]", i + 1);
    mrn_lua_check_choice(L, where, key, lua_tostring(L, -1), names);
    t->columns[i] = mrn_thermo_column(lua_tostring(L, -1));
    lua_pop(L, 1);
  }
  t->ncolumns = (int)n;
}

void mrn_lua_read_thermo(lua_State *L, int idx, const char *where, mrn_lua_thermo *t) {
  idx = lua_absindex(L, idx);
  char sub[96];
  snprintf(sub, sizeof sub, "%s thermo", where);
  const int n = MRN_COUNT(thermo_specs);
  if (lua_type(L, idx) == LUA_TNUMBER) {
    lua_createtable(L, 0, 1);
    lua_pushvalue(L, idx);
    lua_setfield(L, -2, "thermo");
    mrn_lua_check_table(L, -1, where, number_form, 1);
    t->every = mrn_lua_get_integer(L, -1, where, number_form, 1, "thermo");
    lua_pop(L, 1);
    return;
  }
  if (lua_type(L, idx) != LUA_TTABLE)
    mrn_lua_error(L, where, "thermo must be a number of steps or a table {every, columns}, got %s",
                  luaL_typename(L, idx));
  mrn_lua_check_table(L, idx, sub, thermo_specs, n);
  if (mrn_lua_has(L, idx, "every")) t->every = mrn_lua_get_integer(L, idx, sub, thermo_specs, n, "every");
  if (mrn_lua_has(L, idx, "columns")) {
    lua_getfield(L, idx, "columns");
    read_columns(L, lua_gettop(L), sub, t);
    lua_pop(L, 1);
  }
}

void mrn_lua_thermo_apply(const mrn_lua_thermo *t, mrn_run_options *opt) {
  opt->thermo_every = t->every;
  opt->thermo_columns = t->ncolumns ? t->columns : NULL;
  opt->thermo_ncolumns = t->ncolumns;
}

const mrn_spec_group mrn_lua_thermo_group = {"thermo", thermo_specs, MRN_COUNT(thermo_specs)};
