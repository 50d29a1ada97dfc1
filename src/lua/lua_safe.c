/* moraine: the --safe mode (doc/security.md).
 *
 * Each standard function that runs a program, loads native code, creates a
 * file outside the output directory or reaches past Lua's own checks (the
 * debug library) is replaced by one that raises "WHAT(): not available with
 * --safe (WHY)". The functions that write a named file check the name
 * first (mrn_confine_check); every chunk loader runs in text mode, since
 * "maliciously crafted binary chunks can crash the interpreter" (Lua 5.4
 * manual, §6.1, load). */
#include "lua/lua_safe.h"

#include <H5PLpublic.h>
#include <lauxlib.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/confine.h"
#include "io/output.h"
#include "lua/lua_check.h"

/* registry key of the output directory; present only with --safe */
#define SAFE_DIR_KEY "moraine.safe_dir"

/* ------------------------------------------------------- write checks */

void mrn_lua_check_write(lua_State *L, const char *where, const char *path) {
  lua_getfield(L, LUA_REGISTRYINDEX, SAFE_DIR_KEY);
  const char *dir = lua_tostring(L, -1);
  int rc = dir ? mrn_confine_check(dir, path) : MRN_OK;
  lua_pop(L, 1);
  if (rc != MRN_OK)
    mrn_lua_error(L, where, "%s; --safe allows writes only below the output directory", mrn_error_message());
}

/* check the file DIR/NAME+SUFFIX, the key named in the message */
static void check_output(lua_State *L, const char *where, const char *key, const char *dir, const char *name,
                         const char *suffix) {
  if (!name) return;
  char *path = mrn_path_join(dir, name);
  if (!path) luaL_error(L, "out of memory");
  lua_pushfstring(L, "%s%s", path, suffix);
  free(path);
  lua_pushfstring(L, "%s: %s", where, key);
  mrn_lua_check_write(L, lua_tostring(L, -1), lua_tostring(L, -2));
  lua_pop(L, 2);
}

void mrn_lua_check_outputs(lua_State *L, const char *where, const mrn_output *o, const char *name) {
  lua_getfield(L, LUA_REGISTRYINDEX, SAFE_DIR_KEY);
  int safe = lua_isstring(L, -1);
  lua_pop(L, 1);
  if (!safe) return;
  /* every file of a VTK series (<vtk>.pvd, <vtk>_NNNNNN.vtp, ...) is in the
   * directory of its .pvd; both checkpoints in that of <name>_failed.h5 */
  check_output(L, where, "vtk", o->dir, o->vtk_name, ".pvd");
  check_output(L, where, "diagnostics", o->dir, o->csv_name, "");
  check_output(L, where, "series", o->dir, o->series_name, "");
  check_output(L, where, "name", o->dir, name, "_failed.h5");
}

/* ------------------------------------------------------- replacements */

static int refused(lua_State *L) {
  return mrn_lua_error(L, lua_tostring(L, lua_upvalueindex(1)), "not available with --safe (%s)",
                       lua_tostring(L, lua_upvalueindex(2)));
}

/* table[name] = a function raising "LIB.NAME(): not available with --safe (WHY)" */
static void refuse(lua_State *L, int table, const char *lib, const char *name, const char *why) {
  lua_pushfstring(L, "%s.%s()", lib, name);
  lua_pushstring(L, why);
  lua_pushcclosure(L, refused, 2);
  lua_setfield(L, table, name);
}

/* table[name] = f, with the function it replaces as f's upvalue 1 */
static void wrap(lua_State *L, int table, const char *name, lua_CFunction f) {
  lua_getfield(L, table, name);
  lua_pushcclosure(L, f, 1);
  lua_setfield(L, table, name);
}

/* the replaced function (upvalue 1) called with every argument */
static int call_replaced(lua_State *L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

/* io.open(path [, mode]): a mode with w, a or + writes */
static int safe_open(lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  if (strpbrk(luaL_optstring(L, 2, "r"), "wa+")) mrn_lua_check_write(L, "io.open()", path);
  return call_replaced(L);
}

/* io.output(path) opens the file for writing; io.output(file) does not open */
static int safe_output(lua_State *L) {
  if (lua_type(L, 1) == LUA_TSTRING) mrn_lua_check_write(L, "io.output()", lua_tostring(L, 1));
  return call_replaced(L);
}

static int safe_remove(lua_State *L) {
  mrn_lua_check_write(L, "os.remove()", luaL_checkstring(L, 1));
  return call_replaced(L);
}

/* a rename writes both directories */
static int safe_rename(lua_State *L) {
  mrn_lua_check_write(L, "os.rename()", luaL_checkstring(L, 1));
  mrn_lua_check_write(L, "os.rename()", luaL_checkstring(L, 2));
  return call_replaced(L);
}

/* load(chunk [, name [, mode [, env]]]) with mode "t" whatever was asked;
 * an absent env stays absent (it is not a nil env) */
static int safe_load(lua_State *L) {
  if (lua_gettop(L) < 3) lua_settop(L, 3);
  lua_pushliteral(L, "t");
  lua_replace(L, 3);
  return call_replaced(L);
}

int mrn_lua_load_text(lua_State *L, const char *path) {
  int status = luaL_loadfilex(L, path, "t");
  /* Lua's refusal of a binary chunk (checkmode in ldo.c) names no file */
  const char *msg = status != LUA_OK ? lua_tostring(L, -1) : NULL;
  if (msg && !strncmp(msg, "attempt to load a binary", 24)) {
    lua_pushfstring(L, "%s: %s", path ? path : "stdin", msg);
    lua_remove(L, -2);
  }
  return status;
}

/* loadfile([path [, mode [, env]]]): Lua's own, in text mode whatever the mode */
static int safe_loadfile(lua_State *L) {
  const char *path = luaL_optstring(L, 1, NULL);
  int env = !lua_isnone(L, 3);
  if (mrn_lua_load_text(L, path) != LUA_OK) {
    luaL_pushfail(L);
    lua_insert(L, -2);
    return 2;
  }
  if (env) { /* the chunk's first upvalue is its _ENV */
    lua_pushvalue(L, 3);
    if (!lua_setupvalue(L, -2, 1)) lua_pop(L, 1);
  }
  return 1;
}

/* dofile([path]): Lua's own, in text mode */
static int safe_dofile(lua_State *L) {
  const char *path = luaL_optstring(L, 1, NULL);
  lua_settop(L, 1);
  if (mrn_lua_load_text(L, path) != LUA_OK) return lua_error(L);
  lua_call(L, 0, LUA_MULTRET);
  return lua_gettop(L) - 1;
}

/* package.searchers[2] in text mode: a Lua module found on package.path
 * (upvalue 1: package.searchpath, upvalue 2: the package table) */
static int search_lua(lua_State *L) {
  const char *name = luaL_checkstring(L, 1);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushstring(L, name);
  lua_getfield(L, lua_upvalueindex(2), "path");
  if (!lua_isstring(L, -1)) return luaL_error(L, "'package.path' must be a string");
  lua_call(L, 2, 2);
  if (lua_isnil(L, -2)) return 1; /* not found: the list of files tried */
  const char *file = lua_tostring(L, -2);
  if (luaL_loadfilex(L, file, "t") != LUA_OK)
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", name, file, lua_tostring(L, -1));
  lua_pushstring(L, file);
  return 2;
}

/* in place of the C searchers: a C module found on package.cpath is refused
 * by name (loading it runs its code); otherwise nothing is found */
static int search_c(lua_State *L) {
  const char *name = luaL_checkstring(L, 1);
  lua_getfield(L, lua_upvalueindex(2), "cpath");
  if (!lua_isstring(L, -1)) return 0;
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushstring(L, name);
  lua_pushvalue(L, -3);
  lua_call(L, 2, 1);
  if (!lua_isstring(L, -1)) return 0;
  luaL_where(L, 2); /* the line calling require, past require itself */
  return luaL_error(L, "%srequire('%s'): '%s' is a C module: not loaded with --safe (it runs native code)",
                    lua_tostring(L, -1), name, lua_tostring(L, -2));
}

static void restrict_package(lua_State *L) {
  lua_getglobal(L, "package");
  int package = lua_gettop(L);
  refuse(L, package, "package", "loadlib", "it loads native code");
  lua_getfield(L, package, "searchers");
  int searchers = lua_gettop(L);
  lua_getfield(L, package, "searchpath");
  lua_pushvalue(L, package);
  lua_pushcclosure(L, search_lua, 2);
  lua_rawseti(L, searchers, 2);
  lua_getfield(L, package, "searchpath");
  lua_pushvalue(L, package);
  lua_pushcclosure(L, search_c, 2);
  lua_rawseti(L, searchers, 3);
  lua_pushnil(L); /* the all-in-one C searcher */
  lua_rawseti(L, searchers, 4);
  lua_pop(L, 2);
}

/* every debug function but traceback: they read and change locals,
 * upvalues, metatables and the registry, past every other restriction */
static void restrict_debug(lua_State *L) {
  lua_getglobal(L, "debug");
  int debug = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, debug)) {
    lua_pop(L, 1);
    const char *name = lua_tostring(L, -1);
    if (strcmp(name, "traceback") != 0)
      refuse(L, debug, "debug", name, "the debug library reaches past the other restrictions");
  }
  lua_pop(L, 1);
}

void mrn_lua_safe_open(lua_State *L, const char *outdir) {
  lua_pushstring(L, outdir);
  lua_setfield(L, LUA_REGISTRYINDEX, SAFE_DIR_KEY);

  lua_getglobal(L, "os");
  int os = lua_gettop(L);
  refuse(L, os, "os", "execute", "it runs a program");
  refuse(L, os, "os", "tmpname", "it creates a file outside the output directory");
  wrap(L, os, "remove", safe_remove);
  wrap(L, os, "rename", safe_rename);
  lua_getglobal(L, "io");
  int io = lua_gettop(L);
  refuse(L, io, "io", "popen", "it runs a program");
  refuse(L, io, "io", "tmpfile", "it creates a file outside the output directory");
  wrap(L, io, "open", safe_open);
  wrap(L, io, "output", safe_output);
  lua_pushglobaltable(L);
  int base = lua_gettop(L);
  wrap(L, base, "load", safe_load);
  lua_pushcfunction(L, safe_loadfile);
  lua_setfield(L, base, "loadfile");
  lua_pushcfunction(L, safe_dofile);
  lua_setfield(L, base, "dofile");
  lua_pop(L, 3);

  restrict_package(L);
  restrict_debug(L);
  /* a checkpoint naming a filter HDF5 does not have built in would make
   * it load a plugin library from HDF5_PLUGIN_PATH: native code */
  H5PLset_loading_state(0);
}
