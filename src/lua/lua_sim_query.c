/* moraine: the methods that read a simulation's state — time, step, energy,
 * diagnostics, fields, one particle, settings — and write one snapshot or
 * one series value on request. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "io/particle_fields.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"
#include "solver/dist.h"
#include "solver/timestep.h"

/* the critical steps the CFL policies use, without their Courant number */
int l_sim_dt_estimate(lua_State *L) {
  sim_box *b = mrn_lua_sim_check_valid(L, 1, "dt_estimate()");
  lua_createtable(L, 0, 3);
  lua_pushnumber(L, mrn_dt_particle_critical(b->sim));
  lua_setfield(L, -2, "cfl");
  lua_pushnumber(L, mrn_dt_grid_critical(b->sim));
  lua_setfield(L, -2, "grid_cfl");
  lua_pushnumber(L, b->sim->grid.cell * mrn_sim_slowness(b->sim));
  lua_setfield(L, -2, "a_tau");
  return 1;
}

int l_sim_write_vtk(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  if (!b->out.vtk_name) mrn_lua_error(L, "write_vtk()", "no VTK series configured (output{vtk = name})");
  if (mrn_output_claim(&b->out, mrn_lua_overwrite(L)) != MRN_OK) mrn_lua_engine_error(L, "write_vtk()");
  if (mrn_output_write_vtk(&b->out, b->sim) != MRN_OK) mrn_lua_engine_output_error(L, "write_vtk()");
  return 0;
}

/* ------------------------------------------------------- reading state */

int l_sim_time(lua_State *L) { lua_pushnumber(L, mrn_lua_sim_check(L, 1)->sim->time); return 1; }
int l_sim_step(lua_State *L) { lua_pushinteger(L, mrn_lua_sim_check(L, 1)->sim->step); return 1; }
int l_sim_dt(lua_State *L) { lua_pushnumber(L, mrn_lua_sim_check(L, 1)->sim->dt); return 1; }
int l_sim_particle_count(lua_State *L) {
  lua_pushinteger(L, (lua_Integer)mrn_lua_sim_check(L, 1)->sim->particles.n);
  return 1;
}
int l_sim_dim(lua_State *L) { lua_pushinteger(L, mrn_lua_sim_check(L, 1)->sim->dim); return 1; }

int l_sim_energy(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  mrn_diagnostics d;
  mrn_sim_diagnostics(b->sim, &d);
  lua_createtable(L, 0, 6);
  lua_pushnumber(L, d.kinetic); lua_setfield(L, -2, "kinetic");
  lua_pushnumber(L, d.gravity); lua_setfield(L, -2, "gravity");
  lua_pushnumber(L, d.elastic); lua_setfield(L, -2, "elastic");
  lua_pushnumber(L, d.total); lua_setfield(L, -2, "total");
  lua_pushnumber(L, d.plastic); lua_setfield(L, -2, "plastic");
  lua_pushnumber(L, d.friction); lua_setfield(L, -2, "friction");
  lua_pushnumber(L, d.damping); lua_setfield(L, -2, "damping");
  lua_pushnumber(L, d.external); lua_setfield(L, -2, "external");
  lua_pushnumber(L, d.inflow); lua_setfield(L, -2, "inflow");
  lua_pushnumber(L, d.inflow_work); lua_setfield(L, -2, "inflow_work");
  lua_pushnumber(L, d.outflow); lua_setfield(L, -2, "outflow");
  lua_pushnumber(L, d.walls); lua_setfield(L, -2, "walls");
  lua_pushnumber(L, d.bodies); lua_setfield(L, -2, "bodies");
  lua_pushnumber(L, d.bodies_work); lua_setfield(L, -2, "bodies_work");
  lua_pushnumber(L, d.contact); lua_setfield(L, -2, "contact");
  lua_pushnumber(L, d.mpm_error); lua_setfield(L, -2, "mpm_error");
  return 1;
}

int l_sim_diagnostics(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  mrn_diagnostics d;
  mrn_sim_diagnostics(b->sim, &d);
  double values[64];
  mrn_diagnostics_values(&d, values);
  lua_createtable(L, 0, mrn_diagnostics_column_count() + 8);
  for (int i = 0; i < mrn_diagnostics_column_count(); i++) {
    lua_pushnumber(L, values[i]);
    lua_setfield(L, -2, mrn_diagnostics_column_name(i));
  }
  int dim = b->sim->dim;
  mrn_lua_push_vector(L, d.momentum, dim); lua_setfield(L, -2, "momentum");
  mrn_lua_push_vector(L, d.angular, 3); lua_setfield(L, -2, "angular_momentum");
  mrn_lua_push_vector(L, d.com, dim); lua_setfield(L, -2, "center_of_mass");
  mrn_lua_push_vector(L, d.com_velocity, dim); lua_setfield(L, -2, "com_velocity");
  lua_pushnumber(L, b->sim->time); lua_setfield(L, -2, "time");
  lua_pushinteger(L, b->sim->step); lua_setfield(L, -2, "step");
  lua_pushnumber(L, b->sim->dt); lua_setfield(L, -2, "dt");
  mrn_books books; /* summed over the processes (solver/dist.h) */
  mrn_dist_books(b->sim, &books);
  lua_pushinteger(L, (lua_Integer)books.outflow_particles); lua_setfield(L, -2, "outflow_particles");
  lua_pushnumber(L, books.outflow_mass); lua_setfield(L, -2, "outflow_mass");
  lua_pushnumber(L, books.outflow); lua_setfield(L, -2, "energy_outflow");
  lua_pushinteger(L, (lua_Integer)books.inflow_particles); lua_setfield(L, -2, "inflow_particles");
  lua_pushnumber(L, books.inflow_mass); lua_setfield(L, -2, "inflow_mass");
  lua_pushnumber(L, b->sim->mass_scaling); lua_setfield(L, -2, "mass_scaling");
  return 1;
}

/* sim:field(name) -> flat array of n * ncomp values */
static const mrn_spec field_specs[] = {
    {"gather", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL,
     "every particle of a distributed run, in the order of their ids, on every process (collective)", NULL},
};

const mrn_spec_group mrn_lua_field_group = {"field()", field_specs, MRN_COUNT(field_specs)};

/* the values of buf (count values of the field's type) as a new Lua array */
static void push_values(lua_State *L, const mrn_field_ref *f, const void *buf, size_t count) {
  lua_createtable(L, (int)count, 0);
  for (size_t i = 0; i < count; i++) {
    if (f->type == MRN_VTK_FLOAT64) lua_pushnumber(L, ((const double *)buf)[i]);
    else if (f->type == MRN_VTK_INT32) lua_pushinteger(L, ((const int32_t *)buf)[i]);
    else lua_pushinteger(L, ((const int64_t *)buf)[i]);
    lua_rawseti(L, -2, (lua_Integer)i + 1);
  }
}

/* the field of every process's particles in id order: records of the
 * particle's values then its id, gathered (solver/dist.h), then the values
 * alone; leaves the array on the stack */
static void push_gathered(lua_State *L, sim_box *b, const mrn_field_ref *f, const unsigned char *buf) {
  const mrn_particles *ps = &b->sim->particles;
  const size_t vals = (size_t)f->ncomp * (f->type == MRN_VTK_INT32 ? 4 : 8), rec = vals + sizeof(int64_t);
  unsigned char *mine = lua_newuserdatauv(L, ps->n * rec + 1, 0);
  for (size_t p = 0; p < ps->n; p++) {
    memcpy(mine + p * rec, buf + p * vals, vals);
    memcpy(mine + p * rec + vals, ps->id + p, sizeof(int64_t));
  }
  unsigned char *all = NULL;
  size_t total = 0;
  mrn_lua_active = L;
  if (mrn_dist_gather_by_id(b->sim, mine, ps->n, rec, &all, &total) != MRN_OK) mrn_lua_engine_error(L, "field()");
  for (size_t p = 0; p < total; p++) memmove(all + p * vals, all + p * rec, vals);
  lua_pop(L, 1);
  push_values(L, f, all, total * (size_t)f->ncomp);
  free(all);
}

int l_sim_field(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *name = luaL_checkstring(L, 2);
  int gather = 0;
  if (!lua_isnoneornil(L, 3)) {
    mrn_lua_check_table(L, 3, "field()", field_specs, MRN_COUNT(field_specs));
    gather = mrn_lua_get_boolean(L, 3, "field()", field_specs, MRN_COUNT(field_specs), "gather", 0);
  }
  mrn_field_ref f;
  if (!mrn_field_lookup(b->sim, name, &f)) mrn_lua_check_choice(L, "field()", "name", name, mrn_output_field_names());
  size_t n = b->sim->particles.n;
  size_t total = n * f.ncomp;
  void *buf = lua_newuserdatauv(L, (total ? total : 1) * 8, 0);
  mrn_field_fill(b->sim, &f, buf);
  if (gather) push_gathered(L, b, &f, buf);
  else push_values(L, &f, buf, total);
  lua_pushinteger(L, f.ncomp);
  return 2;
}

/* sim:record(name, value): a value for the next row of the HDF5 series */
int l_sim_record(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *name = luaL_checkstring(L, 2);
  double v = luaL_checknumber(L, 3);
  if (!name[0] || strchr(name, '/')) mrn_lua_error(L, "record()", "'%s' is not a valid series name", name);
  if (mrn_output_record(&b->out, b->sim->dim, name, v) != MRN_OK) mrn_lua_engine_output_error(L, "record()");
  return 0;
}

/* sim:particle(i) -> table of one particle's state (1-based index) */
int l_sim_particle(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  lua_Integer i = luaL_checkinteger(L, 2);
  mrn_particles *ps = &b->sim->particles;
  if (i < 1 || (size_t)i > ps->n)
    return luaL_error(L, "particle(): index %I outside 1..%I", (lua_Integer)i, (lua_Integer)ps->n);
  size_t p = (size_t)i - 1;
  int dim = b->sim->dim;
  lua_createtable(L, 0, 8);
  mrn_lua_push_vector(L, ps->x + 3 * p, dim); lua_setfield(L, -2, "x");
  mrn_lua_push_vector(L, ps->v + 3 * p, dim); lua_setfield(L, -2, "v");
  mrn_lua_push_vector(L, ps->stress + 6 * p, 6); lua_setfield(L, -2, "stress");
  mrn_lua_push_vector(L, ps->strain + 6 * p, 6); lua_setfield(L, -2, "strain");
  lua_pushnumber(L, ps->mass[p]); lua_setfield(L, -2, "mass");
  lua_pushnumber(L, mrn_particle_volume(ps, p)); lua_setfield(L, -2, "volume");
  lua_pushinteger(L, ps->id[p]); lua_setfield(L, -2, "id");
  lua_pushinteger(L, ps->material[p] + 1); lua_setfield(L, -2, "material");
  return 1;
}

int l_sim_info(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  mrn_sim *s = b->sim;
  lua_createtable(L, 0, 8);
  lua_pushstring(L, mrn_shape_info_of(s->shape)->name); lua_setfield(L, -2, "shape");
  lua_pushstring(L, mrn_kernel_boundary_names()[s->kernel_boundary]); lua_setfield(L, -2, "shape_boundary");
  lua_pushstring(L, mrn_grid_velocity_names()[s->scheme.grid_velocity]); lua_setfield(L, -2, "grid_velocity");
  lua_pushstring(L, mrn_velocity_update_names()[s->scheme.velocity_update]); lua_setfield(L, -2, "velocity_update");
  lua_pushstring(L, mrn_position_update_names()[s->scheme.position_update]); lua_setfield(L, -2, "position_update");
  lua_pushnumber(L, s->scheme.flip_fraction); lua_setfield(L, -2, "flip_fraction");
  lua_pushinteger(L, s->scheme.xpic_order); lua_setfield(L, -2, "xpic_order");
  lua_pushstring(L, s->scheme.name); lua_setfield(L, -2, "transfer");
  lua_pushstring(L, mrn_stress_update_names()[s->scheme.stress_update]); lua_setfield(L, -2, "stress_update");
  lua_pushstring(L, mrn_volumetric_names()[s->scheme.volumetric]); lua_setfield(L, -2, "volumetric");
  lua_pushstring(L, mrn_holds_names()[s->scheme.holds]); lua_setfield(L, -2, "holds");
  lua_pushnumber(L, s->grid.cell); lua_setfield(L, -2, "cell");
  mrn_lua_push_vector(L, s->grid.origin, s->dim); lua_setfield(L, -2, "origin");
  mrn_lua_push_vector(L, s->grid.size, s->dim); lua_setfield(L, -2, "size");
  mrn_lua_push_vector(L, s->gravity, s->dim); lua_setfield(L, -2, "gravity");
  lua_pushinteger(L, s->sort_every); lua_setfield(L, -2, "sort_every");
  lua_pushstring(L, b->out.dir); lua_setfield(L, -2, "output_dir");
  return 1;
}
