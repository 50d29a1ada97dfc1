/* moraine: sim:add_particles(region, {...}): seeding a region with
 * particles and their initial velocity and stress. */
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"
#include "solver/contact.h"
#include "solver/dist.h"
#include "solver/suspicious.h"

static const char *const placement_choices[] = {"gauss", "regular", NULL};
static const mrn_spec particle_specs[] = {
    {"material", MRN_SPEC_ANY, 1, 0, 0, 0, 0, 0, NULL, "a material from mpm.material.<model>{...}", NULL},
    {"per_axis", MRN_SPEC_INTEGER, 0, 2, 1, 8, 0, 0, "", "particles per cell along each axis (default 2)", NULL},
    {"per_cell", MRN_SPEC_INTEGER, 0, 4, 1, 512, 0, 0, "", "particles per cell, a square (2D) or cube (3D) number", NULL},
    {"placement", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "gauss (default) or regular", placement_choices},
    {"velocity", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "m/s", "initial velocity: vector or function(x, y, z)", NULL},
    {"stress", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "Pa", "initial stress: 6 values (xx,yy,zz,xy,yz,xz) or function(x, y, z)", NULL},
    {"body", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "the body the particles belong to, for add_contact (default: \"default\")", NULL},
};

static void init_vector_field(lua_State *L, int idx, const char *where, const char *key, sim_box *b, size_t first,
                              long count, double *field, int stride, int ncomp) {
  idx = lua_absindex(L, idx);
  mrn_particles *ps = &b->sim->particles;
  if (lua_type(L, idx) == LUA_TTABLE) {
    double v[6] = {0};
    if ((int)luaL_len(L, idx) != ncomp || !mrn_lua_read_numbers(L, idx, ncomp, v))
      mrn_lua_error(L, where, "%s must be a table of %d numbers", key, ncomp);
    for (long i = 0; i < count; i++)
      for (int k = 0; k < ncomp; k++) field[(first + i) * stride + k] = v[k];
    return;
  }
  if (lua_type(L, idx) != LUA_TFUNCTION)
    mrn_lua_error(L, where, "%s must be a table of %d numbers or a function(x, y, z), got %s", key, ncomp,
                  luaL_typename(L, idx));
  for (long i = 0; i < count; i++) {
    size_t p = first + i;
    int top = lua_gettop(L);
    lua_pushvalue(L, idx);
    for (int d = 0; d < 3; d++) lua_pushnumber(L, ps->x[3 * p + d]);
    lua_call(L, 3, LUA_MULTRET); /* errors propagate with the deck's location */
    double v[6] = {0};
    if (!mrn_lua_read_numbers(L, top + 1, ncomp, v))
      mrn_lua_error(L, where, "%s function must return %d numbers (or a table of them) at (%g, %g, %g)", key, ncomp,
                    ps->x[3 * p], ps->x[3 * p + 1], ps->x[3 * p + 2]);
    for (int k = 0; k < ncomp; k++) field[p * stride + k] = v[k];
    lua_settop(L, top);
  }
}

/* (sim, options, first, count): initial velocity and stress of new particles */
static int init_particle_fields(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *where = "add_particles()";
  size_t first = (size_t)lua_tointeger(L, 3);
  long count = (long)lua_tointeger(L, 4);
  mrn_particles *ps = &b->sim->particles;
  if (mrn_lua_has(L, 2, "velocity")) {
    lua_getfield(L, 2, "velocity");
    init_vector_field(L, -1, where, "velocity", b, first, count, ps->v, 3, b->sim->dim);
    lua_pop(L, 1);
    /* grad v / C follow at the next run (000 §3.2); particles added during
     * a run start with C = 0, as a source's, and leave the others' alone */
    if (!lua_toboolean(L, 5)) b->sim->affine_pending = 1;
  }
  if (mrn_lua_has(L, 2, "stress")) {
    lua_getfield(L, 2, "stress");
    init_vector_field(L, -1, where, "stress", b, first, count, ps->stress, 6, 6);
    lua_pop(L, 1);
  }
  for (long i = 0; i < count; i++) {
    const double *v = ps->v + 3 * (first + i), *s = ps->stress + 6 * (first + i);
    for (int k = 0; k < 6; k++)
      if (!isfinite(s[k]) || (k < 3 && !isfinite(v[k])))
        mrn_lua_error(L, where, "initial velocity or stress is not finite at (%f, %f, %f)", ps->x[3 * (first + i)],
                      ps->x[3 * (first + i) + 1], ps->x[3 * (first + i) + 2]);
  }
  return 0;
}

int l_sim_add_particles(lua_State *L) {
  const char *where = "add_particles()";
  sim_box *b = mrn_lua_sim_check_between_steps(L, 1, where);
  const char *outer = b->busy; /* "run{}" from a hook between steps, else NULL */
  mrn_region *region = mrn_lua_check_region(L, 2, where);
  mrn_lua_check_table(L, 3, where, particle_specs, MRN_COUNT(particle_specs));
  lua_getfield(L, 3, "material");
  mrn_material *mat = mrn_lua_check_material(L, -1, where);
  lua_pop(L, 1);
  const int dim = b->sim->dim;
  int per_axis = (int)mrn_lua_get_integer(L, 3, where, particle_specs, MRN_COUNT(particle_specs), "per_axis");
  if (mrn_lua_has(L, 3, "per_cell")) {
    if (mrn_lua_has(L, 3, "per_axis")) mrn_lua_error(L, where, "give per_axis or per_cell, not both");
    long per_cell = mrn_lua_get_integer(L, 3, where, particle_specs, MRN_COUNT(particle_specs), "per_cell");
    per_axis = (int)lround(pow((double)per_cell, 1.0 / dim));
    long check = dim == 2 ? (long)per_axis * per_axis : (long)per_axis * per_axis * per_axis;
    if (check != per_cell)
      mrn_lua_error(L, where, "per_cell = %ld is not a %s number (use 1, 4, 9, 16, ... in 2D; 1, 8, 27, ... in 3D)",
                    per_cell, dim == 2 ? "square" : "cube");
  }
  const char *placement = mrn_lua_get_string(L, 3, where, particle_specs, MRN_COUNT(particle_specs), "placement");
  mrn_seed_placement pl = placement && strcmp(placement, "regular") == 0 ? MRN_SEED_REGULAR : MRN_SEED_GAUSS;
  if (region->dim && region->dim != dim)
    mrn_lua_error(L, where, "this region is %dD only, the simulation is %dD", region->dim, dim);
  /* mpm.box{min = {x, y}, max = {x, y}} is flat at z = 0: it holds no seeding point of a 3D grid */
  if (dim == 3 && !(region->hi[2] > region->lo[2]))
    mrn_lua_error(L, where, "the region has no extent along z (z from %g to %g), so it seeds nothing in a 3D "
                  "simulation (a box needs min and max of 3 components)", region->lo[2], region->hi[2]);

  int mat_index = mrn_sim_add_material(b->sim, mat);
  if (mat_index < 0) mrn_lua_engine_error(L, where);
  const char *body_name = mrn_lua_get_string(L, 3, where, particle_specs, MRN_COUNT(particle_specs), "body");
  const int body = body_name ? mrn_sim_body(b->sim, body_name) : 0;
  if (body < 0) mrn_lua_engine_error(L, where);
  size_t first = 0;
  long count = 0;
  mrn_lua_active = L;
  b->busy = where; /* region functions run inside the seeding */
  int seeded = mrn_sim_seed(b->sim, region, mat_index, per_axis, pl, &first, &count);
  b->busy = outer;
  if (seeded != MRN_OK) mrn_lua_engine_error(L, where);
  /* a spread simulation keeps this process's share: judge the whole seeding */
  double total = (double)count;
  mrn_dist_reduce(b->sim, &total, 1, MRN_COMM_SUM);
  if (total == 0) mrn_lua_error(L, where, "the region seeds no particle on this grid (is it inside the domain?)");
  mrn_suspicious_seed(b->sim, per_axis, (long)total);
  mrn_sim_set_body(b->sim, first, (size_t)count, body);

  /* the initial fields call deck functions that may fail: on any error the
   * particles just seeded are removed again, so a caught error leaves the
   * simulation as it was */
  lua_pushcfunction(L, init_particle_fields);
  lua_pushvalue(L, 1);
  lua_pushvalue(L, 3);
  lua_pushinteger(L, (lua_Integer)first);
  lua_pushinteger(L, count);
  lua_pushboolean(L, outer != NULL);
  b->busy = where; /* and so do the velocity and stress functions */
  int status = lua_pcall(L, 5, 0, 0);
  b->busy = outer;
  if (status != LUA_OK) {
    b->sim->particles.n = first;
    mrn_sim_particles_changed(b->sim);
    /* the checks in there name add_particles() but cannot see the deck line: add it */
    const char *msg = lua_tostring(L, -1);
    if (msg && strncmp(msg, where, strlen(where)) == 0) {
      luaL_where(L, 1);
      lua_insert(L, -2);
      lua_concat(L, 2);
    }
    return lua_error(L);
  }
  /* once the energy balance runs, W_MPM books them; before, E_ref takes them in */
  if (b->sim->energy_ref_set) mrn_sim_book_inflow(b->sim, first, (size_t)count);
  lua_pushinteger(L, count);
  return 1;
}

const mrn_spec_group mrn_lua_particle_group = {"add_particles()", particle_specs, MRN_COUNT(particle_specs)};
