/* moraine: mpm.material.lua{ ... update = function(batch) ... end } — a
 * material whose stress update is a deck's function (material/user.h), and
 * mpm.driver{}, the single-point material driver (material/driver.h) for
 * trying such a function, or any model, along a prescribed path.
 *
 * The function receives one batch of at most 32 points of the material per
 * call, as a table (doc/lua-api.md "User material"):
 *   n, dt                     the number of points and the time step (s)
 *   stress[i][1..6]           in: the start-of-step stress, already rotated
 *                             by the Jaumann spin; out: the new stress (Pa)
 *   dstrain[i][1..6]          the strain increment sym(L) dt
 *   F[i][1..9], J[i], J_old[i] the deformation gradient (row-major) at the
 *                             end of the step, det F after and before
 *   state[i].NAME             in: the history variables; out: their new values
 *   dw_plastic[i]             out (optional): plastic work per unit volume, <= 0
 * Components are xx, yy, zz, xy, yz, xz; shear strains are tensor
 * components; stresses are tension positive. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/tensor.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"
#include "material/driver.h"
#include "material/user.h"
#include "solver/simulation.h"

/* the deck's update function and where it was defined */
typedef struct lua_law {
  mrn_lua_callback *fn;
  char defined[96]; /* "deck.lua:12" */
} lua_law;

static void law_release(void *ctx) {
  lua_law *law = ctx;
  mrn_lua_callback_release(law->fn);
  free(law);
}

static void push_numbers(lua_State *L, const double *v, int count) {
  lua_createtable(L, count, 0);
  for (int k = 0; k < count; k++) {
    lua_pushnumber(L, v[k]);
    lua_rawseti(L, -2, k + 1);
  }
}

/* field `key` of the table at -1: a table holding, per point, what `push` pushes */
#define PER_POINT(L, key, n, push)   \
  do {                               \
    lua_createtable(L, n, 0);        \
    for (int i = 0; i < n; i++) {    \
      push;                          \
      lua_rawseti(L, -2, i + 1);     \
    }                                \
    lua_setfield(L, -2, key);        \
  } while (0)

static void push_batch(lua_State *L, const mrn_material *m, const mrn_material_point *pt, int n) {
  const mrn_material_type *t = m->type;
  lua_createtable(L, 0, 10);
  lua_pushinteger(L, n), lua_setfield(L, -2, "n");
  lua_pushnumber(L, pt[0].dt), lua_setfield(L, -2, "dt");
  PER_POINT(L, "stress", n, push_numbers(L, pt[i].stress, 6));
  PER_POINT(L, "dstrain", n, push_numbers(L, pt[i].dstrain, 6));
  PER_POINT(L, "F", n, push_numbers(L, pt[i].F, 9));
  PER_POINT(L, "J", n, lua_pushnumber(L, pt[i].J));
  PER_POINT(L, "J_old", n, lua_pushnumber(L, pt[i].J_old));
  PER_POINT(L, "dw_plastic", n, lua_pushnumber(L, 0.0));
  lua_createtable(L, n, 0);
  for (int i = 0; i < n; i++) {
    lua_createtable(L, 0, t->nstate);
    for (int s = 0; s < t->nstate; s++) {
      lua_pushnumber(L, pt[i].state[s]);
      lua_setfield(L, -2, t->state_names[s]);
    }
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "state");
}

/* the number at key of the table at idx (field `k` when key is NULL) */
static int read_number(lua_State *L, int idx, const char *key, int k, double *out) {
  int type = key ? lua_getfield(L, idx, key) : lua_geti(L, idx, k);
  int ok = type == LUA_TNUMBER;
  if (ok) *out = lua_tonumber(L, -1);
  lua_pop(L, 1);
  return ok;
}

static int bad_value(const lua_law *law, const mrn_material *m, const char *what) {
  return mrn_error_code(MRN_ERR_HOOK, "%s: material '%s' (lua): the update function left %s, expected a number",
                        law->defined, m->name, what);
}

/* one point's results from the batch table at b */
static int read_point(lua_State *L, int b, const lua_law *law, const mrn_material *m, mrn_material_point *pt, int i) {
  char what[96];
  lua_getfield(L, b, "stress");
  int fine = lua_geti(L, -1, i + 1) == LUA_TTABLE;
  for (int k = 0; k < 6 && fine; k++) {
    fine = read_number(L, -1, NULL, k + 1, &pt->stress[k]);
    if (!fine) snprintf(what, sizeof what, "stress[%d][%d] not a number", i + 1, k + 1);
  }
  if (!fine && lua_type(L, -1) != LUA_TTABLE) snprintf(what, sizeof what, "stress[%d] not a table", i + 1);
  lua_pop(L, 2);
  if (!fine) return bad_value(law, m, what);
  lua_getfield(L, b, "state");
  fine = lua_geti(L, -1, i + 1) == LUA_TTABLE;
  for (int s = 0; s < m->type->nstate && fine; s++) {
    fine = read_number(L, -1, m->type->state_names[s], 0, &pt->state[s]);
    if (!fine) snprintf(what, sizeof what, "state[%d].%s not a number", i + 1, m->type->state_names[s]);
  }
  if (!fine && lua_type(L, -1) != LUA_TTABLE) snprintf(what, sizeof what, "state[%d] not a table", i + 1);
  lua_pop(L, 2);
  if (!fine) return bad_value(law, m, what);
  lua_getfield(L, b, "dw_plastic");
  fine = read_number(L, -1, NULL, i + 1, &pt->dw_plastic);
  lua_pop(L, 1);
  if (!fine) return bad_value(law, m, (snprintf(what, sizeof what, "dw_plastic[%d] not a number", i + 1), what));
  return MRN_OK;
}

/* The law of material/user.h: the deck's function on one batch. Energies:
 * the stress work over the step (000 §5.1.4) less the plastic work the
 * function reports, as the built-in models split them. */
static int law_update(void *ctx, const mrn_material *m, mrn_material_point *pt, int n) {
  const lua_law *law = ctx;
  lua_State *L = mrn_lua_active;
  if (!L) return mrn_error("material '%s' (lua): no Lua state to run its update function in", m->name);
  if (!lua_checkstack(L, 8)) return mrn_error("material '%s' (lua): Lua stack overflow", m->name);
  const int top = lua_gettop(L);
  double old[MRN_MATERIAL_BATCH][6];
  for (int i = 0; i < n; i++) memcpy(old[i], pt[i].stress, sizeof old[i]);
  mrn_lua_callback_push(L, law->fn);
  push_batch(L, m, pt, n);
  lua_pushvalue(L, -1);
  lua_insert(L, top + 1); /* keep the batch below the function to read the results back */
  int rc = mrn_lua_callback_pcall(L, 1, 0);
  if (rc) {
    lua_settop(L, top);
    char message[1536]; /* a copy: the error buffer is rewritten below */
    snprintf(message, sizeof message, "%s", mrn_error_message());
    return mrn_error_code(rc, "%s (in the update function of material '%s', %s)", message, m->name, law->defined);
  }
  for (int i = 0; i < n && !rc; i++) {
    rc = read_point(L, top + 1, law, m, &pt[i], i);
    if (rc) break;
    double mid[6];
    for (int k = 0; k < 6; k++) mid[k] = 0.5 * (old[i][k] + pt[i].stress[k]);
    pt[i].de_elastic = sym_ddot(mid, pt[i].dstrain) + pt[i].dw_plastic;
  }
  lua_settop(L, top);
  return rc;
}

/* ---- mpm.material.lua{} ------------------------------------------------------------- */

static const mrn_spec lua_specs[] = {
    {"name", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "label of the material (default: lua)", NULL},
    {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3", "mass density", NULL},
    {"wave_speed", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "m/s",
     "speed of the fastest elastic wave, for time-step estimates", NULL},
    {"state", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "names of the history variables kept per particle", NULL},
    {"update", MRN_SPEC_FUNCTION, 1, 0, 0, 0, 0, 0, NULL, "function(batch): the stress update", NULL},
};

/* the names of state = {...} at idx into names (at most MRN_USER_MAX_STATE, distinct, non-empty) */
static int read_state_names(lua_State *L, int idx, const char *where, const char **names) {
  int n = (int)luaL_len(L, idx);
  if (n > MRN_USER_MAX_STATE)
    mrn_lua_error(L, where, "state: %d history variables, at most %d", n, MRN_USER_MAX_STATE);
  for (int i = 0; i < n; i++) {
    if (lua_geti(L, idx, i + 1) != LUA_TSTRING)
      mrn_lua_error(L, where, "state[%d] must be a name (a string), got %s", i + 1, luaL_typename(L, -1));
    names[i] = lua_tostring(L, -1);
    lua_pop(L, 1); /* the table keeps the string alive */
    if (!names[i][0] || strlen(names[i]) > 31)
      mrn_lua_error(L, where, "state[%d] = '%s' must have 1 to 31 characters", i + 1, names[i]);
    for (int j = 0; j < i; j++)
      if (!strcmp(names[j], names[i])) mrn_lua_error(L, where, "state[%d] = '%s' is given twice", i + 1, names[i]);
  }
  return n;
}

static void remember(lua_State *L, int idx, const char *name);

static int l_new_lua_material(lua_State *L) {
  const char *where = "material.lua{}";
  mrn_lua_check_table(L, 1, where, lua_specs, MRN_COUNT(lua_specs));
  const char *names[MRN_USER_MAX_STATE];
  int nstate = 0;
  if (lua_getfield(L, 1, "state") == LUA_TTABLE) nstate = read_state_names(L, lua_gettop(L), where, names);
  lua_getfield(L, 1, "update");
  lua_law *law = calloc(1, sizeof *law);
  if (!law) mrn_lua_error(L, where, "out of memory");
  lua_Debug ar;
  lua_pushvalue(L, -1);
  lua_getinfo(L, ">S", &ar);
  snprintf(law->defined, sizeof law->defined, "%s:%d", ar.short_src, ar.linedefined);
  law->fn = mrn_lua_callback_new(L, -1, "material.lua{} update");
  const mrn_user_law user = {law_update, law_release, law};
  mrn_material *m = mrn_material_user_new(nstate, names, &user);
  if (!m) {
    law_release(law);
    mrn_lua_engine_error(L, where);
  }
  mrn_lua_push_material(L, m); /* owns m from here, errors included */
  const char *name = mrn_lua_get_string(L, 1, where, lua_specs, MRN_COUNT(lua_specs), "name");
  if (name) snprintf(m->name, sizeof m->name, "%s", name);
  static const char *const keys[] = {"density", "wave_speed"};
  for (int i = 0; i < 2; i++)
    if (mrn_material_set(m, keys[i], mrn_lua_get_number(L, 1, where, lua_specs, MRN_COUNT(lua_specs), keys[i])))
      mrn_lua_error(L, where, "%s", strchr(mrn_error_message(), ':') + 2);
  if (mrn_material_prepare(m) != MRN_OK) mrn_lua_error(L, where, "%s", strchr(mrn_error_message(), ':') + 2);
  remember(L, -1, m->name);
  return 1;
}

/* registry: the deck's Lua materials by name, weak values */
#define USER_MATERIALS_KEY "moraine.lua_materials"

static void push_user_materials(lua_State *L) { mrn_lua_push_weak_table_mode(L, USER_MATERIALS_KEY, "v"); }

/* the material userdata at idx, under its name */
static void remember(lua_State *L, int idx, const char *name) {
  idx = lua_absindex(L, idx);
  push_user_materials(L);
  lua_pushvalue(L, idx);
  lua_setfield(L, -2, name);
  lua_pop(L, 1);
}

void mrn_lua_rebind_user_materials(lua_State *L, struct mrn_sim *sim, const char *where) {
  for (int i = 0; i < sim->nmaterials; i++) {
    mrn_material *old = sim->materials[i];
    if (!mrn_material_is_user(old) || mrn_material_user_has_law(old)) continue;
    push_user_materials(L);
    if (lua_getfield(L, -1, old->name) == LUA_TUSERDATA) {
      mrn_material *m = mrn_lua_check_material(L, -1, where);
      if (m->type->nstate > sim->particles.state_stride)
        mrn_lua_error(L, where, "material '%s' (lua) keeps %d history variables, the checkpoint %d", m->name,
                      m->type->nstate, sim->particles.state_stride);
      mrn_material_ref(m);
      sim->materials[i] = m;
      mrn_material_unref(old);
    }
    lua_pop(L, 2);
  }
}

void mrn_lua_open_user_material(lua_State *L, int materials) {
  lua_pushcfunction(L, l_new_lua_material);
  lua_setfield(L, materials, "lua");
  mrn_spec_register_group("material.lua{}", lua_specs, MRN_COUNT(lua_specs));
}

/* ---- mpm.driver{} ------------------------------------------------------------------- */

#define MRN_LUA_DRIVER "moraine.driver"

static const mrn_spec driver_specs[] = {
    {"material", MRN_SPEC_ANY, 1, 0, 0, 0, 0, 0, NULL, "the material (mpm.material.<model>{...})", NULL},
    {"stress", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, "Pa", "initial stress {xx, yy, zz, xy, yz, xz}, tension positive",
     NULL},
    {"midpoint", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL,
     "advance F with the mid-point rule, as the explicit step does (default true)", NULL},
};

static mrn_driver *check_driver(lua_State *L) { return luaL_checkudata(L, 1, MRN_LUA_DRIVER); }

/* the number at idx, finite */
static double finite_arg(lua_State *L, int idx, const char *what) {
  double v = luaL_checknumber(L, idx);
  if (!isfinite(v)) luaL_error(L, "driver: %s must be finite, got %s", what, mrn_num(v).s);
  return v;
}

static void read_table(lua_State *L, int idx, int count, double *out, const char *what) {
  luaL_checktype(L, idx, LUA_TTABLE);
  if (!mrn_lua_read_numbers(L, idx, count, out)) luaL_error(L, "driver: %s must hold %d numbers", what, count);
}

static int l_driver_new(lua_State *L) {
  const char *where = "driver{}";
  mrn_lua_check_table(L, 1, where, driver_specs, MRN_COUNT(driver_specs));
  lua_getfield(L, 1, "material");
  mrn_material *m = mrn_lua_check_material(L, -1, where);
  double stress[6] = {0};
  if (lua_getfield(L, 1, "stress") == LUA_TTABLE && !mrn_lua_read_numbers(L, -1, 6, stress))
    mrn_lua_error(L, where, "stress must hold 6 numbers {xx, yy, zz, xy, yz, xz}");
  lua_pop(L, 1);
  mrn_driver *d = lua_newuserdatauv(L, sizeof *d, 1);
  lua_pushvalue(L, -2);
  lua_setiuservalue(L, -2, 1); /* the driver keeps its material alive */
  luaL_setmetatable(L, MRN_LUA_DRIVER);
  if (mrn_driver_init(d, m, stress) != MRN_OK) mrn_lua_engine_error(L, where);
  d->kinematics = mrn_lua_get_boolean(L, 1, where, driver_specs, MRN_COUNT(driver_specs), "midpoint", 1)
                      ? MRN_DRIVER_F_MIDPOINT
                      : MRN_DRIVER_F_EULER;
  return 1;
}

/* record the deck's thread for a Lua material's update during a driver
 * call; returns the one to restore in driver_done */
static lua_State *driver_begin(lua_State *L) {
  lua_State *previous = mrn_lua_active;
  mrn_lua_active = L;
  return previous;
}

/* the end of a driver call: the thread restored, an error raised */
static int driver_done(lua_State *L, lua_State *previous, int rc) {
  mrn_lua_active = previous;
  if (rc == MRN_ERR_HOOK) {
    lua_pushstring(L, mrn_error_message());
    return lua_error(L);
  }
  if (rc) mrn_lua_engine_error(L, NULL);
  lua_settop(L, 1);
  return 1;
}

/* d:step(L, dt): L the velocity gradient {9 numbers, row-major} (1/s) */
static int l_driver_step(lua_State *L) {
  mrn_driver *d = check_driver(L);
  double grad[9];
  read_table(L, 2, 9, grad, "L");
  double dt = finite_arg(L, 3, "dt");
  lua_State *previous = driver_begin(L);
  return driver_done(L, previous, mrn_driver_step(d, grad, dt));
}

/* d:increment(deps, dt): a strain increment {xx, yy, zz, xy, yz, xz} without spin */
static int l_driver_strain(lua_State *L) {
  mrn_driver *d = check_driver(L);
  double de[6];
  read_table(L, 2, 6, de, "deps");
  double dt = finite_arg(L, 3, "dt");
  lua_State *previous = driver_begin(L);
  return driver_done(L, previous, mrn_driver_strain(d, de, dt));
}

/* d:triaxial(rate, lateral, dt) and d:simple_shear(rate, normal, dt) (normal nil: constant volume) */
static int l_driver_triaxial(lua_State *L) {
  mrn_driver *d = check_driver(L);
  double rate = finite_arg(L, 2, "rate"), lateral = finite_arg(L, 3, "lateral"), dt = finite_arg(L, 4, "dt");
  lua_State *previous = driver_begin(L);
  return driver_done(L, previous, mrn_driver_triaxial(d, rate, lateral, dt));
}

static int l_driver_simple_shear(lua_State *L) {
  mrn_driver *d = check_driver(L);
  double rate = finite_arg(L, 2, "rate"), dt = finite_arg(L, 4, "dt");
  double normal = lua_isnil(L, 3) ? NAN : finite_arg(L, 3, "normal");
  lua_State *previous = driver_begin(L);
  return driver_done(L, previous, mrn_driver_simple_shear(d, rate, normal, dt));
}

/* d.stress, d.strain, d.F, d.state (by name), d.time, d.e_elastic, d.w_plastic */
static int l_driver_index(lua_State *L) {
  mrn_driver *d = check_driver(L);
  const char *key = luaL_checkstring(L, 2);
  if (!strcmp(key, "stress")) push_numbers(L, d->stress, 6);
  else if (!strcmp(key, "strain")) push_numbers(L, d->strain, 6);
  else if (!strcmp(key, "F")) push_numbers(L, d->F, 9);
  else if (!strcmp(key, "time")) lua_pushnumber(L, d->time);
  else if (!strcmp(key, "e_elastic")) lua_pushnumber(L, d->e_elastic);
  else if (!strcmp(key, "w_plastic")) lua_pushnumber(L, d->w_plastic);
  else if (!strcmp(key, "state")) {
    const mrn_material_type *t = d->mat->type;
    lua_createtable(L, 0, t->nstate);
    for (int s = 0; s < t->nstate; s++) lua_pushnumber(L, d->state[s]), lua_setfield(L, -2, t->state_names[s]);
  } else {
    lua_getmetatable(L, 1);
    if (lua_getfield(L, -1, key) != LUA_TFUNCTION) {
      static const char *const names[] = {"stress", "strain", "F", "state", "time", "e_elastic", "w_plastic",
                                          "step", "increment", "triaxial", "simple_shear", NULL};
      return mrn_lua_no_such(L, "driver", "field", key, names);
    }
  }
  return 1;
}

void mrn_lua_open_driver(lua_State *L, int module) {
  luaL_newmetatable(L, MRN_LUA_DRIVER);
  static const luaL_Reg methods[] = {
      {"step", l_driver_step},          {"increment", l_driver_strain}, {"triaxial", l_driver_triaxial},
      {"simple_shear", l_driver_simple_shear}, {"__index", l_driver_index}, {NULL, NULL},
  };
  luaL_setfuncs(L, methods, 0);
  lua_pop(L, 1);
  lua_pushcfunction(L, l_driver_new);
  lua_setfield(L, module, "driver");
  mrn_spec_register_group("driver{}", driver_specs, MRN_COUNT(driver_specs));
}
