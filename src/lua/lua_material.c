/* moraine: materials in decks — mpm.material.<model>{ parameters }.
 * The constructors are generated from the material registry, so a new model
 * file needs no binding code. */
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"

typedef struct material_box {
  mrn_material *m;
} material_box;

mrn_material *mrn_lua_check_material(lua_State *L, int idx, const char *where) {
  material_box *b = luaL_testudata(L, idx, MRN_LUA_MATERIAL);
  if (!b) mrn_lua_error(L, where, "expected a material (mpm.material.<model>{...}), got %s", luaL_typename(L, idx));
  return b->m;
}

void mrn_lua_push_material(lua_State *L, mrn_material *m) {
  material_box *b = lua_newuserdatauv(L, sizeof *b, 0);
  b->m = m;
  luaL_setmetatable(L, MRN_LUA_MATERIAL);
}

static int l_new_material(lua_State *L) {
  const mrn_material_type *type = lua_touserdata(L, lua_upvalueindex(1));
  char where[96];
  snprintf(where, sizeof where, "material.%s{}", type->name);
  if (!lua_istable(L, 1)) mrn_lua_error(L, where, "expected a table of parameters, got %s", luaL_typename(L, 1));
  material_box *b = lua_newuserdatauv(L, sizeof *b, 0);
  b->m = NULL;
  luaL_setmetatable(L, MRN_LUA_MATERIAL);
  b->m = mrn_material_new(type);
  if (!b->m) mrn_lua_engine_error(L, where);
  lua_pushnil(L);
  while (lua_next(L, 1)) {
    if (lua_type(L, -2) != LUA_TSTRING) mrn_lua_error(L, where, "parameters must be named (key = value)");
    const char *key = lua_tostring(L, -2);
    if (strcmp(key, "name") == 0) {
      if (lua_type(L, -1) != LUA_TSTRING) mrn_lua_error(L, where, "name must be a string, got %s", luaL_typename(L, -1));
      snprintf(b->m->name, sizeof b->m->name, "%s", lua_tostring(L, -1));
    } else {
      const mrn_spec *s = mrn_spec_find(type->params, type->nparams, key);
      if (s && lua_type(L, -1) != LUA_TNUMBER)
        mrn_lua_error(L, where, "%s must be a number (%s, %s), got %s", key, s->doc, s->unit, luaL_typename(L, -1));
      /* mrn_material_set reports unknown keys (with a suggestion) and ranges */
      if (mrn_material_set(b->m, key, lua_tonumber(L, -1)) != MRN_OK)
        mrn_lua_error(L, where, "%s", strchr(mrn_error_message(), ':') + 2);
    }
    lua_pop(L, 1);
  }
  if (mrn_material_prepare(b->m) != MRN_OK) mrn_lua_error(L, where, "%s", strchr(mrn_error_message(), ':') + 2);
  return 1;
}

static int l_material_gc(lua_State *L) {
  material_box *b = luaL_checkudata(L, 1, MRN_LUA_MATERIAL);
  mrn_material_unref(b->m);
  b->m = NULL;
  return 0;
}

static int l_material_tostring(lua_State *L) {
  mrn_material *m = mrn_lua_check_material(L, 1, "tostring");
  luaL_Buffer buf;
  luaL_buffinit(L, &buf);
  lua_pushfstring(L, "moraine material '%s' (%s:", m->name, m->type->name);
  luaL_addvalue(&buf);
  for (int i = 0; i < m->type->nparams; i++) {
    char item[96];
    snprintf(item, sizeof item, " %s=%g", m->type->params[i].key, m->param[i]);
    luaL_addstring(&buf, item);
  }
  luaL_addstring(&buf, ")");
  luaL_pushresult(&buf);
  return 1;
}

/* material.param("E") */
static int l_material_index(lua_State *L) {
  mrn_material *m = mrn_lua_check_material(L, 1, "material");
  const char *key = luaL_checkstring(L, 2);
  if (strcmp(key, "name") == 0) {
    lua_pushstring(L, m->name);
    return 1;
  }
  if (strcmp(key, "model") == 0) {
    lua_pushstring(L, m->type->name);
    return 1;
  }
  const mrn_spec *s = mrn_spec_find(m->type->params, m->type->nparams, key);
  if (!s) {
    const char *names[MRN_MATERIAL_MAX_PARAMS + 3] = {"name", "model"};
    for (int i = 0; i < m->type->nparams && i < MRN_MATERIAL_MAX_PARAMS; i++) names[i + 2] = m->type->params[i].key;
    char what[96];
    snprintf(what, sizeof what, "material %s", m->type->name);
    return mrn_lua_no_such(L, what, "parameter", key, names);
  }
  lua_pushnumber(L, m->param[s - m->type->params]);
  return 1;
}

void mrn_lua_open_materials(lua_State *L, int module) {
  luaL_newmetatable(L, MRN_LUA_MATERIAL);
  /* the metamethod __NAME is l_material_NAME; every mpm.material.<model> is l_new_material */
  static const luaL_Reg meta[] = {
      {"__gc", l_material_gc},
      {"__tostring", l_material_tostring},
      {"__index", l_material_index},
      {NULL, NULL},
  };
  luaL_setfuncs(L, meta, 0);
  lua_pop(L, 1);

  lua_newtable(L);
  for (int i = 0; i < mrn_material_type_count(); i++) {
    const mrn_material_type *t = mrn_material_type_at(i);
    if (t == &mrn_material_user) continue; /* its constructor takes a function (lua_material_user.c) */
    lua_pushlightuserdata(L, (void *)t);
    lua_pushcclosure(L, l_new_material, 1);
    lua_setfield(L, -2, t->name);
    static char groups[64][96]; /* the registry keeps the names for the life of the process */
    if (i < 64) {
      snprintf(groups[i], sizeof groups[i], "material.%s{}", t->name);
      mrn_spec_register_group(groups[i], t->params, t->nparams);
    }
  }
  mrn_lua_open_user_material(L, lua_gettop(L));
  mrn_lua_strict(L, -1, "mpm.material", "model");
  lua_setfield(L, module, "material");
}
