/* moraine: shared pieces of the Lua binding. */
#ifndef MRN_LUA_INTERNAL_H
#define MRN_LUA_INTERNAL_H

#include <lauxlib.h>
#include <lua.h>

#include "material/material.h"
#include "particles/region.h"

#define MRN_LUA_SIM "moraine.simulation"
#define MRN_LUA_MATERIAL "moraine.material"
#define MRN_LUA_REGION "moraine.region"
/* registry key of the path of the deck that runs (absent when the module is
 * used without moraine's runner) */
#define MRN_LUA_DECK_KEY "moraine.deck"

/* Engine callbacks into Lua (region predicates, hooks, dt functions) run on
 * the Lua thread that called into the engine; the binding records it here
 * before every such call. */
extern lua_State *mrn_lua_active;

/* A Lua function kept alive in the registry, called from the engine */
typedef struct mrn_lua_callback {
  int ref;
  char where[64]; /* what the function is for, for messages */
} mrn_lua_callback;

/* reference the function at idx; returns a malloc'd callback (free with mrn_lua_callback_release) */
mrn_lua_callback *mrn_lua_callback_new(lua_State *L, int idx, const char *where);
void mrn_lua_callback_release(void *cb);
/* push the function onto the active thread's stack */
void mrn_lua_callback_push(lua_State *L, const mrn_lua_callback *cb);
/* protected call with nargs arguments already pushed after the function;
 * on error the engine error message is set to the Lua message and
 * MRN_ERR_HOOK returned, or MRN_ERR_INTERRUPTED when a signal stopped it */
int mrn_lua_callback_pcall(lua_State *L, int nargs, int nresults);

/* SIGINT and SIGTERM stop the Lua code of L too (lua_interrupt.c): the first
 * signal arms a count hook that raises "interrupted by signal N" at the deck
 * line running. NULL before L is closed: no thread to stop. */
void mrn_lua_watch_interrupts(lua_State *L);
/* After such a signal stopped the deck: writes <name>_interrupted.h5 for each
 * simulation the deck still holds (with particles, not inside a call of its
 * own, not already written by its run) and appends what was written to the
 * message at the top of the stack (lua_sim.c) */
void mrn_lua_save_interrupted(lua_State *L);

void mrn_lua_open_regions(lua_State *L, int module);
void mrn_lua_open_materials(lua_State *L, int module);
void mrn_lua_open_simulation(lua_State *L, int module);
void mrn_lua_open_warnings(lua_State *L, int module);
/* mpm.param (lua_param.c), and the warning, once a deck has ended, about
 * each of the --set NAME=VALUE `sets` whose NAME it never asked for */
int l_param(lua_State *L);
void mrn_lua_warn_unused_sets(lua_State *L, const char *const *sets, int nsets);
/* sim:implicit{...} and the integrator object (lua_implicit.c) */
void mrn_lua_open_implicit(lua_State *L, int module);
/* simulation{ integrator = "implicit", implicit = {...} }: check the options
 * table at opt_idx (0: none, the defaults) and keep it for the simulation at
 * sim_idx; mrn_lua_implicit_prepare makes the integrator from it before the
 * first run (particles are seeded by then) */
void mrn_lua_implicit_configure(lua_State *L, int sim_idx, int opt_idx, const char *where);
void mrn_lua_implicit_prepare(lua_State *L, int sim_idx, const char *where);

mrn_region *mrn_lua_check_region(lua_State *L, int idx, const char *where);
/* the engine simulation of a simulation userdata (raises if freed) */
struct mrn_sim *mrn_lua_check_sim(lua_State *L, int idx);
/* particle_field, value, set_value, set_field, probe (lua_fields.c) into the methods table at idx */
void mrn_lua_add_field_methods(lua_State *L, int methods);
/* point_force, load_factor, clear_forces (lua_loads.c) into the methods table at idx */
void mrn_lua_add_load_methods(lua_State *L, int methods);
/* sim:add_wall, sim:wall, sim:set_wall (lua_wall.c) */
void mrn_lua_add_wall_methods(lua_State *L, int methods);
void mrn_lua_add_contact_methods(lua_State *L, int methods);
/* print(), io.write() and the write method of the terminal's files through
 * the run log, in a state whose standard libraries are open (lua_print.c) */
void mrn_lua_log_prints(lua_State *L);
/* the deck's file writes once, on process 0, in a distributed run
 * (lua_parallel_io.c); mpm.parallel_io */
void mrn_lua_parallel_io_open(lua_State *L);
int mrn_lua_l_parallel_io(lua_State *L);
/* set_watchdog, watchdog (lua_watchdog.c) into the methods table at idx */
void mrn_lua_add_watchdog_methods(lua_State *L, int methods);
/* simulation{ watchdog = {...} | false } and set_watchdog{}: the table or boolean at idx */
void mrn_lua_read_watchdog(lua_State *L, int idx, const char *where, struct mrn_sim *sim);
/* The arguments {region, force | traction} at idx: calls set(ctx, p, f) for
 * every point in the region with its share of the force (a total force split
 * equally, or traction times V0^((dim-1)/dim)); returns how many. Raises on
 * bad arguments, an empty region or a failing set (message named by where). */
struct mrn_sim;
long mrn_lua_point_force_args(lua_State *L, int idx, const struct mrn_sim *sim, const char *where,
                              int (*set)(void *ctx, size_t p, const double f[3]), void *ctx);
/* the load factor at idx of sim:load_factor(f) and imp:load_factor(f): a finite number */
double mrn_lua_check_load_factor(lua_State *L, int idx);
mrn_material *mrn_lua_check_material(lua_State *L, int idx, const char *where);
/* push a material userdata owning m (its reference) */
void mrn_lua_push_material(lua_State *L, mrn_material *m);
/* mpm.material.lua{} into the table of constructors at idx, and mpm.driver{} (lua_material_user.c) */
void mrn_lua_open_user_material(lua_State *L, int materials);
void mrn_lua_open_driver(lua_State *L, int module);
/* A checkpoint holds a Lua material's parameters and history but not its
 * function: each such material of sim is replaced by the deck's Lua
 * material of the same name, when the deck has made one. */
void mrn_lua_rebind_user_materials(lua_State *L, struct mrn_sim *sim, const char *where);

/* read a vector of the simulation's dimension from a function's results or a table at idx */
int mrn_lua_read_numbers(lua_State *L, int idx, int count, double *out);

#endif
