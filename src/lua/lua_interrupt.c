/* moraine: SIGINT and SIGTERM while Lua code runs.
 *
 * The signal handler sets a flag (core/interrupt.c), which a run reads after
 * each whole step; Lua code (a deck's setup, a loop, a hook, a region
 * function) never would. So the first signal also arms a count hook on the
 * deck's Lua thread, as the standalone `lua` interpreter does for Ctrl-C:
 * lua_sethook may be called from a signal handler (ldebug.c), and Lua 5.4
 * looks at the hook on every backward jump, so even `while true do end`
 * stops at the next instruction, with "interrupted by signal N" at its line.
 * The hook is not installed before a signal: a count hook makes the virtual
 * machine call out at every instruction, a cost every Lua loop of a deck
 * would pay for a signal that rarely comes. Code in C (a step, a seeding, a library function) is not cut
 * short: the hook fires when it returns to Lua, and a second signal still
 * exits at once. Coroutines made after the signal inherit the hook; one
 * already running stops when it yields or returns to the main thread. */
#include <lauxlib.h>

#include "core/interrupt.h"
#include "lua/lua_internal.h"

static lua_State *volatile watched; /* the deck's main thread */

/* push "FILE:LINE: " of the innermost Lua function running ("" in none) */
static void push_where(lua_State *L) {
  lua_Debug ar;
  for (int level = 0; lua_getstack(L, level, &ar); level++) {
    lua_getinfo(L, "Sl", &ar);
    if (ar.currentline > 0) {
      lua_pushfstring(L, "%s:%d: ", ar.short_src, ar.currentline);
      return;
    }
  }
  lua_pushliteral(L, "");
}

/* Called before every Lua instruction once armed. It stays armed, so Lua
 * code that catches the error with pcall stops again at once; it fires only
 * on instructions, never in the C message handler the error goes through. */
static void on_instruction(lua_State *L, lua_Debug *ar) {
  (void)ar;
  int sig = mrn_interrupt_pending();
  if (!sig) { /* the flag was cleared: back to full speed */
    lua_sethook(L, NULL, 0, 0);
    return;
  }
  push_where(L);
  lua_pushfstring(L, "interrupted by signal %d", sig);
  lua_concat(L, 2);
  lua_error(L);
}

static void arm(lua_State *L) { lua_sethook(L, on_instruction, LUA_MASKCOUNT, 1); }

/* in the signal handler. Only the main thread, which lives as long as the
 * state: a coroutine may have been collected by the time a signal comes. */
static void on_signal(int sig) {
  (void)sig;
  lua_State *L = watched;
  if (L) arm(L);
}

void mrn_lua_watch_interrupts(lua_State *L) {
  watched = L;
  mrn_interrupt_notify(L ? on_signal : NULL);
  if (L && mrn_interrupt_pending()) arm(L); /* a signal came before */
}
