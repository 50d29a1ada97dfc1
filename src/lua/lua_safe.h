/* moraine: the --safe mode of the deck runner (doc/security.md).
 *
 * A deck is a Lua program with the rights of the user who runs it. With
 * --safe it may not run programs, load native code or binary chunks, use the
 * debug library, or write outside the output directory; reading stays
 * allowed. */
#ifndef MRN_LUA_SAFE_H
#define MRN_LUA_SAFE_H

#include <lua.h>

struct mrn_output;

/* Install the restrictions in L, whose standard libraries and moraine module
 * are open; writes are confined to `outdir`, which exists. Raises a Lua
 * error only when out of memory (call it protected). */
void mrn_lua_safe_open(lua_State *L, const char *outdir);

/* luaL_loadfile in text mode: a binary chunk is refused with
 * "PATH: attempt to load a binary chunk (mode is 't')" */
int mrn_lua_load_text(lua_State *L, const char *path);

/* With --safe: raise "WHERE: 'PATH' is outside the output directory ...;
 * --safe allows writes only below the output directory" unless the file
 * `path` lies inside it. Without --safe: nothing. */
void mrn_lua_check_write(lua_State *L, const char *where, const char *path);

/* With --safe: the same for every file the outputs `o` will write and for
 * the checkpoints <name>_failed.h5 and <name>_interrupted.h5 of a run that
 * stops early; `where` names the call ("simulation{}"), the key is added. */
void mrn_lua_check_outputs(lua_State *L, const char *where, const struct mrn_output *o, const char *name);

#endif
