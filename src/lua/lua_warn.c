/* moraine: mpm.warnings{ignore = {...}} — silencing warnings from a deck (core/warn.h). */
#include <lauxlib.h>

#include "core/error.h"
#include "core/warn.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"

static const mrn_spec warnings_specs[] = {
    {"ignore", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL,
     "list of warning IDs to silence (dt_above_cfl, courant_above_one, one_particle_per_cell, or all)", NULL},
};

static int l_warnings(lua_State *L) {
  const char *where = "warnings{}";
  mrn_lua_check_table(L, 1, where, warnings_specs, MRN_COUNT(warnings_specs));
  lua_getfield(L, 1, "ignore");
  if (lua_istable(L, -1)) {
    /* the valid names, "all" included, for the did-you-mean of a misspelt ID */
    const char *valid[16];
    int n = 0;
    for (const char *const *id = mrn_warning_ids(); *id && n < 14; id++) valid[n++] = *id;
    valid[n++] = "all";
    valid[n] = NULL;
    lua_Integer len = luaL_len(L, -1);
    for (lua_Integer i = 1; i <= len; i++) {
      lua_geti(L, -1, i);
      if (lua_type(L, -1) != LUA_TSTRING)
        mrn_lua_error(L, where, "ignore[%d] must be a warning ID (a string), got %s", (int)i, luaL_typename(L, -1));
      const char *id = lua_tostring(L, -1);
      mrn_lua_check_choice(L, where, "ignore", id, valid);
      mrn_warning_ignore(id);
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
  return 0;
}

void mrn_lua_open_warnings(lua_State *L, int module) {
  mrn_spec_register_group("warnings{}", warnings_specs, MRN_COUNT(warnings_specs));
  lua_pushcfunction(L, l_warnings);
  lua_setfield(L, module, "warnings");
}
