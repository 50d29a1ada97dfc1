/* moraine: mpm.param(NAME, default), the deck's reading of --set NAME=VALUE,
 * and the warning about a --set no mpm.param call read. */
#include <lauxlib.h>
#include <string.h>

#include "core/spec.h"
#include "core/warn.h"
#include "lua/lua_internal.h"

#define PARAMS_READ "moraine.params_read" /* registry: the set of names mpm.param was asked for */

/* note that the deck asked for `name` */
static void mark_read(lua_State *L, const char *name) {
  if (lua_getfield(L, LUA_REGISTRYINDEX, PARAMS_READ) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setfield(L, LUA_REGISTRYINDEX, PARAMS_READ);
  }
  lua_pushboolean(L, 1);
  lua_setfield(L, -2, name);
  lua_pop(L, 1);
}

int l_param(lua_State *L) {
  const char *name = luaL_checkstring(L, 1);
  int has_default = !lua_isnone(L, 2);
  lua_settop(L, 2);
  mark_read(L, name);
  lua_getfield(L, LUA_REGISTRYINDEX, "moraine.args");
  lua_getfield(L, -1, name);
  if (lua_isnil(L, -1)) {
    if (!has_default) return luaL_error(L, "param('%s'): not given with --set and no default", name);
    lua_settop(L, 2);
    return 1;
  }
  /* convert to the default's type when it is a number or boolean */
  if (lua_type(L, 2) == LUA_TNUMBER) {
    if (!lua_isnumber(L, -1))
      return luaL_error(L, "param('%s'): --set %s=%s is not a number", name, name, lua_tostring(L, -1));
    lua_pushnumber(L, lua_tonumber(L, -1));
  } else if (lua_type(L, 2) == LUA_TBOOLEAN) {
    const char *s = lua_tostring(L, -1);
    lua_pushboolean(L, strcmp(s, "true") == 0 || strcmp(s, "1") == 0 || strcmp(s, "yes") == 0);
  }
  return 1;
}

#define MAX_NAMES 64 /* names the did-you-mean compares with */

/* the names mpm.param was asked for, NULL-terminated, into names[MAX_NAMES + 1] */
static void names_read(lua_State *L, int read, const char **names) {
  int n = 0;
  lua_pushnil(L);
  while (lua_next(L, read)) {
    lua_pop(L, 1);
    if (n < MAX_NAMES && lua_type(L, -1) == LUA_TSTRING) names[n++] = lua_tostring(L, -1);
  }
  names[n] = NULL;
}

/* the length of NAME in "NAME=VALUE" */
static size_t name_length(const char *set) { return strcspn(set, "="); }

/* One warning naming every --set whose NAME no mpm.param call asked for, in
 * the order given, with the nearest name the deck did ask for: a misspelt
 * --set changes nothing in the run, and without it nobody would notice. */
void mrn_lua_warn_unused_sets(lua_State *L, const char *const *sets, int nsets) {
  int top = lua_gettop(L);
  if (lua_getfield(L, LUA_REGISTRYINDEX, PARAMS_READ) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
  }
  int read = lua_gettop(L);
  const char *names[MAX_NAMES + 1];
  names_read(L, read, names);
  char list[1024] = "";
  size_t len = 0;
  int unused = 0;
  for (int i = 0; i < nsets && len < sizeof list; i++) {
    size_t n = name_length(sets[i]);
    int later = 0; /* the last value of a name is the one that counts */
    for (int j = i + 1; j < nsets; j++) later |= name_length(sets[j]) == n && !strncmp(sets[i], sets[j], n);
    lua_pushlstring(L, sets[i], n);
    const char *name = lua_tostring(L, -1);
    if (!later && lua_getfield(L, read, name) == LUA_TNIL)
      len += (size_t)snprintf(list + len, sizeof list - len, "%s--set %s%s", unused++ ? ", " : "", sets[i],
                              mrn_hint(mrn_suggest_from(names, name)).s);
    lua_settop(L, read);
  }
  if (unused)
    mrn_warning("unused_set", "%s: never read by mpm.param, so %s nothing", list,
                unused > 1 ? "they changed" : "it changed");
  lua_settop(L, top);
}
