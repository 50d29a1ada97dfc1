/* moraine: the `moraine` Lua module and the deck runner. */
#define _GNU_SOURCE /* dladdr */
#include <dlfcn.h>
#include <lauxlib.h>
#include <lualib.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/spec.h"
#include "io/output.h"
#include "io/provenance.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"
#include "lua/lua_safe.h"
#include "lua/lua_sim.h"
#include "lua/moraine_lua.h"

static char library_dir[2 * PATH_MAX];

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

/* The prefix an installed moraine binary lives in, from the file that holds
 * this code: <prefix>/bin/moraine, or the Lua C module
 * <prefix>/lib/lua/5.4/moraine.so that a stock lua5.4 loaded. `out` gets
 * "<dir>/<up>" for the first candidate under which the pure-Lua library
 * exists; 0 when none (a build-tree binary). */
static int installed_prefix(char *out, size_t cap) {
  Dl_info info;
  char self[PATH_MAX];
  if (!dladdr((void *)installed_prefix, &info) || !info.dli_fname) return 0;
  /* for the executable itself dladdr answers argv[0], which may be a bare name found on $PATH */
  if (!strcmp(info.dli_fname, program_invocation_name)) {
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0) return 0;
    self[len] = '\0';
  } else if (!realpath(info.dli_fname, self)) {
    return 0;
  }
  char *slash = strrchr(self, '/');
  if (!slash) return 0;
  *slash = '\0';
  static const char *const ups[] = {MORAINE_BIN_TO_PREFIX, MORAINE_CMOD_TO_PREFIX};
  for (int i = 0; i < 2; i++) {
    char candidate[PATH_MAX + 256];
    snprintf(candidate, sizeof candidate, "%s/%s/%s/moraine", self, ups[i], MORAINE_LUA_INSTALL_REL);
    if (is_dir(candidate)) {
      snprintf(candidate, sizeof candidate, "%s/%s", self, ups[i]);
      char real[PATH_MAX];
      snprintf(out, cap, "%s", realpath(candidate, real) ? real : candidate);
      return 1;
    }
  }
  return 0;
}

/* The pure-Lua library is looked for in the prefix of an installed binary
 * (<prefix>/share/moraine/lua), then in the source tree the binary was built
 * from; no environment variable is needed. */
const char *mrn_lua_library_dir(void) {
  if (library_dir[0]) return library_dir;
  char prefix[PATH_MAX + 128];
  if (installed_prefix(prefix, sizeof prefix))
    snprintf(library_dir, sizeof library_dir, "%s/%s", prefix, MORAINE_LUA_INSTALL_REL);
  else
    snprintf(library_dir, sizeof library_dir, "%s", MORAINE_LUA_SOURCE_DIR);
  return library_dir;
}

/* The moraine program, for decks that start further runs
 * (lua/moraine/sweep.lua): the running executable, or the installed
 * <prefix>/bin/moraine when a stock lua5.4 loaded the module; "moraine"
 * when neither can be found. */
static void push_executable(lua_State *L) {
  char exe[PATH_MAX], prefix[PATH_MAX + 128];
  Dl_info info;
  ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
  int in_exe = dladdr((void *)push_executable, &info) && info.dli_fname && !strcmp(info.dli_fname, program_invocation_name);
  if (in_exe && len > 0) {
    exe[len] = '\0';
    lua_pushstring(L, exe);
  } else if (!in_exe && installed_prefix(prefix, sizeof prefix)) {
    lua_pushfstring(L, "%s/%s/moraine", prefix, MORAINE_INSTALL_BINDIR);
  } else {
    lua_pushstring(L, "moraine");
  }
}

/* registry[key] = the value on top, unless it is set already (pops it) */
static void registry_default(lua_State *L, const char *key) {
  if (lua_getfield(L, LUA_REGISTRYINDEX, key) == LUA_TNIL) {
    lua_pushvalue(L, -2);
    lua_setfield(L, LUA_REGISTRYINDEX, key);
  }
  lua_pop(L, 2);
}

/* package.path: the pure-Lua library's directory first */
static void prepend_library_path(lua_State *L) {
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "path");
  const char *old = lua_tostring(L, -1);
  const char *dir = mrn_lua_library_dir();
  lua_pushfstring(L, "%s/?.lua;%s/?/init.lua;%s", dir, dir, old ? old : "");
  lua_setfield(L, -3, "path");
  lua_pop(L, 2);
}

int luaopen_moraine(lua_State *L) {
  lua_getfield(L, LUA_REGISTRYINDEX, "moraine.module");
  if (!lua_isnil(L, -1)) return 1;
  lua_pop(L, 1);
  mrn_lua_active = L;
  /* what the moraine program sets before, for a stock lua5.4: no --set, output in "out" */
  lua_newtable(L);
  registry_default(L, "moraine.args");
  lua_pushstring(L, "out");
  registry_default(L, "moraine.outdir");
  prepend_library_path(L);
  lua_newtable(L);
  int module = lua_gettop(L);
  mrn_lua_open_regions(L, module);
  mrn_lua_open_materials(L, module);
  mrn_lua_open_driver(L, module);
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
  lua_pushcfunction(L, mrn_lua_l_parallel_io);
  lua_setfield(L, module, "parallel_io");
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
  lua_getglobal(L, "package");
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
  mrn_lua_log_prints(L);
  mrn_lua_parallel_io_open(L); /* before --safe's checks, which then judge the deck's own paths */
  if (opt && opt->safe) mrn_lua_safe_open(L, opt->outdir ? opt->outdir : "out");
  if (opt && opt->restart) mrn_lua_restart_open(L, opt->restart);
  return 0;
}

/* The deck as a function on the stack: the file at path, or standard input
 * for "-" (its text kept in the registry for the provenance). With --safe
 * it too must be source text. A status of lua_load. */
static int load_deck(lua_State *L, const char *path, const mrn_deck_options *opt) {
  const char *mode = opt && opt->safe ? "t" : NULL;
  if (strcmp(path, "-") != 0) return mode ? mrn_lua_load_text(L, path) : luaL_loadfile(L, path);
  luaL_Buffer b;
  luaL_buffinit(L, &b);
  size_t got;
  while ((got = fread(luaL_prepbuffer(&b), 1, LUAL_BUFFERSIZE, stdin)) > 0) luaL_addsize(&b, got);
  luaL_pushresult(&b);
  if (ferror(stdin)) {
    lua_pushfstring(L, "cannot read the deck from standard input: %s", strerror(errno));
    return LUA_ERRFILE;
  }
  lua_pushvalue(L, -1);
  lua_setfield(L, LUA_REGISTRYINDEX, "moraine.deck_text");
  size_t len;
  const char *text = lua_tolstring(L, -1, &len);
  /* a first line "#!..." is skipped, as luaL_loadfile does; its newline stays, so the line numbers do */
  size_t skip = text[0] == '#' ? strcspn(text, "\n") : 0;
  int status = luaL_loadbufferx(L, text + skip, len - skip, "=stdin", mode);
  if (status != LUA_OK && mode) { /* Lua's refusal of a binary chunk names no file */
    lua_pushfstring(L, "stdin: %s", lua_tostring(L, -1));
    lua_remove(L, -2);
  }
  lua_remove(L, -2);
  return status;
}

/* the deck, the command line and the version beside the outputs (io/provenance.h) */
static int write_provenance(lua_State *L, const char *path, const mrn_deck_options *opt) {
  if (strcmp(path, "-") != 0) return mrn_provenance_write(opt->outdir, path, opt->argc, opt->argv, opt->sets, opt->nsets);
  lua_getfield(L, LUA_REGISTRYINDEX, "moraine.deck_text");
  size_t len;
  const char *text = lua_tolstring(L, -1, &len);
  int rc = mrn_provenance_write_text(opt->outdir, text, len, opt->argc, opt->argv, opt->sets, opt->nsets);
  lua_pop(L, 1);
  return rc;
}

/* after the deck ran: --restart's checkpoint must have been continued */
static int restart_done(lua_State *L) {
  const char *unfinished = mrn_lua_restart_unfinished(L);
  return unfinished ? luaL_error(L, "%s", unfinished) : 0;
}

int mrn_lua_run_deck(const char *path, const mrn_deck_options *opt) {
  lua_State *L = luaL_newstate();
  if (!L) {
    mrn_log_error("cannot create a Lua state (out of memory)");
    return 1;
  }
  luaL_openlibs(L);
  mrn_lua_watch_interrupts(L);
  lua_pushcfunction(L, traceback_handler);
  int handler = lua_gettop(L);
  lua_pushcfunction(L, open_protected);
  lua_pushlightuserdata(L, (void *)opt);
  int status = lua_pcall(L, 1, 0, handler);
  if (status == LUA_OK) status = load_deck(L, path, opt);
  /* provenance: the deck, the command line and the version beside the
   * outputs; a run whose record cannot be written is not started */
  int rc = 0;
  if (status == LUA_OK && opt && opt->outdir && write_provenance(L, path, opt) != MRN_OK) {
    mrn_log_error("%s", mrn_error_message());
    rc = MRN_EXIT_OUTPUT;
  }
  if (status == LUA_OK && rc == 0) {
    /* mpm.deck and mpm.deck_dir: decks find their neighbouring files through these */
    lua_getglobal(L, "mpm");
    lua_pushstring(L, path);
    lua_setfield(L, -2, "deck");
    lua_pushstring(L, path); /* for the outputs' records, whatever the deck does to mpm.deck */
    lua_setfield(L, LUA_REGISTRYINDEX, MRN_LUA_DECK_KEY);
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
    if (status == LUA_OK && opt) mrn_lua_warn_unused_sets(L, opt->sets, opt->nsets);
  }
  if (status != LUA_OK) {
    mrn_log_error("%s", lua_tostring(L, -1));
    rc = mrn_lua_exit_status(L);
  }
  mrn_lua_watch_interrupts(NULL);
  lua_close(L); /* closes the simulations still open: their last outputs */
  if (mrn_lua_take_late_output_failure()) rc = MRN_EXIT_OUTPUT;
  mrn_output_forget_files();
  return rc;
}
