/* moraine: checking the argument tables a deck passes to the Lua API.
 *
 * Every table argument is described by an array of mrn_spec. Before a
 * function reads a table it calls mrn_lua_check_table(), which rejects
 * unknown keys (suggesting the closest valid one) and values of the wrong
 * type. The getters then read each key with its default and range check.
 * Every error is raised with luaL_error at level 1, so the message starts
 * with the deck file and line of the call: "deck.lua:12: simulation{}: ...". */
#ifndef MRN_LUA_CHECK_H
#define MRN_LUA_CHECK_H

#include <lua.h>

#include "core/spec.h"

#define MRN_COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* raise "where: message" with the caller's file and line */
int mrn_lua_error(lua_State *L, const char *where, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* The same for an output file that could not be written (disk full, quota,
 * file-size limit, permission): the message is also remembered, so that
 * when it is what stops the deck moraine exits with MRN_EXIT_OUTPUT. */
int mrn_lua_output_error(lua_State *L, const char *where, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Re-raise the engine's last error (mrn_error_message()) at the deck line:
 * "where: message", or the message alone when where is NULL. Every failed
 * engine call of the binding ends in one of these two, so the message a deck
 * sees is the engine's, unchanged. */
int mrn_lua_engine_error(lua_State *L, const char *where);
/* the same for an output that could not be written (mrn_lua_output_error) */
int mrn_lua_engine_output_error(lua_State *L, const char *where);
/* the exit status for the error message at the top of the stack: 1, or
 * MRN_EXIT_OUTPUT when it is the last output error raised */
int mrn_lua_exit_status(lua_State *L);
/* whether the message at idx is the last output error raised; mark the
 * message at idx as one (a message extended after it was raised) */
int mrn_lua_is_output_error(lua_State *L, int idx);
/* push the registry table `name`, made with weak keys the first time (its
 * entries go with the objects they describe) */
void mrn_lua_push_weak_table(lua_State *L, const char *name);
/* the same with a weak `mode` of its own ("k", "v" or "kv") */
void mrn_lua_push_weak_table_mode(lua_State *L, const char *name, const char *mode);
void mrn_lua_mark_output_error(lua_State *L, int idx);
/* An output that fails where no error can be raised (the last rewrite of a
 * series when the garbage collector closes a simulation, at the latest when
 * the deck ends): the message is printed at once, and
 * mrn_lua_take_late_output_failure() then answers 1 (once), so that moraine
 * exits with MRN_EXIT_OUTPUT. */
void mrn_lua_late_output_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
int mrn_lua_take_late_output_failure(void);

/* check that idx is a table whose keys are all in specs and whose values have
 * the declared types; `where` names the function for messages ("simulation{}") */
void mrn_lua_check_table(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count);

/* getters: each looks the key up in specs for its default and range */
double mrn_lua_get_number(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count, const char *key);
long mrn_lua_get_integer(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count, const char *key);
int mrn_lua_get_boolean(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count, const char *key,
                        int def);
/* string value or NULL when absent and not required; checks `choices` with did-you-mean */
const char *mrn_lua_get_string(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count,
                               const char *key);
/* reads the vector `key` of exactly `dim` numbers into out (untouched when
 * absent), each checked against the key's spec; returns 1 if present */
int mrn_lua_get_vector(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count, const char *key,
                       int dim, double *out, int required);

/* The checks a key's getter makes, for values that come without a table
 * (setters such as sim:set_gravity{...} and sim:set_dt(0.001)): a setter and
 * the constructor key it changes share one spec, so they refuse the same
 * values with the same message. */
/* raise "NAME = V is out of range (expected ...)" unless v is a finite number
 * in the spec's range; NAME is `name`, or the spec's key when NULL */
void mrn_lua_check_number(lua_State *L, const char *where, const mrn_spec *spec, const char *name, double v);
/* the value at idx as a vector of exactly `dim` numbers, each checked by
 * mrn_lua_check_number and named KEY[i] */
void mrn_lua_to_vector(lua_State *L, int idx, const char *where, const mrn_spec *spec, int dim, double *out);
/* 1 when the key is present (not nil) */
int mrn_lua_has(lua_State *L, int idx, const char *key);

/* Reading a name that the table at idx does not hold (mpm.boxx,
 * sim:ad_particles) raises "<what> has no <kind> 'boxx' (did you mean
 * 'box'?)" at the deck line, instead of Lua's "attempt to call a nil value":
 * the table gets a metatable whose __index suggests the nearest of its keys.
 * Names present are found as before, without the metatable. */
void mrn_lua_strict(lua_State *L, int idx, const char *what, const char *kind);
/* raise "<what> has no <kind> 'key'" with the nearest of names (NULL-terminated) */
int mrn_lua_no_such(lua_State *L, const char *what, const char *kind, const char *key, const char *const *names);

/* check a string against a NULL-terminated list, raising with did-you-mean and the valid names */
void mrn_lua_check_choice(lua_State *L, const char *where, const char *key, const char *value,
                          const char *const *choices);

#endif
