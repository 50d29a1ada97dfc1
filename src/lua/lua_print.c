/* moraine: the deck's prints through the run log (core/log.h).
 *
 * print(), io.write() and the write method of io.stdout and io.stderr do
 * what Lua's own do, and the run log gets the same text; the progress bar
 * leaves the terminal's line first. Every other file is written by Lua's own
 * method. What the deck writes goes out at once (Lua's print flushes too). */
#include <lauxlib.h>
#include <stdio.h>

#include "core/log.h"
#include "lua/lua_internal.h"

static int log_print(lua_State *L) {
  const int n = lua_gettop(L);
  luaL_Buffer b;
  luaL_buffinit(L, &b);
  for (int i = 1; i <= n; i++) {
    if (i > 1) luaL_addchar(&b, '\t');
    luaL_tolstring(L, i, NULL);
    luaL_addvalue(&b);
  }
  luaL_addchar(&b, '\n');
  luaL_pushresult(&b);
  size_t len;
  const char *text = lua_tolstring(L, -1, &len);
  mrn_log_text(stdout, text, len);
  return 0;
}

/* the terminal stream of the open file at 1, or NULL */
static FILE *screen_of(lua_State *L) {
  luaL_Stream *p = luaL_testudata(L, 1, LUA_FILEHANDLE);
  return p && p->closef && (p->f == stdout || p->f == stderr) ? p->f : NULL;
}

/* file:write(...): upvalue 1 is Lua's own method */
static int log_file_write(lua_State *L) {
  FILE *screen = screen_of(L);
  if (!screen) {
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
  }
  const int n = lua_gettop(L);
  luaL_Buffer b;
  luaL_buffinit(L, &b);
  for (int i = 2; i <= n; i++) {
    /* numbers as Lua's io library writes them */
    if (lua_type(L, i) == LUA_TNUMBER) {
      char num[64];
      if (lua_isinteger(L, i)) snprintf(num, sizeof num, LUA_INTEGER_FMT, (LUAI_UACINT)lua_tointeger(L, i));
      else snprintf(num, sizeof num, LUA_NUMBER_FMT, (LUAI_UACNUMBER)lua_tonumber(L, i));
      luaL_addstring(&b, num);
    } else {
      size_t len;
      const char *s = luaL_checklstring(L, i, &len);
      luaL_addlstring(&b, s, len);
    }
  }
  luaL_pushresult(&b);
  size_t len;
  const char *text = lua_tolstring(L, -1, &len);
  mrn_log_text(screen, text, len);
  if (ferror(screen)) return luaL_fileresult(L, 0, NULL);
  lua_settop(L, 1);
  return 1;
}

/* io.write(...): the write method of the default output file */
static int log_io_write(lua_State *L) {
  lua_getfield(L, LUA_REGISTRYINDEX, "_IO_output");
  lua_getfield(L, -1, "write");
  lua_insert(L, 1);
  lua_insert(L, 2);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

void mrn_lua_log_prints(lua_State *L) {
  lua_pushcfunction(L, log_print);
  lua_setglobal(L, "print");
  luaL_getmetatable(L, LUA_FILEHANDLE);
  lua_getfield(L, -1, "__index");
  lua_getfield(L, -1, "write");
  lua_pushcclosure(L, log_file_write, 1);
  lua_setfield(L, -2, "write");
  lua_pop(L, 2);
  lua_getglobal(L, "io");
  lua_pushcfunction(L, log_io_write);
  lua_setfield(L, -2, "write");
  lua_pop(L, 1);
}
