/* moraine: the simulation object of a deck — its userdata, its life and its
 * method table. A thin, checked skin over solver/simulation.h and
 * solver/run.h; the methods live in lua_sim_*.c by concern (lua_sim.h). */
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "io/output.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"

sim_box *mrn_lua_sim_check(lua_State *L, int idx) {
  sim_box *b = luaL_checkudata(L, idx, MRN_LUA_SIM);
  if (!b->sim) luaL_error(L, "simulation has been freed");
  return b;
}

/* the simulation holds a state its grid cannot (see raise_engine_error in lua_sim_run.c) */
sim_box *mrn_lua_sim_check_valid(lua_State *L, int idx, const char *what) {
  sim_box *b = mrn_lua_sim_check(L, idx);
  if (b->invalid_step)
    mrn_lua_error(L, what, "the simulation stopped at step %ld on a state its grid cannot hold (a particle outside "
                  "it); load an earlier checkpoint to go on", b->invalid_step);
  return b;
}

/* The calls that free or reallocate what a running step or seeding uses are
 * refused from inside that simulation's own hooks and callbacks. */
sim_box *mrn_lua_sim_check_idle(lua_State *L, int idx, const char *what) {
  sim_box *b = mrn_lua_sim_check(L, idx);
  if (b->busy)
    mrn_lua_error(L, what, "not allowed inside a hook or callback of this simulation's %s (call it after %s returns)",
                  b->busy, b->busy);
  return b;
}

sim_box *mrn_lua_sim_check_between_steps(lua_State *L, int idx, const char *what) {
  sim_box *b = mrn_lua_sim_check(L, idx);
  if (!b->busy) return b;
  const int hook = b->between_steps && !strcmp(b->busy, "run{}"); /* not inside a seeding a hook started */
  if (hook && b->sim->integrator.step)
    mrn_lua_error(L, what, "not allowed inside a hook of a run of the implicit integrator (call it after run{} returns)");
  if (hook) return b;
  mrn_lua_error(L, what, "not allowed inside a callback of this simulation's %s (a step is under way); particles may be "
                "added from a hook (sim:hook{...}) or stop_when, between steps, or after %s returns", b->busy, b->busy);
  return b;
}

struct mrn_sim *mrn_lua_check_sim(lua_State *L, int idx) { return mrn_lua_sim_check(L, idx)->sim; }

const char *mrn_lua_output_dir(lua_State *L) {
  lua_getfield(L, LUA_REGISTRYINDEX, "moraine.outdir");
  const char *dir = lua_tostring(L, -1);
  lua_pop(L, 1);
  return dir ? dir : "out";
}

/* ------------------------------------------------------- the userdata */

/* Every simulation userdata is a key of this registry table, whose weak keys
 * do not keep one alive: the simulations a signal finds (mrn_lua_save_interrupted). */
static void remember_sim(lua_State *L, int idx) {
  idx = lua_absindex(L, idx);
  mrn_lua_push_weak_table(L, MRN_LUA_SIMULATIONS);
  lua_pushvalue(L, idx);
  lua_pushboolean(L, 1);
  lua_rawset(L, -3);
  lua_pop(L, 1);
}

/* a new simulation userdata with its outputs ready and no engine simulation yet */
sim_box *mrn_lua_sim_push(lua_State *L) {
  sim_box *b = lua_newuserdatauv(L, sizeof *b, 0);
  memset(b, 0, sizeof *b);
  luaL_setmetatable(L, MRN_LUA_SIM);
  remember_sim(L, -1);
  mrn_output_init(&b->out, mrn_lua_output_dir(L));
  b->out_ready = 1;
  b->thermo.every = 100;
  b->progress = 1;
  b->ckpt_last_step = -1;
  return b;
}

void mrn_lua_push_vector(lua_State *L, const double *v, int n) {
  lua_createtable(L, n, 0);
  for (int i = 0; i < n; i++) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

/* ------------------------------------------------------- end of life */

/* free everything; 0, or MRN_ERR_IO when the last outputs (the series'
 * last rewrite, closing the CSV) could not be written */
static int release_sim(lua_State *L) {
  sim_box *b = luaL_checkudata(L, 1, MRN_LUA_SIM);
  /* __gc never comes while running (the run holds the simulation); free() and __close can */
  if (b->busy) mrn_lua_sim_check_idle(L, 1, "free()");
  for (int i = 0; i < b->nhooks; i++) mrn_lua_callback_release(b->hook_cb[i]);
  b->nhooks = 0;
  int rc = b->out_ready ? mrn_output_free(&b->out) : MRN_OK;
  b->out_ready = 0;
  mrn_sim_free(b->sim);
  b->sim = NULL;
  mrn_stash_free(&b->taking);
  return rc;
}

/* sim:free() and the end of a `<close>` variable: a failure is raised */
static int l_sim_free(lua_State *L) {
  if (release_sim(L) != MRN_OK) mrn_lua_engine_output_error(L, "free()");
  return 0;
}

/* the collector, at the latest when the deck ends: nothing can be raised */
static int l_sim_gc(lua_State *L) {
  sim_box *b = luaL_checkudata(L, 1, MRN_LUA_SIM);
  if (release_sim(L) != MRN_OK) mrn_lua_late_output_error("closing simulation '%s': %s", b->name, mrn_error_message());
  return 0;
}

static int l_sim_tostring(lua_State *L) {
  sim_box *b = luaL_checkudata(L, 1, MRN_LUA_SIM);
  if (!b->sim) {
    lua_pushstring(L, "moraine simulation (freed)");
    return 1;
  }
  mrn_sim *s = b->sim;
  char cells[64];
  if (s->dim == 3) snprintf(cells, sizeof cells, "%d x %d x %d", s->grid.ncell[0], s->grid.ncell[1], s->grid.ncell[2]);
  else snprintf(cells, sizeof cells, "%d x %d", s->grid.ncell[0], s->grid.ncell[1]);
  lua_pushfstring(L, "moraine simulation '%s' (%dD, %s cells of %f m, %I particles, %s + %s, step %I, t = %f s)", b->name,
                  s->dim, cells, s->grid.cell, (lua_Integer)s->particles.n, s->scheme.name,
                  mrn_stress_update_names()[s->scheme.stress_update], (lua_Integer)s->step, s->time);
  return 1;
}

/* The method table: sim:NAME is the C function l_sim_NAME, and the
 * metamethod __NAME is l_sim_NAME too, except __close, which is sim:free.
 * The methods of lua_fields.c, lua_loads.c, lua_watchdog.c,
 * lua_sim_source.c, lua_wall.c, lua_contact.c and lua_implicit.c join the table after these. */
static const luaL_Reg methods[] = {
    {"add_particles", l_sim_add_particles},
    {"run", l_sim_run},
    {"hook", l_sim_hook},
    {"set_gravity", l_sim_set_gravity},
    {"set_boundary", l_sim_set_boundary},
    {"set_scheme", l_sim_set_scheme},
    {"set_dt", l_sim_set_dt},
    {"constrain", l_sim_constrain},
    {"reaction", l_sim_reaction},
    {"set_constraint", l_sim_set_constraint},
    {"save", l_sim_save},
    {"import", l_sim_import},
    {"set_damping", l_sim_set_damping},
    {"set_split", l_sim_set_split},
    {"split", l_sim_split},
    {"set_parallel", l_sim_set_parallel},
    {"parallel", l_sim_parallel},
    {"rebalance", l_sim_rebalance},
    {"dt_estimate", l_sim_dt_estimate},
    {"output", l_sim_output},
    {"write_vtk", l_sim_write_vtk},
    {"time", l_sim_time},
    {"step", l_sim_step},
    {"dt", l_sim_dt},
    {"particle_count", l_sim_particle_count},
    {"dim", l_sim_dim},
    {"energy", l_sim_energy},
    {"diagnostics", l_sim_diagnostics},
    {"field", l_sim_field},
    {"reduce", l_sim_reduce},
    {"record", l_sim_record},
    {"particle", l_sim_particle},
    {"info", l_sim_info},
    {"free", l_sim_free},
    {NULL, NULL},
};

static const luaL_Reg meta[] = {
    {"__gc", l_sim_gc},
    {"__close", l_sim_free},
    {"__tostring", l_sim_tostring},
    {NULL, NULL},
};

/* the option groups of the simulation's functions, in the order --list-options prints them */
static const mrn_spec_group *const groups[] = {
    &mrn_lua_simulation_group, &mrn_lua_grid_group, &mrn_lua_scheme_group, &mrn_lua_output_group,
    &mrn_lua_boundary_group,   &mrn_lua_face_group, &mrn_lua_dt_group,     &mrn_lua_damping_group,
    &mrn_lua_split_group,
    &mrn_lua_run_group,        &mrn_lua_thermo_group, &mrn_lua_checkpoint_group, &mrn_lua_hook_group,
    &mrn_lua_particle_group,   &mrn_lua_load_group,
    &mrn_lua_constrain_group,  &mrn_lua_reduce_group, &mrn_lua_import_group, &mrn_lua_wall_group,
    &mrn_lua_contact_group,    &mrn_lua_parallel_group,   &mrn_lua_field_group,
};

void mrn_lua_open_simulation(lua_State *L, int module) {
  luaL_newmetatable(L, MRN_LUA_SIM);
  luaL_setfuncs(L, meta, 0);
  lua_newtable(L);
  luaL_setfuncs(L, methods, 0);
  mrn_lua_add_field_methods(L, lua_gettop(L));
  mrn_lua_add_load_methods(L, lua_gettop(L));
  mrn_lua_add_wall_methods(L, lua_gettop(L));
  mrn_lua_add_contact_methods(L, lua_gettop(L));
  mrn_lua_add_watchdog_methods(L, lua_gettop(L));
  mrn_lua_add_source_methods(L, lua_gettop(L));
  mrn_lua_strict(L, -1, "simulation", "method");
  lua_setfield(L, -2, "__index");
  lua_pop(L, 1);
  lua_pushcfunction(L, l_simulation);
  lua_setfield(L, module, "simulation");
  lua_pushcfunction(L, l_load);
  lua_setfield(L, module, "load");
  lua_pushcfunction(L, l_resume);
  lua_setfield(L, module, "resume");
  for (int i = 0; i < MRN_COUNT(groups); i++)
    mrn_spec_register_group(groups[i]->name, groups[i]->specs, groups[i]->count);
}
