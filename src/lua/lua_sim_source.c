/* moraine: sim:add_source{...} and sim:source(i): inflow sources
 * (solver/source.h) from a deck. */
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"

static const char *const face_choices[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax", NULL};
static const mrn_spec source_specs[] = {
    {"name", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "label, unique in the simulation (default source<N>)", NULL},
    {"region", MRN_SPEC_ANY, 1, 0, 0, 0, 0, 0, NULL, "the inlet: an mpm.box{...} inside the grid", NULL},
    {"material", MRN_SPEC_ANY, 1, 0, 0, 0, 0, 0, NULL, "a material from mpm.material.<model>{...}", NULL},
    {"velocity", MRN_SPEC_ANY, 1, 0, 0, 0, 0, 0, "m/s",
     "inflow velocity, normal to the inflow face: dim numbers, or function(t) returning them", NULL},
    {"face", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "the box's face the material enters through (default: from a constant velocity)", face_choices},
    {"per_axis", MRN_SPEC_INTEGER, 0, 2, 1, 8, 0, 0, "", "particles per cell along each axis (default 2)", NULL},
    {"stress", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "Pa", "the new particles' stress: 6 values (xx,yy,zz,xy,yz,xz)", NULL},
};
#define SOURCE_SPECS source_specs, MRN_COUNT(source_specs)

/* the velocity function of a source: fn(t) -> dim numbers or a table */
static int call_velocity(void *ctx, const mrn_sim *sim, double t, double v[3]) {
  lua_State *L = mrn_lua_active;
  mrn_lua_callback_push(L, ctx);
  lua_pushnumber(L, t);
  const int top = lua_gettop(L) - 2;
  int rc = mrn_lua_callback_pcall(L, 1, LUA_MULTRET);
  if (rc != MRN_OK) return rc;
  v[0] = v[1] = v[2] = 0.0;
  int ok = lua_gettop(L) > top && mrn_lua_read_numbers(L, top + 1, sim->dim, v);
  lua_settop(L, top);
  if (!ok)
    return mrn_error_code(MRN_ERR_HOOK, "source velocity function: expected %d numbers (or a table of them) at t = %g s",
                          sim->dim, t);
  return MRN_OK;
}

/* region = mpm.box{...}: its corners into cfg */
static void read_box(lua_State *L, const char *where, const mrn_sim *sim, mrn_source_config *cfg) {
  lua_getfield(L, 2, "region");
  const mrn_region *r = mrn_lua_check_region(L, -1, where);
  if (r->kind != MRN_REGION_BOX) mrn_lua_error(L, where, "region: the inlet must be an mpm.box{...}");
  if (r->dim && r->dim != sim->dim) mrn_lua_error(L, where, "region: this box is %dD, the simulation is %dD", r->dim, sim->dim);
  memcpy(cfg->lo, r->p0, sizeof cfg->lo);
  memcpy(cfg->hi, r->p1, sizeof cfg->hi);
  lua_pop(L, 1);
}

/* face = "xmin" ..., or the face a constant velocity enters through */
static void read_face(lua_State *L, const char *where, const mrn_sim *sim, mrn_source_config *cfg, int constant) {
  const char *face = mrn_lua_get_string(L, 2, where, SOURCE_SPECS, "face");
  if (face) {
    int k = 0;
    while (strcmp(face_choices[k], face)) k++;
    if (k / 2 >= sim->dim) mrn_lua_error(L, where, "face: there is no face '%s' in %dD", face, sim->dim);
    cfg->axis = k / 2, cfg->side = k % 2;
    return;
  }
  if (!constant) mrn_lua_error(L, where, "face: give the inflow face (e.g. face = \"xmin\") with a velocity function");
  int axis = -1;
  for (int d = 0; d < sim->dim; d++)
    if (cfg->velocity[d] != 0.0) axis = axis < 0 ? d : sim->dim;
  if (axis < 0) mrn_lua_error(L, where, "velocity: the inflow velocity is zero (no flow)");
  if (axis == sim->dim) mrn_lua_error(L, where, "velocity: the inflow velocity must lie along one axis (normal to the inflow face)");
  cfg->axis = axis, cfg->side = cfg->velocity[axis] > 0.0 ? 0 : 1;
}

/* velocity = {...} | function(t): 1 for a function (made the callback last,
 * when nothing can raise any more) */
static int read_velocity(lua_State *L, const char *where, const mrn_sim *sim, mrn_source_config *cfg) {
  lua_getfield(L, 2, "velocity");
  const int fn = lua_type(L, -1) == LUA_TFUNCTION;
  if (!fn && (lua_type(L, -1) != LUA_TTABLE || (int)luaL_len(L, -1) != sim->dim ||
              !mrn_lua_read_numbers(L, -1, sim->dim, cfg->velocity)))
    mrn_lua_error(L, where, "velocity must be a table of %d numbers or a function(t)", sim->dim);
  for (int d = 0; d < 3; d++)
    if (!isfinite(cfg->velocity[d])) mrn_lua_error(L, where, "velocity must be finite");
  lua_pop(L, 1);
  return fn;
}

static void read_stress(lua_State *L, const char *where, mrn_source_config *cfg) {
  if (!mrn_lua_has(L, 2, "stress")) return;
  lua_getfield(L, 2, "stress");
  if (!lua_istable(L, -1) || luaL_len(L, -1) != 6 || !mrn_lua_read_numbers(L, -1, 6, cfg->stress))
    mrn_lua_error(L, where, "stress must be a table of 6 numbers (xx, yy, zz, xy, yz, xz)");
  for (int k = 0; k < 6; k++)
    if (!isfinite(cfg->stress[k])) mrn_lua_error(L, where, "stress must be finite");
  lua_pop(L, 1);
}

static int l_sim_add_source(lua_State *L) {
  const char *where = "add_source{}";
  sim_box *b = mrn_lua_sim_check_idle(L, 1, where);
  mrn_sim *sim = b->sim;
  mrn_lua_check_table(L, 2, where, SOURCE_SPECS);
  mrn_source_config cfg;
  memset(&cfg, 0, sizeof cfg);
  char name[MRN_SOURCE_NAME];
  const char *given = mrn_lua_get_string(L, 2, where, SOURCE_SPECS, "name");
  if (given) snprintf(name, sizeof name, "%s", given);
  else snprintf(name, sizeof name, "source%d", sim->nsources + 1);
  cfg.name = name;
  read_box(L, where, sim, &cfg);
  lua_getfield(L, 2, "material");
  mrn_material *mat = mrn_lua_check_material(L, -1, where);
  lua_pop(L, 1);
  cfg.per_axis = (int)mrn_lua_get_integer(L, 2, where, SOURCE_SPECS, "per_axis");
  read_stress(L, where, &cfg);
  const int fn = read_velocity(L, where, sim, &cfg);
  read_face(L, where, sim, &cfg, !fn);
  cfg.material = mrn_sim_add_material(sim, mat);
  if (cfg.material < 0) mrn_lua_engine_error(L, where);
  mrn_lua_callback *cb = NULL;
  if (fn) {
    lua_getfield(L, 2, "velocity");
    cb = mrn_lua_callback_new(L, -1, "source velocity");
    lua_pop(L, 1);
    cfg.fn = call_velocity, cfg.ctx = cb, cfg.release = mrn_lua_callback_release;
  }
  const int index = mrn_sim_add_source(sim, &cfg);
  if (index < 0) {
    mrn_lua_callback_release(cb);
    mrn_lua_engine_error(L, where);
  }
  lua_pushinteger(L, index + 1);
  return 1;
}

/* the source at argument 2: its number (from 1) or its name */
static const mrn_source *check_source(lua_State *L, const mrn_sim *sim, const char *where) {
  if (lua_type(L, 2) == LUA_TSTRING) {
    for (int k = 0; k < sim->nsources; k++)
      if (!strcmp(sim->sources[k].name, lua_tostring(L, 2))) return &sim->sources[k];
    mrn_lua_error(L, where, "no source named '%s'", lua_tostring(L, 2));
  }
  lua_Integer i = luaL_checkinteger(L, 2);
  if (i < 1 || i > sim->nsources) mrn_lua_error(L, where, "source %d does not exist (%d sources)", (int)i, sim->nsources);
  return &sim->sources[i - 1];
}

static void set_number(lua_State *L, const char *key, double v) {
  lua_pushnumber(L, v);
  lua_setfield(L, -2, key);
}

static int l_sim_source(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const mrn_source *s = check_source(L, b->sim, "source()");
  lua_createtable(L, 0, 12);
  lua_pushstring(L, s->name);
  lua_setfield(L, -2, "name");
  set_number(L, "progress", s->st.progress);
  set_number(L, "mass", s->st.mass);
  set_number(L, "energy", s->st.energy);
  set_number(L, "work", s->st.work);
  set_number(L, "area", s->area);
  set_number(L, "spacing", s->spacing);
  set_number(L, "density", mrn_material_density(b->sim->materials[s->cfg.material]));
  lua_pushinteger(L, s->st.particles);
  lua_setfield(L, -2, "particles");
  lua_pushinteger(L, s->st.layers);
  lua_setfield(L, -2, "layers");
  lua_pushstring(L, face_choices[2 * s->cfg.axis + s->cfg.side]);
  lua_setfield(L, -2, "face");
  mrn_lua_push_vector(L, s->v, b->sim->dim);
  lua_setfield(L, -2, "velocity");
  return 1;
}

void mrn_lua_add_source_methods(lua_State *L, int methods) {
  /* sim:NAME is l_sim_NAME, as in lua_sim.c */
  static const luaL_Reg fns[] = {
      {"add_source", l_sim_add_source},
      {"source", l_sim_source},
      {NULL, NULL},
  };
  lua_pushvalue(L, methods);
  luaL_setfuncs(L, fns, 0);
  lua_pop(L, 1);
  mrn_spec_register_group("add_source{}", SOURCE_SPECS);
}
