/* moraine: a deck's own files in a distributed run (doc/parallel.md, "What
 * the deck sees").
 *
 * The deck runs on every process, so its own file writes would happen once
 * per process, each process writing what it holds over the others'. By
 * default they happen once: on every process but 0, io.open for writing,
 * appending or updating and io.output with a file name open the null device
 * instead (the deck's code runs unchanged, its writes go nowhere), and
 * os.remove and os.rename do nothing and succeed. Reading is untouched.
 * mpm.parallel_io("every") gives every process its own writes (each to a
 * name of its own, e.g. from sim:parallel().rank); "once" restores the
 * default. On one process nothing changes. */
#include <lauxlib.h>
#include <string.h>

#include "core/comm.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"

#define EVERY_KEY "moraine.parallel_io_every"
#define NULL_DEVICE "/dev/null"

/* 1 when this process writes the deck's files */
static int writes_here(lua_State *L) {
  if (mrn_comm_rank() == 0) return 1;
  lua_getfield(L, LUA_REGISTRYINDEX, EVERY_KEY);
  const int every = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return every;
}

/* the replaced function (upvalue 1) on the arguments, the first one the
 * null device when `discard`: its results */
static int call_replaced(lua_State *L, int discard) {
  if (discard) {
    lua_pushstring(L, NULL_DEVICE);
    lua_replace(L, 1);
  }
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

/* io.open(path [, mode]) */
static int open_once(lua_State *L) {
  const int writes = strpbrk(luaL_optstring(L, 2, "r"), "wa+") != NULL;
  return call_replaced(L, writes && !writes_here(L));
}

/* io.output([file]): a file name opens it for writing */
static int output_once(lua_State *L) { return call_replaced(L, lua_type(L, 1) == LUA_TSTRING && !writes_here(L)); }

/* os.remove, os.rename: done by the writing process only */
static int file_op_once(lua_State *L) {
  if (!writes_here(L)) {
    lua_pushboolean(L, 1);
    return 1;
  }
  return call_replaced(L, 0);
}

/* table[name] = fn with the old table[name] as its upvalue */
static void wrap(lua_State *L, const char *lib, const char *name, lua_CFunction fn) {
  lua_getglobal(L, lib);
  lua_getfield(L, -1, name);
  lua_pushcclosure(L, fn, 1);
  lua_setfield(L, -2, name);
  lua_pop(L, 1);
}

void mrn_lua_parallel_io_open(lua_State *L) {
  if (mrn_comm_size() < 2) return;
  wrap(L, "io", "open", open_once);
  wrap(L, "io", "output", output_once);
  wrap(L, "os", "remove", file_op_once);
  wrap(L, "os", "rename", file_op_once);
}

/* mpm.parallel_io([mode]): "once" or "every"; returns the mode before */
int mrn_lua_l_parallel_io(lua_State *L) {
  lua_getfield(L, LUA_REGISTRYINDEX, EVERY_KEY);
  const int every = lua_toboolean(L, -1);
  lua_pop(L, 1);
  if (!lua_isnoneornil(L, 1)) {
    const char *mode = lua_tostring(L, 1);
    if (!mode || (strcmp(mode, "once") != 0 && strcmp(mode, "every") != 0))
      mrn_lua_error(L, "parallel_io()", "mode = '%s' is not valid; valid: 'once', 'every'", luaL_tolstring(L, 1, NULL));
    lua_pushboolean(L, strcmp(mode, "every") == 0);
    lua_setfield(L, LUA_REGISTRYINDEX, EVERY_KEY);
  }
  lua_pushstring(L, every ? "every" : "once");
  return 1;
}
