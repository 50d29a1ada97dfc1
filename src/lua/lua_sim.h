/* moraine: the simulation object of a deck, shared by the files that make
 * it (lua_sim*.c), one concern each:
 *   lua_sim.c             the userdata, its life (free, __gc) and the method table
 *   lua_sim_config.c      mpm.simulation{...} and the output options
 *   lua_sim_options.c     boundary, scheme, dt and damping: read by
 *                         simulation{} and by the set_*() methods
 *   lua_sim_set.c         the set_*() methods and the velocity constraints
 *   lua_sim_seed.c        add_particles()
 *   lua_sim_source.c      add_source() and source(): inflow sources
 *   lua_sim_run.c         run{}, hook{} and the errors a run raises
 *   lua_sim_query.c       reading the state: time, energy, field, particle, ...
 *   lua_sim_reduce.c      reduce()
 *   lua_sim_checkpoint.c  save(), mpm.load(), import() and the checkpoints
 *                         a stopped run or a signal leaves
 * Not part of the engine's C interface: the engine stays usable without Lua. */
#ifndef MRN_LUA_SIM_H
#define MRN_LUA_SIM_H

#include <stddef.h>

#include "core/spec.h"
#include "io/output.h"
#include "lua/lua_internal.h"
#include "solver/run.h"
#include "solver/simulation.h"

#define MRN_LUA_MAX_HOOKS 32

/* the thermo settings of a simulation or a run (lua_thermo.c) */
typedef struct mrn_lua_thermo {
  long every;
  int ncolumns; /* 0: the default columns */
  int columns[MRN_THERMO_MAX_COLUMNS];
} mrn_lua_thermo;

/* The run{} calls of a simulation, as a checkpoint keeps them so that a
 * resume continues the call it was in (lua_resume.c). */
typedef struct mrn_lua_run_record {
  long index;        /* run{} calls started: the number of the last one, from 1 */
  int active;        /* 1 while that call is under way */
  int cut_short;     /* it stopped inside the hooks or reports of its last state */
  double start_time; /* the state it started from */
  long start_step;
  double time, until; /* its target as the deck gave it (0: not given) */
  long steps;
  long ckpt_every;   /* its checkpoint = {every, wall, keep} */
  double ckpt_wall;
  long ckpt_keep;
} mrn_lua_run_record;

/* the userdata behind a deck's simulation object */
typedef struct sim_box {
  mrn_sim *sim;
  mrn_output out;
  int out_ready;
  mrn_hook hooks[MRN_LUA_MAX_HOOKS];
  mrn_lua_callback *hook_cb[MRN_LUA_MAX_HOOKS];
  int nhooks;
  mrn_lua_thermo thermo;
  int progress;
  char name[64];
  const char *busy; /* "run{}" or "add_particles()" while deck callbacks can run inside it */
  int between_steps; /* 1 while a hook or stop_when of a run is called: the step is over */
  long invalid_step; /* > 0: a run stopped keeping an invalid state (a particle outside the grid) at this step */
  int interrupted;   /* a run stopped on a signal and wrote <name>_interrupted.h5 */
  int summary_record; /* its line of the end-of-run summary (io/summary.h), 0 before its first run */
  mrn_lua_run_record run;
  int resumed;          /* taken from a checkpoint: its next run{} continues the one saved */
  double ckpt_next_wall; /* wall clock of the next checkpoint = {wall} */
  long ckpt_last_step;   /* step of the checkpoint last written or taken */
  mrn_stash taking;      /* a checkpoint's /resume while it is taken (freed with the box if that raises) */
} sim_box;

/* ---- the userdata (lua_sim.c) */

/* the simulation at idx; raises if freed */
sim_box *mrn_lua_sim_check(lua_State *L, int idx);
/* the same, refusing a simulation left on a state its grid cannot hold
 * (what: the call, for the message) */
sim_box *mrn_lua_sim_check_valid(lua_State *L, int idx, const char *what);
/* the same, refused from inside the simulation's own hooks and callbacks */
sim_box *mrn_lua_sim_check_idle(lua_State *L, int idx, const char *what);
/* the same, but let through from a hook of an explicit run (between its
 * steps), where particles may be added */
sim_box *mrn_lua_sim_check_between_steps(lua_State *L, int idx, const char *what);
/* a new simulation userdata with its outputs ready and no engine simulation yet */
sim_box *mrn_lua_sim_push(lua_State *L);
/* the output directory of the deck (-o) */
const char *mrn_lua_output_dir(lua_State *L);
/* a Lua array of the n numbers v */
void mrn_lua_push_vector(lua_State *L, const double *v, int n);
/* The registry table whose weak keys are every simulation userdata: the
 * simulations a signal finds (mrn_lua_save_interrupted) */
#define MRN_LUA_SIMULATIONS "moraine.simulations"

/* ---- readers shared between the files */

/* the simulation's name and the deck's path and text into its HDF5 series'
 * attributes (lua_sim_config.c) */
void mrn_lua_describe_run(lua_State *L, const char *where, sim_box *b);

/* output = {vtk, every, every_steps, fields, format, grid} at idx (lua_sim_config.c) */
void mrn_lua_read_output(lua_State *L, int idx, const char *where, sim_box *b);
/* on_leave = "stop" | "delete" in the table at idx (absent: unchanged) */
void mrn_lua_read_on_leave(lua_State *L, int idx, const char *where, const mrn_spec *specs, int nspecs, mrn_sim *sim);
/* lua_sim_options.c: each applies the value at idx on top of sim's settings */
void mrn_lua_read_boundary(lua_State *L, int idx, const char *where, mrn_sim *sim);
void mrn_lua_read_scheme(lua_State *L, int idx, const char *where, mrn_sim *sim);
void mrn_lua_read_dt(lua_State *L, int idx, const char *where, mrn_sim *sim);
void mrn_lua_read_damping(lua_State *L, int idx, const char *where, mrn_sim *sim);
void mrn_lua_read_split(lua_State *L, int idx, const char *where, mrn_sim *sim);

/* thermo = N or {every, columns} at idx: the keys given change t */
void mrn_lua_read_thermo(lua_State *L, int idx, const char *where, mrn_lua_thermo *t);
/* t as the thermo options of a run */
void mrn_lua_thermo_apply(const mrn_lua_thermo *t, mrn_run_options *opt);

/* When a run stops on an invalid state or a signal, the state it reached is
 * kept: a checkpoint OUTDIR/<name>_<why>.h5, when a VTK series is set a last
 * snapshot, and every CSV and series row on disk. Fills `note` for the
 * message with what was written and what could not be; MRN_ERR_IO when
 * something could not (lua_sim_checkpoint.c). */
int mrn_lua_sim_write_final_state(sim_box *b, const char *why, char *note, size_t len);

/* ---- resuming (lua_resume.c) */

/* the simulation's name, thermo interval, run record and outputs, walked
 * into or out of a stash (io/stash.h) */
void mrn_lua_sim_stash(sim_box *b, mrn_stash *s);
/* a checkpoint of the simulation with what a resume needs (the stash); 0 or MRN_ERR_IO */
int mrn_lua_sim_save(sim_box *b, const char *path);
/* --restart FILE (opt: the registry's plan): before each run{} of a
 * simulation; SKIP for a call the checkpoint is past, HERE when the
 * checkpoint has just been taken into b, NONE otherwise */
enum { MRN_LUA_RESTART_NONE, MRN_LUA_RESTART_SKIP, MRN_LUA_RESTART_HERE };
int mrn_lua_restart_at_run(lua_State *L, sim_box *b, const char *where);
/* read the plan of --restart FILE before the deck runs; raises on a bad file */
void mrn_lua_restart_open(lua_State *L, const char *path);
/* after the deck: an error message when the plan was never carried out, else NULL */
const char *mrn_lua_restart_unfinished(lua_State *L);
/* --overwrite was given */
int mrn_lua_overwrite(lua_State *L);
/* the periodic checkpoints of run{ checkpoint = ... } as an observer of the run */
mrn_run_observer mrn_lua_checkpoint_observer(sim_box *b);

/* ---- the methods, one C function each: sim:NAME is l_sim_NAME */

int l_simulation(lua_State *L); /* mpm.simulation{} */
int l_load(lua_State *L);       /* mpm.load() */
int l_resume(lua_State *L);     /* mpm.resume() */
int l_sim_add_particles(lua_State *L);
int l_sim_run(lua_State *L);
int l_sim_hook(lua_State *L);
int l_sim_set_gravity(lua_State *L);
int l_sim_set_boundary(lua_State *L);
int l_sim_set_scheme(lua_State *L);
int l_sim_set_dt(lua_State *L);
int l_sim_set_damping(lua_State *L);
int l_sim_set_split(lua_State *L);
/* lua_sim_parallel.c: a distributed run */
int l_sim_set_parallel(lua_State *L);
int l_sim_parallel(lua_State *L);
int l_sim_rebalance(lua_State *L);
extern const mrn_spec_group mrn_lua_parallel_group;
extern const mrn_spec_group mrn_lua_field_group; /* field */
int l_sim_split(lua_State *L);
int l_sim_output(lua_State *L);
int l_sim_constrain(lua_State *L);
int l_sim_reaction(lua_State *L);
int l_sim_set_constraint(lua_State *L);
int l_sim_save(lua_State *L);
int l_sim_import(lua_State *L);
int l_sim_dt_estimate(lua_State *L);
int l_sim_write_vtk(lua_State *L);
int l_sim_time(lua_State *L);
int l_sim_step(lua_State *L);
int l_sim_dt(lua_State *L);
int l_sim_particle_count(lua_State *L);
int l_sim_dim(lua_State *L);
int l_sim_energy(lua_State *L);
int l_sim_diagnostics(lua_State *L);
int l_sim_field(lua_State *L);
int l_sim_reduce(lua_State *L);
int l_sim_record(lua_State *L);
int l_sim_particle(lua_State *L);
int l_sim_info(lua_State *L);
/* sim:add_source{} and sim:source(i) into the method table at `methods` (lua_sim_source.c) */
void mrn_lua_add_source_methods(lua_State *L, int methods);

/* ---- the option groups, for --list-options (registered by lua_sim.c in one order) */

extern const mrn_spec_group mrn_lua_simulation_group, mrn_lua_grid_group, mrn_lua_output_group; /* config */
extern const mrn_spec_group mrn_lua_scheme_group, mrn_lua_boundary_group, mrn_lua_face_group; /* options */
extern const mrn_spec_group mrn_lua_dt_group, mrn_lua_damping_group, mrn_lua_split_group;                          /* options */
extern const mrn_spec_group mrn_lua_run_group, mrn_lua_hook_group, mrn_lua_thermo_group;                            /* run */

extern const mrn_spec_group mrn_lua_run_group, mrn_lua_hook_group;                            /* run */
extern const mrn_spec_group mrn_lua_checkpoint_group;                                         /* run */
extern const mrn_spec_group mrn_lua_particle_group;                                           /* seed */
extern const mrn_spec_group mrn_lua_load_group, mrn_lua_import_group;                         /* checkpoint */
extern const mrn_spec_group mrn_lua_constrain_group;                                          /* set */
extern const mrn_spec_group mrn_lua_wall_group;                                               /* wall */
extern const mrn_spec_group mrn_lua_contact_group;                                            /* contact */
extern const mrn_spec_group mrn_lua_reduce_group;                                             /* reduce */

#endif
