/* moraine: running decks — the entry points main.c uses. */
#ifndef MRN_LUA_MORAINE_LUA_H
#define MRN_LUA_MORAINE_LUA_H

#include <lua.h>

typedef struct mrn_deck_options {
  const char *outdir;       /* output directory (default "out") */
  const char *const *sets;  /* NAME=VALUE strings from --set */
  int nsets;
  const char *const *argv;  /* the command line, for provenance */
  int argc;
  int safe;                 /* --safe: the restrictions of lua_safe.h */
  const char *restart;      /* --restart FILE: the checkpoint the deck's run continues, or NULL */
  int overwrite;            /* --overwrite: runs may replace another run's outputs */
} mrn_deck_options;

/* Open the moraine module into L: package.preload["moraine"], the global
 * `mpm`, and the search path of the pure-Lua library. */
void mrn_lua_open(lua_State *L, const mrn_deck_options *opt);
int luaopen_moraine(lua_State *L);

/* exit status when the deck stopped because an output file could not be
 * written (disk full, quota, file-size limit, permission); the files written
 * before stay complete and no partial file is left */
#define MRN_EXIT_OUTPUT 3

/* Run a deck file. Returns 0 on success; on error prints "moraine: <message>"
 * to stderr and returns 1, or MRN_EXIT_OUTPUT for an output error. */
int mrn_lua_run_deck(const char *path, const mrn_deck_options *opt);

/* the directory holding the pure-Lua library (lua/moraine/...'s parent) */
const char *mrn_lua_library_dir(void);

#endif
