/* moraine: the `moraine` Lua module and the deck runner. */
#include <lauxlib.h>
#include <lualib.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/spec.h"
#include "io/output.h"
#include "io/provenance.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"
#include "lua/lua_safe.h"
#include "lua/lua_sim.h"
#include "lua/moraine_lua.h"

static char library_dir[PATH_MAX + 128];

/* mpm.wall_time(): seconds of a monotonic wall clock, for timing parts of a
 * deck (os.clock() counts the CPU time of every thread) */
static int l_wall_time(lua_State *L) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  lua_pushnumber(L, (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec);
  return 1;
}

static int is_dir(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* The pure-Lua library is looked for next to the executable first
 * (<prefix>/bin/moraine -> <prefix>/share/moraine/lua), then in the source
 * tree the binary was built from; no environment variable is needed. */
const char *mrn_lua_library_dir(void) {
  if (library_dir[0]) return library_dir;
  char exe[PATH_MAX];
  ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (len > 0) {
    exe[len] = '\0';
    char *slash = strrchr(exe, '/');
    if (slash) {
      *slash = '\0';
      char candidate[PATH_MAX + 128];
      snprintf(candidate, sizeof candidate, "%s/../%s/moraine", exe, MORAINE_LUA_INSTALL_REL);
      if (is_dir(candidate)) {
        snprintf(library_dir, sizeof library_dir, "%s/../%s", exe, MORAINE_LUA_INSTALL_REL);
        return library_dir;
      }
    }
  }
  snprintf(library_dir, sizeof library_dir, "%s", MORAINE_LUA_SOURCE_DIR);
  return library_dir;
}

/* The path of the running executable (for decks that start further runs,
 * lua/moraine/sweep.lua); "moraine" when /proc/self/exe cannot be read. */
static void push_executable(lua_State *L) {
  char exe[PATH_MAX];
  ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
  lua_pushstring(L, len > 0 ? (exe[len] = '\0', exe) : "moraine");
}

static int l_param(lua_State *L) {
  const char *name = luaL_checkstring(L, 1);
  int has_default = !lua_isnone(L, 2);
  lua_settop(L, 2);
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

int luaopen_moraine(lua_State *L) {
  lua_getfield(L, LUA_REGISTRYINDEX, "moraine.module");
  if (!lua_isnil(L, -1)) return 1;
  lua_pop(L, 1);
  lua_newtable(L);
  int module = lua_gettop(L);
  mrn_lua_open_regions(L, module);
  mrn_lua_open_materials(L, module);
  mrn_lua_open_simulation(L, module);
  mrn_lua_open_warnings(L, module);
  mrn_lua_open_implicit(L, module);
  lua_pushstring(L, MORAINE_VERSION);
  lua_setfield(L, module, "version");
  lua_pushstring(L, mrn_lua_library_dir());
  lua_setfield(L, module, "library_dir");
  push_executable(L);
  lua_setfield(L, module, "executable");
  lua_pushcfunction(L, l_param);
  lua_setfield(L, module, "param");
  lua_pushcfunction(L, l_wall_time);
  lua_setfield(L, module, "wall_time");
  lua_getfield(L, LUA_REGISTRYINDEX, "moraine.args");
  lua_setfield(L, module, "args");
  lua_getfield(L, LUA_REGISTRYINDEX, "moraine.outdir");
  lua_setfield(L, module, "outdir");
  lua_getfield(L, LUA_REGISTRYINDEX, "moraine.overwrite");
  lua_setfield(L, module, "overwrite");
  lua_pushvalue(L, module);
  lua_setfield(L, LUA_REGISTRYINDEX, "moraine.module");

  /* the pure-Lua part: lua/moraine/init.lua extends the module table */
  lua_getglobal(L, "require");
  lua_pushstring(L, "moraine.init");
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) return lua_error(L);
  if (lua_isfunction(L, -1)) {
    lua_pushvalue(L, module);
    lua_call(L, 1, 0);
  } else {
    lua_pop(L, 1);
  }
  mrn_lua_strict(L, module, "mpm", "function"); /* once complete: mpm.boxx names mpm.box */
  return 1;
}

void mrn_lua_open(lua_State *L, const mrn_deck_options *opt) {
  mrn_lua_active = L;
  lua_pushstring(L, opt && opt->outdir ? opt->outdir : "out");
  lua_setfield(L, LUA_REGISTRYINDEX, "moraine.outdir");
  lua_pushboolean(L, opt && opt->overwrite);
  lua_setfield(L, LUA_REGISTRYINDEX, "moraine.overwrite");
  lua_newtable(L);
  for (int i = 0; opt && i < opt->nsets; i++) {
    const char *eq = strchr(opt->sets[i], '=');
    if (!eq) continue;
    lua_pushlstring(L, opt->sets[i], (size_t)(eq - opt->sets[i]));
    lua_pushstring(L, eq + 1);
    lua_settable(L, -3);
  }
  lua_setfield(L, LUA_REGISTRYINDEX, "moraine.args");

  /* package.path: the library directory first */
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "path");
  const char *old = lua_tostring(L, -1);
  const char *dir = mrn_lua_library_dir();
  lua_pushfstring(L, "%s/?.lua;%s/?/init.lua;%s", dir, dir, old ? old : "");
  lua_setfield(L, -3, "path");
  lua_pop(L, 1);
  lua_getfield(L, -1, "preload");
  lua_pushcfunction(L, luaopen_moraine);
  lua_setfield(L, -2, "moraine");
  lua_pop(L, 2);

  luaL_requiref(L, "moraine", luaopen_moraine, 0);
  lua_setglobal(L, "mpm");
}

static int traceback_handler(lua_State *L) {
  const char *msg = lua_tostring(L, 1);
  if (!msg) msg = luaL_tolstring(L, 1, NULL);
  lua_pushstring(L, msg);
  /* here, before the stack unwinds, the deck still holds its simulations */
  if (mrn_interrupt_pending()) mrn_lua_save_interrupted(L);
  return 1;
}

static int open_protected(lua_State *L) {
  const mrn_deck_options *opt = lua_touserdata(L, 1);
  mrn_lua_open(L, opt);
  if (opt && opt->safe) mrn_lua_safe_open(L, opt->outdir ? opt->outdir : "out");
  if (opt && opt->restart) mrn_lua_restart_open(L, opt->restart);
  return 0;
}

/* after the deck ran: --restart's checkpoint must have been continued */
static int restart_done(lua_State *L) {
  const char *unfinished = mrn_lua_restart_unfinished(L);
  return unfinished ? luaL_error(L, "%s", unfinished) : 0;
}

int mrn_lua_run_deck(const char *path, const mrn_deck_options *opt) {
  lua_State *L = luaL_newstate();
  if (!L) {
    fprintf(stderr, "moraine: cannot create a Lua state (out of memory)\n");
    return 1;
  }
  luaL_openlibs(L);
  mrn_lua_watch_interrupts(L);
  lua_pushcfunction(L, traceback_handler);
  int handler = lua_gettop(L);
  lua_pushcfunction(L, open_protected);
  lua_pushlightuserdata(L, (void *)opt);
  int status = lua_pcall(L, 1, 0, handler);
  /* with --safe the deck too must be source text */
  if (status == LUA_OK) status = opt && opt->safe ? mrn_lua_load_text(L, path) : luaL_loadfile(L, path);
  /* provenance: the deck, the command line and the version beside the
   * outputs; a run whose record cannot be written is not started */
  int rc = 0;
  if (status == LUA_OK && opt && opt->outdir &&
      mrn_provenance_write(opt->outdir, path, opt->argc, opt->argv, opt->sets, opt->nsets) != MRN_OK) {
    fprintf(stderr, "moraine: %s\n", mrn_error_message());
    rc = MRN_EXIT_OUTPUT;
  }
  if (status == LUA_OK && rc == 0) {
    /* mpm.deck and mpm.deck_dir: decks find their neighbouring files through these */
    lua_getglobal(L, "mpm");
    lua_pushstring(L, path);
    lua_setfield(L, -2, "deck");
    const char *slash = strrchr(path, '/');
    if (slash) lua_pushlstring(L, path, (size_t)(slash - path));
    else lua_pushstring(L, ".");
    lua_setfield(L, -2, "deck_dir");
    lua_pop(L, 1);
    status = lua_pcall(L, 0, 0, handler);
    if (status == LUA_OK) {
      lua_pushcfunction(L, restart_done);
      status = lua_pcall(L, 0, 0, 0);
    }
  }
  if (status != LUA_OK) {
    fprintf(stderr, "moraine: %s\n", lua_tostring(L, -1));
    rc = mrn_lua_exit_status(L);
  }
  mrn_lua_watch_interrupts(NULL);
  lua_close(L); /* closes the simulations still open: their last outputs */
  if (mrn_lua_take_late_output_failure()) rc = MRN_EXIT_OUTPUT;
  mrn_output_forget_files();
  return rc;
}
