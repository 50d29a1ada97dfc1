#include "lua/lua_check.h"
#include "core/error.h"
#include "core/log.h"
#include "lua/moraine_lua.h"

#include <lauxlib.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* push "FILE:LINE: where: message", the location being the deck line that called the API */
static void push_message(lua_State *L, const char *where, const char *fmt, va_list ap) {
  char buf[1024];
  vsnprintf(buf, sizeof buf, fmt, ap);
  luaL_where(L, 1);
  lua_pushfstring(L, "%s: %s", where, buf);
  lua_concat(L, 2);
}

int mrn_lua_error(lua_State *L, const char *where, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  push_message(L, where, fmt, ap);
  va_end(ap);
  return lua_error(L);
}

#define OUTPUT_ERROR_KEY "moraine.output_error"

int mrn_lua_output_error(lua_State *L, const char *where, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  push_message(L, where, fmt, ap);
  va_end(ap);
  mrn_lua_mark_output_error(L, -1);
  return lua_error(L);
}

int mrn_lua_engine_error(lua_State *L, const char *where) {
  if (!where) return luaL_error(L, "%s", mrn_error_message());
  return mrn_lua_error(L, where, "%s", mrn_error_message());
}

int mrn_lua_engine_output_error(lua_State *L, const char *where) {
  return mrn_lua_output_error(L, where, "%s", mrn_error_message());
}

static int late_output_failure;

void mrn_lua_late_output_error(const char *fmt, ...) {
  char message[2048];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(message, sizeof message, fmt, ap);
  va_end(ap);
  mrn_log_error("%s", message);
  late_output_failure = 1;
}

int mrn_lua_take_late_output_failure(void) {
  int failed = late_output_failure;
  late_output_failure = 0;
  return failed;
}

int mrn_lua_is_output_error(lua_State *L, int idx) {
  idx = lua_absindex(L, idx);
  lua_getfield(L, LUA_REGISTRYINDEX, OUTPUT_ERROR_KEY);
  int output = lua_type(L, -1) == LUA_TSTRING && lua_type(L, idx) == LUA_TSTRING && lua_rawequal(L, -1, idx);
  lua_pop(L, 1);
  return output;
}

void mrn_lua_mark_output_error(lua_State *L, int idx) {
  lua_pushvalue(L, idx);
  lua_setfield(L, LUA_REGISTRYINDEX, OUTPUT_ERROR_KEY);
}

int mrn_lua_exit_status(lua_State *L) { return mrn_lua_is_output_error(L, -1) ? MRN_EXIT_OUTPUT : 1; }

static void list_choices(const char *const *choices, char *buf, size_t len) {
  buf[0] = '\0';
  for (int i = 0; choices[i]; i++) {
    size_t used = strlen(buf);
    snprintf(buf + used, len - used, "%s'%s'", i ? ", " : "", choices[i]);
  }
}

void mrn_lua_check_choice(lua_State *L, const char *where, const char *key, const char *value,
                          const char *const *choices) {
  for (int i = 0; choices[i]; i++)
    if (strcmp(choices[i], value) == 0) return;
  char valid[512];
  list_choices(choices, valid, sizeof valid);
  mrn_lua_error(L, where, "%s = '%s' is not valid%s; valid: %s", key, value, mrn_hint(mrn_suggest_from(choices, value)).s,
                valid);
}

static int type_matches(lua_State *L, int idx, mrn_spec_type t) {
  switch (t) {
  case MRN_SPEC_NUMBER: return lua_type(L, idx) == LUA_TNUMBER;
  case MRN_SPEC_INTEGER: return lua_isinteger(L, idx) || (lua_type(L, idx) == LUA_TNUMBER && floor(lua_tonumber(L, idx)) == lua_tonumber(L, idx));
  case MRN_SPEC_BOOLEAN: return lua_type(L, idx) == LUA_TBOOLEAN;
  case MRN_SPEC_STRING: return lua_type(L, idx) == LUA_TSTRING;
  case MRN_SPEC_VECTOR: return lua_type(L, idx) == LUA_TTABLE;
  case MRN_SPEC_TABLE: return lua_type(L, idx) == LUA_TTABLE;
  case MRN_SPEC_FUNCTION: return lua_type(L, idx) == LUA_TFUNCTION;
  case MRN_SPEC_ANY: return 1;
  }
  return 1;
}

void mrn_lua_check_table(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count) {
  idx = lua_absindex(L, idx);
  if (!lua_istable(L, idx))
    mrn_lua_error(L, where, "expected a table of options, got %s", luaL_typename(L, idx));
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    if (lua_type(L, -2) != LUA_TSTRING) {
      lua_pop(L, 2);
      mrn_lua_error(L, where, "options must be named (key = value); found a positional value");
    }
    const char *key = lua_tostring(L, -2);
    const mrn_spec *s = mrn_spec_find(specs, count, key);
    if (!s) {
      const char *hint = mrn_spec_suggest(specs, count, key);
      if (hint) mrn_lua_error(L, where, "unknown key '%s'%s", key, mrn_hint(hint).s);
      char valid[1024] = "";
      for (int i = 0; i < count; i++) {
        size_t used = strlen(valid);
        snprintf(valid + used, sizeof valid - used, "%s%s", i ? ", " : "", specs[i].key);
      }
      mrn_lua_error(L, where, "unknown key '%s' (valid keys: %s)", key, valid);
    }
    if (!type_matches(L, -1, s->type)) {
      if (s->type == MRN_SPEC_INTEGER && lua_type(L, -1) == LUA_TNUMBER)
        mrn_lua_error(L, where, "%s must be a whole number, got %s", key, mrn_num(lua_tonumber(L, -1)).s);
      mrn_lua_error(L, where, "%s must be %s %s, got %s", key,
                    s->type == MRN_SPEC_INTEGER ? "an" : "a", mrn_spec_type_name(s->type), luaL_typename(L, -1));
    }
    lua_pop(L, 1);
  }
  for (int i = 0; i < count; i++) {
    if (!specs[i].required) continue;
    lua_getfield(L, idx, specs[i].key);
    int missing = lua_isnil(L, -1);
    lua_pop(L, 1);
    if (missing) mrn_lua_error(L, where, "missing required key '%s' (%s)", specs[i].key, specs[i].doc);
  }
}

int mrn_lua_has(lua_State *L, int idx, const char *key) {
  lua_getfield(L, idx, key);
  int present = !lua_isnil(L, -1);
  lua_pop(L, 1);
  return present;
}

static const mrn_spec *spec_or_die(lua_State *L, const char *where, const mrn_spec *specs, int count, const char *key) {
  const mrn_spec *s = mrn_spec_find(specs, count, key);
  if (!s) luaL_error(L, "internal error: %s has no spec for '%s'", where, key);
  return s;
}

void mrn_lua_check_number(lua_State *L, const char *where, const mrn_spec *s, const char *name, double v) {
  char expected[160];
  if (mrn_spec_check_range(s, v, expected, sizeof expected))
    mrn_lua_error(L, where, "%s = %s is out of range (expected %s%s%s)", name ? name : s->key, mrn_num(v).s, expected,
                  s->unit && s->unit[0] ? ", in " : "", s->unit && s->unit[0] ? s->unit : "");
}

double mrn_lua_get_number(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count, const char *key) {
  const mrn_spec *s = spec_or_die(L, where, specs, count, key);
  lua_getfield(L, idx, key);
  double v = lua_isnil(L, -1) ? s->def : lua_tonumber(L, -1);
  lua_pop(L, 1);
  mrn_lua_check_number(L, where, s, NULL, v);
  return v;
}

long mrn_lua_get_integer(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count, const char *key) {
  const mrn_spec *s = spec_or_die(L, where, specs, count, key);
  lua_getfield(L, idx, key);
  double v = lua_isnil(L, -1) ? s->def : lua_tonumber(L, -1);
  lua_pop(L, 1);
  mrn_lua_check_number(L, where, s, NULL, v);
  return (long)v;
}

int mrn_lua_get_boolean(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count, const char *key,
                        int def) {
  (void)spec_or_die(L, where, specs, count, key);
  lua_getfield(L, idx, key);
  int v = lua_isnil(L, -1) ? def : lua_toboolean(L, -1);
  lua_pop(L, 1);
  return v;
}

const char *mrn_lua_get_string(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count,
                               const char *key) {
  const mrn_spec *s = spec_or_die(L, where, specs, count, key);
  lua_getfield(L, idx, key);
  /* the string stays alive: it is referenced by the argument table */
  const char *v = lua_isnil(L, -1) ? NULL : lua_tostring(L, -1);
  lua_pop(L, 1);
  if (v && s->choices) mrn_lua_check_choice(L, where, key, v, s->choices);
  return v;
}

void mrn_lua_to_vector(lua_State *L, int idx, const char *where, const mrn_spec *s, int dim, double *out) {
  idx = lua_absindex(L, idx);
  if (!lua_istable(L, idx))
    mrn_lua_error(L, where, "%s must be a table of %d numbers, got %s", s->key, dim, luaL_typename(L, idx));
  lua_Integer len = luaL_len(L, idx);
  if (len != dim)
    mrn_lua_error(L, where, "%s must have %d components (the simulation is %dD), got %lld", s->key, dim, dim,
                  (long long)len);
  for (int d = 0; d < dim; d++) {
    lua_geti(L, idx, d + 1);
    if (lua_type(L, -1) != LUA_TNUMBER)
      mrn_lua_error(L, where, "%s[%d] must be a number, got %s", s->key, d + 1, luaL_typename(L, -1));
    out[d] = lua_tonumber(L, -1);
    lua_pop(L, 1);
    char name[80];
    snprintf(name, sizeof name, "%s[%d]", s->key, d + 1);
    mrn_lua_check_number(L, where, s, name, out[d]);
  }
}

int mrn_lua_get_vector(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count, const char *key,
                       int dim, double *out, int required) {
  const mrn_spec *s = spec_or_die(L, where, specs, count, key);
  lua_getfield(L, idx, key);
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    if (required) mrn_lua_error(L, where, "missing required key '%s' (a table of %d numbers)", key, dim);
    return 0;
  }
  mrn_lua_to_vector(L, -1, where, s, dim, out);
  lua_pop(L, 1);
  return 1;
}

int mrn_lua_no_such(lua_State *L, const char *what, const char *kind, const char *key, const char *const *names) {
  return luaL_error(L, "%s has no %s '%s'%s", what, kind, key, mrn_hint(mrn_suggest_from(names, key)).s);
}

#define STRICT_MAX_NAMES 256

/* __index(t, key) of a strict table; upvalues: what, kind */
static int strict_index(lua_State *L) {
  const char *what = lua_tostring(L, lua_upvalueindex(1)), *kind = lua_tostring(L, lua_upvalueindex(2));
  const char *key = luaL_tolstring(L, 2, NULL);
  /* the table's own names; they stay alive in it while the error is built */
  const char *names[STRICT_MAX_NAMES + 1];
  int n = 0;
  lua_pushnil(L);
  while (n < STRICT_MAX_NAMES && lua_next(L, 1)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) names[n++] = lua_tostring(L, -1);
  }
  names[n] = NULL;
  return mrn_lua_no_such(L, what, kind, key, names);
}

void mrn_lua_strict(lua_State *L, int idx, const char *what, const char *kind) {
  idx = lua_absindex(L, idx);
  lua_createtable(L, 0, 1);
  lua_pushstring(L, what);
  lua_pushstring(L, kind);
  lua_pushcclosure(L, strict_index, 2);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, idx);
}

void mrn_lua_push_weak_table(lua_State *L, const char *name) { mrn_lua_push_weak_table_mode(L, name, "k"); }

void mrn_lua_push_weak_table_mode(lua_State *L, const char *name, const char *mode) {
  if (lua_getfield(L, LUA_REGISTRYINDEX, name) == LUA_TTABLE) return;
  lua_pop(L, 1);
  lua_newtable(L);
  lua_createtable(L, 0, 1);
  lua_pushstring(L, mode);
  lua_setfield(L, -2, "__mode");
  lua_setmetatable(L, -2);
  lua_pushvalue(L, -1);
  lua_setfield(L, LUA_REGISTRYINDEX, name);
}
