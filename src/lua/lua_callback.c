#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "lua/lua_internal.h"

lua_State *mrn_lua_active = NULL;

mrn_lua_callback *mrn_lua_callback_new(lua_State *L, int idx, const char *where) {
  mrn_lua_callback *cb = malloc(sizeof *cb);
  if (!cb) luaL_error(L, "out of memory");
  lua_pushvalue(L, idx);
  cb->ref = luaL_ref(L, LUA_REGISTRYINDEX);
  snprintf(cb->where, sizeof cb->where, "%s", where);
  return cb;
}

void mrn_lua_callback_release(void *p) {
  mrn_lua_callback *cb = p;
  if (!cb) return;
  if (mrn_lua_active) luaL_unref(mrn_lua_active, LUA_REGISTRYINDEX, cb->ref);
  free(cb);
}

void mrn_lua_callback_push(lua_State *L, const mrn_lua_callback *cb) { lua_rawgeti(L, LUA_REGISTRYINDEX, cb->ref); }

int mrn_lua_callback_pcall(lua_State *L, int nargs, int nresults) {
  if (lua_pcall(L, nargs, nresults, 0) != LUA_OK) {
    /* a signal stopped the callback (lua_interrupt.c): a run ends as on a
     * signal between steps, with its checkpoint */
    int code = mrn_interrupt_pending() ? MRN_ERR_INTERRUPTED : MRN_ERR_HOOK;
    const char *msg = lua_tostring(L, -1);
    mrn_error_code(code, "%s", msg ? msg : "error object is not a string");
    lua_pop(L, 1);
    return code;
  }
  return MRN_OK;
}

int mrn_lua_read_numbers(lua_State *L, int idx, int count, double *out) {
  idx = lua_absindex(L, idx);
  if (lua_istable(L, idx)) {
    for (int i = 0; i < count; i++) {
      lua_geti(L, idx, i + 1);
      if (lua_type(L, -1) != LUA_TNUMBER) {
        lua_pop(L, 1);
        return 0;
      }
      out[i] = lua_tonumber(L, -1);
      lua_pop(L, 1);
    }
    return 1;
  }
  for (int i = 0; i < count; i++) {
    if (lua_type(L, idx + i) != LUA_TNUMBER) return 0;
    out[i] = lua_tonumber(L, idx + i);
  }
  return 1;
}
