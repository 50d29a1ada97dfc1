/* moraine: regions in decks — mpm.box, mpm.disk/sphere, mpm.cylinder,
 * mpm.polygon, mpm.region(predicate) and their combinations
 * (mpm.union / mpm.difference / mpm.intersection, or a + b, a - b, a * b). */
#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"

typedef struct region_box {
  mrn_region *r;
} region_box;

static void push_region(lua_State *L, mrn_region *r, const char *where) {
  if (!r) mrn_lua_engine_error(L, where);
  region_box *b = lua_newuserdatauv(L, sizeof *b, 0);
  b->r = r;
  luaL_setmetatable(L, MRN_LUA_REGION);
}

mrn_region *mrn_lua_check_region(lua_State *L, int idx, const char *where) {
  region_box *b = luaL_testudata(L, idx, MRN_LUA_REGION);
  if (!b) mrn_lua_error(L, where, "expected a region (mpm.box{...}, mpm.disk{...}, ...), got %s", luaL_typename(L, idx));
  return b->r;
}

/* read a point of 2 or 3 numbers; z = 0 when absent */
static void get_point(lua_State *L, int idx, const char *where, const mrn_spec *specs, int count, const char *key,
                      double out[3]) {
  out[0] = out[1] = out[2] = 0.0;
  lua_getfield(L, idx, key);
  int present = !lua_isnil(L, -1);
  int n = present && lua_istable(L, -1) ? (int)luaL_len(L, -1) : 0;
  lua_pop(L, 1);
  if (!present) mrn_lua_error(L, where, "missing required key '%s' (a point {x, y} or {x, y, z})", key);
  if (n != 2 && n != 3) mrn_lua_error(L, where, "%s must be a point {x, y} or {x, y, z}", key);
  mrn_lua_get_vector(L, idx, where, specs, count, key, n, out, 1);
}

static const mrn_spec box_specs[] = {
    {"min", MRN_SPEC_VECTOR, 1, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "lower corner", NULL},
    {"max", MRN_SPEC_VECTOR, 1, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "upper corner", NULL},
};

static int l_box(lua_State *L) {
  const char *where = "box{}";
  mrn_lua_check_table(L, 1, where, box_specs, MRN_COUNT(box_specs));
  double lo[3], hi[3];
  get_point(L, 1, where, box_specs, MRN_COUNT(box_specs), "min", lo);
  get_point(L, 1, where, box_specs, MRN_COUNT(box_specs), "max", hi);
  push_region(L, mrn_region_box(lo, hi), where);
  return 1;
}

static const mrn_spec sphere_specs[] = {
    {"center", MRN_SPEC_VECTOR, 1, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "centre", NULL},
    {"radius", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "m", "radius", NULL},
};

static int l_sphere(lua_State *L) {
  const char *where = lua_tostring(L, lua_upvalueindex(1));
  mrn_lua_check_table(L, 1, where, sphere_specs, MRN_COUNT(sphere_specs));
  double c[3];
  get_point(L, 1, where, sphere_specs, MRN_COUNT(sphere_specs), "center", c);
  double r = mrn_lua_get_number(L, 1, where, sphere_specs, MRN_COUNT(sphere_specs), "radius");
  push_region(L, mrn_region_sphere(c, r), where);
  return 1;
}

static const mrn_spec cylinder_specs[] = {
    {"from", MRN_SPEC_VECTOR, 1, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "centre of one end of the axis", NULL},
    {"to", MRN_SPEC_VECTOR, 1, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "centre of the other end", NULL},
    {"radius", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "m", "radius", NULL},
};

static int l_cylinder(lua_State *L) {
  const char *where = "cylinder{}";
  mrn_lua_check_table(L, 1, where, cylinder_specs, MRN_COUNT(cylinder_specs));
  double a[3], b[3];
  get_point(L, 1, where, cylinder_specs, MRN_COUNT(cylinder_specs), "from", a);
  get_point(L, 1, where, cylinder_specs, MRN_COUNT(cylinder_specs), "to", b);
  double r = mrn_lua_get_number(L, 1, where, cylinder_specs, MRN_COUNT(cylinder_specs), "radius");
  push_region(L, mrn_region_cylinder(a, b, r), where);
  return 1;
}

static const mrn_spec polygon_specs[] = {
    {"vertices", MRN_SPEC_TABLE, 1, 0, 0, 0, 0, 0, NULL, "list of {x, y} points", NULL},
};

static int l_polygon(lua_State *L) {
  const char *where = "polygon{}";
  mrn_lua_check_table(L, 1, where, polygon_specs, MRN_COUNT(polygon_specs));
  lua_getfield(L, 1, "vertices");
  int n = (int)luaL_len(L, -1);
  if (n < 3) mrn_lua_error(L, where, "vertices must list at least 3 points, got %d", n);
  double *xy = lua_newuserdatauv(L, sizeof(double) * 2 * n, 0); /* freed by the GC even on error */
  for (int i = 0; i < n; i++) {
    lua_geti(L, -2, i + 1);
    if (!lua_istable(L, -1) || !mrn_lua_read_numbers(L, -1, 2, xy + 2 * i))
      mrn_lua_error(L, where, "vertices[%d] must be a point {x, y}", i + 1);
    lua_pop(L, 1);
  }
  mrn_region *r = mrn_region_polygon(xy, n);
  lua_pop(L, 2);
  push_region(L, r, where);
  return 1;
}

/* a Lua predicate function(x, y, z) -> boolean */
static int call_predicate(void *ctx, const double x[3]) {
  lua_State *L = mrn_lua_active;
  mrn_lua_callback_push(L, ctx);
  for (int d = 0; d < 3; d++) lua_pushnumber(L, x[d]);
  if (mrn_lua_callback_pcall(L, 3, 1) != MRN_OK) return -1;
  int inside = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return inside;
}

static int l_region(lua_State *L) {
  luaL_checktype(L, 1, LUA_TFUNCTION);
  mrn_lua_callback *cb = mrn_lua_callback_new(L, 1, "region predicate");
  mrn_region *r = mrn_region_predicate_new(call_predicate, cb, mrn_lua_callback_release);
  if (!r) mrn_lua_callback_release(cb);
  push_region(L, r, "region()");
  return 1;
}

/* The regions at stack indices lo..hi combined as a balanced tree, so that
 * n regions nest about log2(n) deep instead of n (MRN_REGION_MAX_DEPTH);
 * union and intersection are associative, and their operands are still
 * tested from the first. A new reference, or NULL with the message set. */
static mrn_region *combine_range(lua_State *L, mrn_region_kind kind, int lo, int hi) {
  if (lo == hi) {
    mrn_region *r = ((region_box *)lua_touserdata(L, lo))->r;
    mrn_region_ref(r);
    return r;
  }
  int mid = lo + (hi - lo) / 2;
  mrn_region *a = combine_range(L, kind, lo, mid);
  mrn_region *b = a ? combine_range(L, kind, mid + 1, hi) : NULL;
  mrn_region *c = b ? mrn_region_combine(kind, a, b) : NULL;
  mrn_region_unref(a);
  mrn_region_unref(b);
  return c;
}

static int combine(lua_State *L, mrn_region_kind kind, const char *where) {
  int n = lua_gettop(L);
  if (n < 2) mrn_lua_error(L, where, "expected at least two regions, got %d", n);
  /* every argument is checked before any reference is taken: an error
   * raised half-way through would leak the partial combination */
  for (int i = 1; i <= n; i++) mrn_lua_check_region(L, i, where);
  mrn_region *r;
  if (kind == MRN_REGION_DIFFERENCE) { /* a - b - c ... is a - (b + c + ...) */
    mrn_region *rest = combine_range(L, MRN_REGION_UNION, 2, n);
    r = rest ? mrn_region_combine(kind, mrn_lua_check_region(L, 1, where), rest) : NULL;
    mrn_region_unref(rest);
  } else {
    r = combine_range(L, kind, 1, n);
  }
  push_region(L, r, where); /* raises the message when r is NULL */
  return 1;
}

static int l_union(lua_State *L) { return combine(L, MRN_REGION_UNION, "union()"); }
static int l_difference(lua_State *L) { return combine(L, MRN_REGION_DIFFERENCE, "difference()"); }
static int l_intersection(lua_State *L) { return combine(L, MRN_REGION_INTERSECTION, "intersection()"); }

static int l_region_contains(lua_State *L) {
  mrn_region *r = mrn_lua_check_region(L, 1, "region:contains()");
  double x[3] = {luaL_checknumber(L, 2), luaL_checknumber(L, 3), luaL_optnumber(L, 4, 0.0)};
  mrn_lua_active = L;
  int in = mrn_region_contains(r, x);
  if (in < 0) return mrn_lua_engine_error(L, NULL);
  lua_pushboolean(L, in);
  return 1;
}

static int l_region_gc(lua_State *L) {
  region_box *b = luaL_checkudata(L, 1, MRN_LUA_REGION);
  mrn_region_unref(b->r);
  b->r = NULL;
  return 0;
}

static int l_region_tostring(lua_State *L) {
  static const char *kinds[] = {"box", "sphere", "cylinder", "polygon", "union", "intersection", "difference", "predicate"};
  mrn_region *r = mrn_lua_check_region(L, 1, "tostring");
  lua_pushfstring(L, "moraine region (%s)", kinds[r->kind]);
  return 1;
}

void mrn_lua_open_regions(lua_State *L, int module) {
  luaL_newmetatable(L, MRN_LUA_REGION);
  /* mpm.NAME is l_NAME, region:NAME and the metamethod __NAME are
   * l_region_NAME; the operators + - * are mpm.union, mpm.difference and
   * mpm.intersection, and mpm.disk and mpm.sphere are both l_sphere (the
   * upvalue names the function in messages) */
  static const luaL_Reg meta[] = {
      {"__gc", l_region_gc},
      {"__tostring", l_region_tostring},
      {"__add", l_union},
      {"__sub", l_difference},
      {"__mul", l_intersection},
      {NULL, NULL},
  };
  luaL_setfuncs(L, meta, 0);
  lua_newtable(L);
  lua_pushcfunction(L, l_region_contains);
  lua_setfield(L, -2, "contains");
  mrn_lua_strict(L, -1, "region", "method");
  lua_setfield(L, -2, "__index");
  lua_pop(L, 1);

  static const luaL_Reg fns[] = {
      {"box", l_box},
      {"cylinder", l_cylinder},
      {"polygon", l_polygon},
      {"region", l_region},
      {"union", l_union},
      {"difference", l_difference},
      {"intersection", l_intersection},
      {NULL, NULL},
  };
  lua_pushvalue(L, module);
  luaL_setfuncs(L, fns, 0);
  lua_pushstring(L, "disk{}");
  lua_pushcclosure(L, l_sphere, 1);
  lua_setfield(L, -2, "disk");
  lua_pushstring(L, "sphere{}");
  lua_pushcclosure(L, l_sphere, 1);
  lua_setfield(L, -2, "sphere");
  lua_pop(L, 1);
  mrn_spec_register_group("box{}", box_specs, MRN_COUNT(box_specs));
  mrn_spec_register_group("disk{} / sphere{}", sphere_specs, MRN_COUNT(sphere_specs));
  mrn_spec_register_group("cylinder{}", cylinder_specs, MRN_COUNT(cylinder_specs));
  mrn_spec_register_group("polygon{}", polygon_specs, MRN_COUNT(polygon_specs));
}
