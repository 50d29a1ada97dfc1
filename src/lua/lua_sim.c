/* moraine: the simulation object of a deck — mpm.simulation{...} and its
 * methods. A thin, checked skin over solver/simulation.h and solver/run.h. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/error.h"
#include "core/log.h"
#include "io/atomic_file.h"
#include "core/tensor.h"
#include "io/checkpoint.h"
#include "io/particle_fields.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"
#include "lua/lua_safe.h"
#include "solver/run.h"
#include "solver/simulation.h"
#include "solver/suspicious.h"
#include "transfer/blocks.h"

#define MAX_HOOKS 32

typedef struct sim_box {
  mrn_sim *sim;
  mrn_output out;
  int out_ready;
  mrn_hook hooks[MAX_HOOKS];
  mrn_lua_callback *hook_cb[MAX_HOOKS];
  int nhooks;
  long thermo_every;
  int progress;
  char name[64];
  const char *busy; /* "run{}" or "add_particles()" while deck callbacks can run inside it */
  long invalid_step; /* > 0: a run stopped keeping an invalid state (a particle outside the grid) at this step */
  int interrupted;   /* a run stopped on a signal and wrote <name>_interrupted.h5 */
} sim_box;

static sim_box *check_sim(lua_State *L, int idx) {
  sim_box *b = luaL_checkudata(L, idx, MRN_LUA_SIM);
  if (!b->sim) luaL_error(L, "simulation has been freed");
  return b;
}

/* the simulation holds a state its grid cannot (see raise_engine_error) */
static sim_box *check_valid(lua_State *L, int idx, const char *what) {
  sim_box *b = check_sim(L, idx);
  if (b->invalid_step)
    mrn_lua_error(L, what, "the simulation stopped at step %ld on a state its grid cannot hold (a particle outside "
                  "it); load an earlier checkpoint to go on", b->invalid_step);
  return b;
}

/* The calls that free or reallocate what a running step or seeding uses are
 * refused from inside that simulation's own hooks and callbacks. */
static sim_box *check_idle(lua_State *L, int idx, const char *what) {
  sim_box *b = check_sim(L, idx);
  if (b->busy)
    mrn_lua_error(L, what, "not allowed inside a hook or callback of this simulation's %s (call it after %s returns)",
                  b->busy, b->busy);
  return b;
}

struct mrn_sim *mrn_lua_check_sim(lua_State *L, int idx) { return check_sim(L, idx)->sim; }

/* ---------------------------------------------------------------- specs */

static const char *const dim_doc = "2 (plane strain) or 3";
static const char *const integrator_choices[] = {"explicit", "implicit", NULL};

static const mrn_spec sim_specs[] = {
    {"dim", MRN_SPEC_INTEGER, 1, 2, 2, 3, 0, 0, "", "dimension: 2 (plane strain) or 3", NULL},
    {"grid", MRN_SPEC_TABLE, 1, 0, 0, 0, 0, 0, NULL, "background grid {origin, size, cell}", NULL},
    {"shape", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "shape function (default quadratic_bspline)", NULL},
    {"shape_boundary", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "kernels at the grid faces: extended (default), truncated, modified or wls", NULL},
    {"scheme", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "strategy preset string or {transfer, stress_update}", NULL},
    {"gravity", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s^2", "body acceleration (default 0)", NULL},
    {"boundary", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "face conditions (default slip on every face)", NULL},
    {"dt", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "s", "time-step policy (default {a_tau = 0.05})", NULL},
    {"damping", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "grid-force damping {cundall, viscous} (default none)", NULL},
    {"watchdog", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL,
     "physical-sanity bounds {energy, dt, speed, every}, or false (default on)", NULL},
    {"thermo", MRN_SPEC_INTEGER, 0, 100, 0, 1e12, 0, 0, "steps", "thermo line every N steps (0: none)", NULL},
    {"diagnostics", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "CSV file name in the output directory, or false", NULL},
    {"diagnostics_every", MRN_SPEC_INTEGER, 0, 10, 1, 1e12, 0, 0, "steps", "CSV row every N steps", NULL},
    {"series", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "HDF5 time-series file name (default diagnostics.h5), or false", NULL},
    {"output", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "VTK output {vtk, every, every_steps, fields, format}", NULL},
    {"name", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "label shown in messages", NULL},
    {"progress", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL, "progress bar on a terminal (default true)", NULL},
    {"on_leave", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "a particle leaving the grid: stop the run (default) or delete it", NULL},
    {"integrator", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "time integrator: explicit (default) or implicit (001; options in `implicit`)", integrator_choices},
    {"implicit", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL,
     "options of the implicit integrator (the keys of sim:implicit{}), with integrator = \"implicit\"", NULL},
    {"sort_every", MRN_SPEC_INTEGER, 0, 0, 0, 1e12, 0, 0, "steps",
     "reorder the particles by grid block every N explicit steps (0: never; indices change, ids stay)", NULL},
};

static const mrn_spec grid_specs[] = {
    {"origin", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "lower corner (default 0)", NULL},
    {"size", MRN_SPEC_VECTOR, 1, 0, 0, HUGE_VAL, 1, 0, "m", "extent along each axis (whole cells)", NULL},
    {"cell", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "m", "cell size (square/cubic cells)", NULL},
};

static const char *const gradient_choices[] = {"standard", "mls", NULL};
static const mrn_spec scheme_specs[] = {
    {"transfer", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "strategy preset (default FLIP)", NULL},
    {"stress_update", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "USF, USL, MUSL or USAVG (default USF)", NULL},
    {"grid_velocity", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "plain, affine or taylor (overrides the preset)", NULL},
    {"velocity_update", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "PIC, FLIP, blend or XPIC (overrides the preset)", NULL},
    {"position_update", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "grid, particle or XPIC (overrides the preset)", NULL},
    {"flip_fraction", MRN_SPEC_NUMBER, 0, 1, 0, 1, 0, 0, "", "X of the blend X FLIP + (1 - X) PIC (000, Eq. 37)", NULL},
    {"xpic_order", MRN_SPEC_INTEGER, 0, 1, 1, 16, 0, 0, "", "m of XPIC(m) (000, Eqs. 39-41)", NULL},
    {"gradient", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "kernel gradient: standard or mls (002, Eq. 62)", gradient_choices},
};

static const char *const format_choices[] = {"binary", "ascii", NULL};
static const mrn_spec output_specs[] = {
    {"vtk", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "series name (files <vtk>_NNNNNN.vtp and <vtk>.pvd), or false", NULL},
    {"every", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "write every this much model time", NULL},
    {"every_steps", MRN_SPEC_INTEGER, 0, 0, 1, 1e12, 0, 0, "steps", "write every N steps", NULL},
    {"fields", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "list of particle fields (default all)", NULL},
    {"format", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "binary (default) or ascii", format_choices},
    {"grid", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL, "also write the grid (.vti: nodal mass, velocity, force)", NULL},
};

static const mrn_spec boundary_specs[] = {
    {"xmin", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face x = origin", NULL},
    {"xmax", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face x = origin + size", NULL},
    {"ymin", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face y = origin", NULL},
    {"ymax", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face y = origin + size", NULL},
    {"zmin", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face z = origin (3D)", NULL},
    {"zmax", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face z = origin + size (3D)", NULL},
    {"left", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of xmin", NULL},
    {"right", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of xmax", NULL},
    {"bottom", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of ymin in 2D, zmin in 3D", NULL},
    {"top", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of ymax in 2D, zmax in 3D", NULL},
    {"front", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of ymin in 3D", NULL},
    {"back", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of ymax in 3D", NULL},
    {"all", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "every face not named otherwise", NULL},
};

static const mrn_spec face_specs[] = {
    {"kind", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "free, fixed, slip, friction, velocity or periodic", NULL},
    {"mu", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "", "Coulomb friction coefficient (friction faces)", NULL},
    {"v", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s", "prescribed velocity (velocity faces)", NULL},
};

static const mrn_spec dt_specs[] = {
    {"fixed", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "constant time step", NULL},
    {"a_tau", MRN_SPEC_NUMBER, 0, 0.05, 0, HUGE_VAL, 1, 0, "", "dt = a_tau l_cell sqrt(rho/E) (000, Eq. 29)", NULL},
    {"cfl", MRN_SPEC_NUMBER, 0, 0.5, 0, HUGE_VAL, 1, 0, "", "Courant number of the particle CFL step (002, Eqs. 34-37)", NULL},
    {"grid_cfl", MRN_SPEC_NUMBER, 0, 1, 0, HUGE_VAL, 1, 0, "", "factor on the grid-averaged CFL step (001, Eqs. 58-61)", NULL},
    {"fn", MRN_SPEC_FUNCTION, 0, 0, 0, 0, 0, 0, NULL, "function(sim) returning dt", NULL},
    {"min", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "s", "stop the run if dt falls below this", NULL},
    {"max", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "s", "upper bound on dt", NULL},
};

static const mrn_spec damping_specs[] = {
    {"cundall", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "", "D of Cundall's local non-viscous damping (000, Eqs. 61-62)", NULL},
    {"viscous", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "1/s", "alpha of mass-proportional viscous damping -alpha m v", NULL},
};

static void read_damping(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  char sub[96];
  snprintf(sub, sizeof sub, "%s damping", where);
  mrn_lua_check_table(L, idx, sub, damping_specs, MRN_COUNT(damping_specs));
  if (mrn_lua_has(L, idx, "cundall"))
    sim->damping_cundall = mrn_lua_get_number(L, idx, sub, damping_specs, MRN_COUNT(damping_specs), "cundall");
  if (mrn_lua_has(L, idx, "viscous"))
    sim->damping_viscous = mrn_lua_get_number(L, idx, sub, damping_specs, MRN_COUNT(damping_specs), "viscous");
}

static const mrn_spec run_specs[] = {
    {"time", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "model time to advance", NULL},
    {"steps", MRN_SPEC_INTEGER, 0, 0, 1, 1e15, 0, 0, "steps", "number of steps", NULL},
    {"thermo", MRN_SPEC_INTEGER, 0, 0, 0, 1e12, 0, 0, "steps", "thermo interval for this run", NULL},
    {"stop_when", MRN_SPEC_FUNCTION, 0, 0, 0, 0, 0, 0, NULL, "function(sim) -> true to stop", NULL},
    {"progress", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL, "progress bar for this run", NULL},
    {"output", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "VTK output settings from now on (as in simulation{})", NULL},
};

static const mrn_spec hook_specs[] = {
    {"every_steps", MRN_SPEC_INTEGER, 0, 0, 1, 1e15, 0, 0, "steps", "call every N steps", NULL},
    {"every_time", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "call every T of model time", NULL},
    {"at_output", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL, "call after each VTK snapshot a run writes", NULL},
    {"fn", MRN_SPEC_FUNCTION, 1, 0, 0, 0, 0, 0, NULL, "function(sim)", NULL},
};

static const char *const placement_choices[] = {"gauss", "regular", NULL};
static const mrn_spec particle_specs[] = {
    {"material", MRN_SPEC_ANY, 1, 0, 0, 0, 0, 0, NULL, "a material from mpm.material.<model>{...}", NULL},
    {"per_axis", MRN_SPEC_INTEGER, 0, 2, 1, 8, 0, 0, "", "particles per cell along each axis (default 2)", NULL},
    {"per_cell", MRN_SPEC_INTEGER, 0, 4, 1, 512, 0, 0, "", "particles per cell, a square (2D) or cube (3D) number", NULL},
    {"placement", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "gauss (default) or regular", placement_choices},
    {"velocity", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "m/s", "initial velocity: vector or function(x, y, z)", NULL},
    {"stress", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "Pa", "initial stress: 6 values (xx,yy,zz,xy,yz,xz) or function(x, y, z)", NULL},
};

/* ------------------------------------------------------- configuration */

static void read_face(lua_State *L, int value_idx, const char *where, const char *key, mrn_face_bc *f, int dim) {
  value_idx = lua_absindex(L, value_idx);
  const char *kind = NULL;
  f->mu = 0.0;
  f->velocity[0] = f->velocity[1] = f->velocity[2] = 0.0;
  if (lua_type(L, value_idx) == LUA_TSTRING) {
    kind = lua_tostring(L, value_idx);
  } else if (lua_istable(L, value_idx)) {
    lua_geti(L, value_idx, 1);
    const char *positional = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
    lua_pop(L, 1);
    /* { "friction", mu = 0.3 } or { kind = "friction", mu = 0.3 } */
    lua_pushnil(L);
    while (lua_next(L, value_idx)) {
      lua_pop(L, 1);
      if (lua_type(L, -1) == LUA_TSTRING) {
        const char *k = lua_tostring(L, -1);
        if (!mrn_spec_find(face_specs, MRN_COUNT(face_specs), k)) {
          const char *hint = mrn_spec_suggest(face_specs, MRN_COUNT(face_specs), k);
          mrn_lua_error(L, where, "%s: unknown key '%s'%s", key, k, mrn_hint(hint).s);
        }
      }
    }
    kind = mrn_lua_get_string(L, value_idx, where, face_specs, MRN_COUNT(face_specs), "kind");
    if (!kind) kind = positional;
    if (mrn_lua_has(L, value_idx, "mu")) {
      lua_getfield(L, value_idx, "mu");
      if (lua_type(L, -1) != LUA_TNUMBER) mrn_lua_error(L, where, "%s.mu must be a number", key);
      lua_pop(L, 1);
      f->mu = mrn_lua_get_number(L, value_idx, where, face_specs, MRN_COUNT(face_specs), "mu");
    }
  } else {
    mrn_lua_error(L, where, "%s must be a condition name or a table like {\"friction\", mu = 0.3}, got %s", key,
                  luaL_typename(L, value_idx));
  }
  if (!kind) mrn_lua_error(L, where, "%s: no condition kind given (free, fixed, slip or friction)", key);
  mrn_lua_check_choice(L, where, key, kind, mrn_bc_kind_names());
  mrn_bc_kind_from_name(kind, &f->kind);
  if (f->kind == MRN_BC_FRICTION && (!lua_istable(L, value_idx) || !mrn_lua_has(L, value_idx, "mu")))
    mrn_lua_error(L, where, "%s: a friction face needs a coefficient, e.g. {\"friction\", mu = 0.3}", key);
  if (f->kind == MRN_BC_VELOCITY) {
    if (!lua_istable(L, value_idx) || !mrn_lua_has(L, value_idx, "v"))
      mrn_lua_error(L, where, "%s: a velocity face needs v, e.g. {\"velocity\", v = {0.001, 0}}", key);
    char sub[96];
    snprintf(sub, sizeof sub, "%s %s", where, key);
    mrn_lua_get_vector(L, value_idx, sub, face_specs, MRN_COUNT(face_specs), "v", dim, f->velocity, 1);
  }
}

static int face_of_key(const char *key, int dim) {
  static const char *direct[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  for (int i = 0; i < 6; i++)
    if (strcmp(key, direct[i]) == 0) return i;
  if (strcmp(key, "left") == 0) return MRN_FACE_XMIN;
  if (strcmp(key, "right") == 0) return MRN_FACE_XMAX;
  if (strcmp(key, "bottom") == 0) return dim == 2 ? MRN_FACE_YMIN : MRN_FACE_ZMIN;
  if (strcmp(key, "top") == 0) return dim == 2 ? MRN_FACE_YMAX : MRN_FACE_ZMAX;
  if (strcmp(key, "front") == 0) return dim == 3 ? MRN_FACE_YMIN : -2;
  if (strcmp(key, "back") == 0) return dim == 3 ? MRN_FACE_YMAX : -2;
  return -1; /* "all" */
}

/* apply a boundary table on top of the current conditions */
static void read_boundary(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  mrn_lua_check_table(L, idx, where, boundary_specs, MRN_COUNT(boundary_specs));
  char sub[96];
  snprintf(sub, sizeof sub, "%s boundary", where);
  if (mrn_lua_has(L, idx, "all")) {
    mrn_face_bc f;
    lua_getfield(L, idx, "all");
    read_face(L, -1, sub, "all", &f, sim->dim);
    lua_pop(L, 1);
    for (int i = 0; i < 2 * sim->dim; i++) sim->boundary.face[i] = f;
  }
  for (int i = 0; i < MRN_COUNT(boundary_specs); i++) {
    const char *key = boundary_specs[i].key;
    if (strcmp(key, "all") == 0 || !mrn_lua_has(L, idx, key)) continue;
    int face = face_of_key(key, sim->dim);
    if (face == -2 || face >= 2 * sim->dim)
      mrn_lua_error(L, sub, "face '%s' does not exist in %dD", key, sim->dim);
    lua_getfield(L, idx, key);
    read_face(L, -1, sub, key, &sim->boundary.face[face], sim->dim);
    lua_pop(L, 1);
  }
  if (mrn_boundary_validate(&sim->boundary, sim->dim) != MRN_OK) mrn_lua_engine_error(L, sub);
}

/* one of the three knobs by name, overriding the preset */
static int read_knob(lua_State *L, int idx, const char *where, const char *key, const char *const *names) {
  const char *v = mrn_lua_get_string(L, idx, where, scheme_specs, MRN_COUNT(scheme_specs), key);
  if (!v) return -1;
  mrn_lua_check_choice(L, where, key, v, names);
  return mrn_name_index(names, v);
}

static void read_scheme(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  mrn_scheme s = sim->scheme;
  if (lua_type(L, idx) == LUA_TSTRING) {
    if (mrn_scheme_from_preset(lua_tostring(L, idx), &s) != MRN_OK) mrn_lua_engine_error(L, where);
  } else if (lua_istable(L, idx)) {
    const int n = MRN_COUNT(scheme_specs);
    mrn_lua_check_table(L, idx, where, scheme_specs, n);
    const char *su = mrn_lua_get_string(L, idx, where, scheme_specs, n, "stress_update");
    if (su) {
      mrn_lua_check_choice(L, where, "stress_update", su, mrn_stress_update_names());
      mrn_stress_update_from_name(su, &s.stress_update);
    }
    const char *tr = mrn_lua_get_string(L, idx, where, scheme_specs, n, "transfer");
    if (tr && mrn_scheme_from_preset(tr, &s) != MRN_OK) mrn_lua_error(L, where, "transfer: %s", mrn_error_message());
    int k;
    int custom = 0;
    if ((k = read_knob(L, idx, where, "grid_velocity", mrn_grid_velocity_names())) >= 0) s.grid_velocity = k, custom = 1;
    if ((k = read_knob(L, idx, where, "velocity_update", mrn_velocity_update_names())) >= 0) s.velocity_update = k, custom = 1;
    if ((k = read_knob(L, idx, where, "position_update", mrn_position_update_names())) >= 0) s.position_update = k, custom = 1;
    if (mrn_lua_has(L, idx, "flip_fraction")) {
      s.flip_fraction = mrn_lua_get_number(L, idx, where, scheme_specs, n, "flip_fraction");
      custom = 1;
    }
    if (mrn_lua_has(L, idx, "xpic_order")) {
      s.xpic_order = (int)mrn_lua_get_integer(L, idx, where, scheme_specs, n, "xpic_order");
      custom = 1;
    }
    const char *grad = mrn_lua_get_string(L, idx, where, scheme_specs, n, "gradient");
    if (grad) {
      s.mls_gradient = strcmp(grad, "mls") == 0;
      custom = 1;
    }
    if (custom) mrn_scheme_describe(&s);
  } else {
    mrn_lua_error(L, where, "scheme must be a preset name or a table {transfer = ..., stress_update = ...}, got %s",
                  luaL_typename(L, idx));
  }
  if (mrn_scheme_validate(&s) != MRN_OK) mrn_lua_engine_error(L, where);
  sim->scheme = s;
}

static int call_dt_function(void *ctx, mrn_sim *sim, double *dt) {
  lua_State *L = mrn_lua_active;
  (void)sim;
  mrn_lua_callback_push(L, ctx);
  lua_pushvalue(L, 1); /* the simulation userdata is argument 1 of sim:run */
  int rc = mrn_lua_callback_pcall(L, 1, 1);
  if (rc != MRN_OK) return rc;
  int isnum = 0;
  *dt = lua_tonumberx(L, -1, &isnum);
  lua_pop(L, 1);
  if (!isnum) return mrn_error_code(MRN_ERR_HOOK, "dt function: expected a number, got a non-number");
  return MRN_OK;
}

static void read_dt(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  mrn_dt_policy *p = &sim->dt_policy;
  double min = p->min, max = p->max;
  if (lua_type(L, idx) == LUA_TNUMBER) { /* dt = 0.001 is short for dt = {fixed = 0.001} */
    double dt = lua_tonumber(L, idx);
    mrn_lua_check_number(L, where, mrn_spec_find(dt_specs, MRN_COUNT(dt_specs), "fixed"), "dt", dt);
    mrn_dt_policy_fixed(p, dt);
  } else if (lua_type(L, idx) == LUA_TFUNCTION) {
    mrn_dt_policy_release(p);
    p->kind = MRN_DT_CALLBACK;
    p->callback = call_dt_function;
    p->ctx = mrn_lua_callback_new(L, idx, "dt function");
    p->release = mrn_lua_callback_release;
  } else if (lua_istable(L, idx)) {
    char sub[96];
    snprintf(sub, sizeof sub, "%s dt", where);
    mrn_lua_check_table(L, idx, sub, dt_specs, MRN_COUNT(dt_specs));
    int kinds = mrn_lua_has(L, idx, "fixed") + mrn_lua_has(L, idx, "a_tau") + mrn_lua_has(L, idx, "fn") +
                mrn_lua_has(L, idx, "cfl") + mrn_lua_has(L, idx, "grid_cfl");
    if (kinds != 1) mrn_lua_error(L, sub, "give exactly one of fixed, a_tau, cfl, grid_cfl or fn (got %d)", kinds);
    min = mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "min");
    max = mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "max");
    if (mrn_lua_has(L, idx, "fixed")) {
      mrn_dt_policy_fixed(p, mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "fixed"));
    } else if (mrn_lua_has(L, idx, "a_tau")) {
      mrn_dt_policy_a_tau(p, mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "a_tau"));
    } else if (mrn_lua_has(L, idx, "cfl")) {
      mrn_dt_policy_cfl(p, MRN_DT_CFL, mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "cfl"));
    } else if (mrn_lua_has(L, idx, "grid_cfl")) {
      mrn_dt_policy_cfl(p, MRN_DT_GRID_CFL, mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "grid_cfl"));
    } else {
      lua_getfield(L, idx, "fn");
      read_dt(L, -1, where, sim);
      lua_pop(L, 1);
    }
    if (max > 0 && min > max) mrn_lua_error(L, sub, "min = %g is above max = %g", min, max);
  } else {
    mrn_lua_error(L, where, "dt must be a number, a table {fixed|a_tau|cfl|grid_cfl|fn, min, max} or a function, got %s",
                  luaL_typename(L, idx));
  }
  p->min = min;
  p->max = max;
}

static void read_output(lua_State *L, int idx, const char *where, sim_box *b) {
  idx = lua_absindex(L, idx);
  char sub[96];
  snprintf(sub, sizeof sub, "%s output", where);
  mrn_lua_check_table(L, idx, sub, output_specs, MRN_COUNT(output_specs));
  mrn_output *o = &b->out;
  lua_getfield(L, idx, "vtk");
  int vtk_type = lua_type(L, -1);
  const char *name = vtk_type == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
  if (vtk_type != LUA_TNIL && vtk_type != LUA_TSTRING && !(vtk_type == LUA_TBOOLEAN && !lua_toboolean(L, -1)))
    mrn_lua_error(L, sub, "vtk must be a series name or false, got %s", luaL_typename(L, -1));
  if (name && (!name[0] || strstr(name, "..")))
    mrn_lua_error(L, sub, "vtk = '%s' must be a non-empty name inside the output directory", name);
  double every = mrn_lua_has(L, idx, "every") ? mrn_lua_get_number(L, idx, sub, output_specs, MRN_COUNT(output_specs), "every") : 0;
  long every_steps = mrn_lua_has(L, idx, "every_steps")
                         ? mrn_lua_get_integer(L, idx, sub, output_specs, MRN_COUNT(output_specs), "every_steps")
                         : 0;
  if (vtk_type != LUA_TNIL) mrn_output_set_vtk(o, name, every, every_steps);
  else if (o->vtk_name) mrn_output_set_vtk(o, o->vtk_name, every > 0 ? every : o->vtk_every_time,
                                           every_steps > 0 ? every_steps : o->vtk_every_steps);
  lua_pop(L, 1);
  if (mrn_lua_has(L, idx, "grid"))
    o->grid_vtk = mrn_lua_get_boolean(L, idx, sub, output_specs, MRN_COUNT(output_specs), "grid", 0);
  const char *format = mrn_lua_get_string(L, idx, sub, output_specs, MRN_COUNT(output_specs), "format");
  if (format) o->encoding = strcmp(format, "ascii") == 0 ? MRN_VTK_ASCII : MRN_VTK_BINARY;
  if (mrn_lua_has(L, idx, "fields")) {
    lua_getfield(L, idx, "fields");
    int n = (int)luaL_len(L, -1);
    if (n > MRN_OUTPUT_MAX_FIELDS) mrn_lua_error(L, sub, "at most %d fields", MRN_OUTPUT_MAX_FIELDS);
    o->nfields = 0;
    for (int i = 0; i < n; i++) {
      lua_geti(L, -1, i + 1);
      if (lua_type(L, -1) != LUA_TSTRING) mrn_lua_error(L, sub, "fields[%d] must be a field name", i + 1);
      const char *f = lua_tostring(L, -1);
      /* a built-in field, or one the deck registers (checked at the first snapshot) */
      if (!mrn_output_field_find(f) && (strlen(f) >= sizeof o->fields[0] || strpbrk(f, " \t\"<>&")))
        mrn_lua_check_choice(L, sub, "fields", f, mrn_output_field_names());
      snprintf(o->fields[o->nfields++], sizeof o->fields[0], "%s", f);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
}

static const char *output_dir(lua_State *L) {
  lua_getfield(L, LUA_REGISTRYINDEX, "moraine.outdir");
  const char *dir = lua_tostring(L, -1);
  lua_pop(L, 1);
  return dir ? dir : "out";
}

/* ------------------------------------------------------- constructor */

/* Every simulation userdata is a key of this registry table, whose weak keys
 * do not keep one alive: the simulations a signal finds (save_interrupted). */
#define SIMULATIONS "moraine.simulations"

static void remember_sim(lua_State *L, int idx) {
  idx = lua_absindex(L, idx);
  mrn_lua_push_weak_table(L, SIMULATIONS);
  lua_pushvalue(L, idx);
  lua_pushboolean(L, 1);
  lua_rawset(L, -3);
  lua_pop(L, 1);
}

/* a new simulation userdata with its outputs ready and no engine simulation yet */
static sim_box *push_sim_box(lua_State *L) {
  sim_box *b = lua_newuserdatauv(L, sizeof *b, 0);
  memset(b, 0, sizeof *b);
  luaL_setmetatable(L, MRN_LUA_SIM);
  remember_sim(L, -1);
  mrn_output_init(&b->out, output_dir(L));
  b->out_ready = 1;
  b->thermo_every = 100;
  b->progress = 1;
  return b;
}

/* on_leave = "stop" | "delete" in the table at idx (absent: unchanged) */
static void read_on_leave(lua_State *L, int idx, const char *where, const mrn_spec *specs, int nspecs, mrn_sim *sim) {
  const char *policy = mrn_lua_get_string(L, idx, where, specs, nspecs, "on_leave");
  if (!policy) return;
  mrn_lua_check_choice(L, where, "on_leave", policy, mrn_leave_policy_names());
  for (int k = 0; mrn_leave_policy_names()[k]; k++)
    if (!strcmp(policy, mrn_leave_policy_names()[k])) sim->on_leave = (mrn_leave_policy)k;
}

static int l_simulation(lua_State *L) {
  const char *where = "simulation{}";
  mrn_lua_check_table(L, 1, where, sim_specs, MRN_COUNT(sim_specs));
  const int dim = (int)mrn_lua_get_integer(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "dim");
  (void)dim_doc;

  mrn_sim_config cfg;
  memset(&cfg, 0, sizeof cfg);
  cfg.dim = dim;
  lua_getfield(L, 1, "grid");
  char gwhere[] = "simulation{} grid";
  mrn_lua_check_table(L, -1, gwhere, grid_specs, MRN_COUNT(grid_specs));
  mrn_lua_get_vector(L, -1, gwhere, grid_specs, MRN_COUNT(grid_specs), "origin", dim, cfg.origin, 0);
  mrn_lua_get_vector(L, -1, gwhere, grid_specs, MRN_COUNT(grid_specs), "size", dim, cfg.size, 1);
  cfg.cell = mrn_lua_get_number(L, -1, gwhere, grid_specs, MRN_COUNT(grid_specs), "cell");
  lua_pop(L, 1);

  cfg.shape = MRN_SHAPE_QUADRATIC_BSPLINE;
  const char *shape = mrn_lua_get_string(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "shape");
  if (shape) {
    mrn_lua_check_choice(L, where, "shape", shape, mrn_shape_names());
    mrn_shape_from_name(shape, &cfg.shape);
  }
  mrn_lua_get_vector(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "gravity", dim, cfg.gravity, 0);
  const char *sb = mrn_lua_get_string(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "shape_boundary");
  cfg.kernel_boundary = MRN_KERNEL_EXTENDED;
  if (sb) {
    mrn_lua_check_choice(L, where, "shape_boundary", sb, mrn_kernel_boundary_names());
    mrn_kernel_boundary_from_name(sb, &cfg.kernel_boundary);
  }

  sim_box *b = push_sim_box(L);
  int self = lua_gettop(L);
  b->sim = mrn_sim_new(&cfg);
  if (!b->sim) mrn_lua_engine_error(L, where);
  read_on_leave(L, 1, where, sim_specs, MRN_COUNT(sim_specs), b->sim);
  mrn_blocks_set_sort_every(&b->sim->grid, mrn_lua_get_integer(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "sort_every"));
  for (int i = 0; i < MRN_FACE_COUNT; i++) b->sim->boundary.face[i].kind = MRN_BC_SLIP;
  mrn_output_set_csv(&b->out, "diagnostics.csv", 10);
  const char *name = mrn_lua_get_string(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "name");
  snprintf(b->name, sizeof b->name, "%s", name ? name : "simulation");

  if (mrn_lua_has(L, 1, "scheme")) {
    lua_getfield(L, 1, "scheme");
    read_scheme(L, -1, "simulation{} scheme", b->sim);
    lua_pop(L, 1);
  }
  if (mrn_lua_has(L, 1, "boundary")) {
    lua_getfield(L, 1, "boundary");
    read_boundary(L, -1, where, b->sim);
    lua_pop(L, 1);
  }
  if (mrn_lua_has(L, 1, "dt")) {
    lua_getfield(L, 1, "dt");
    read_dt(L, -1, where, b->sim);
    lua_pop(L, 1);
  }
  if (mrn_lua_has(L, 1, "damping")) {
    lua_getfield(L, 1, "damping");
    read_damping(L, -1, where, b->sim);
    lua_pop(L, 1);
  }
  if (mrn_lua_has(L, 1, "watchdog")) {
    lua_getfield(L, 1, "watchdog");
    mrn_lua_read_watchdog(L, -1, where, b->sim);
    lua_pop(L, 1);
  }
  b->thermo_every = mrn_lua_get_integer(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "thermo");
  b->progress = mrn_lua_get_boolean(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "progress", 1);

  long csv_every = mrn_lua_get_integer(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "diagnostics_every");
  lua_getfield(L, 1, "diagnostics");
  if (lua_isnil(L, -1)) mrn_output_set_csv(&b->out, "diagnostics.csv", csv_every);
  else if (lua_type(L, -1) == LUA_TSTRING) mrn_output_set_csv(&b->out, lua_tostring(L, -1), csv_every);
  else if (lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1)) mrn_output_set_csv(&b->out, NULL, csv_every);
  else mrn_lua_error(L, where, "diagnostics must be a file name or false, got %s", luaL_typename(L, -1));
  lua_pop(L, 1);
  lua_getfield(L, 1, "series");
  /* the series holds the diagnostics too: off with them unless named */
  if (lua_isnil(L, -1)) mrn_output_set_series(&b->out, b->out.csv_name ? "diagnostics.h5" : NULL);
  else if (lua_type(L, -1) == LUA_TSTRING) mrn_output_set_series(&b->out, lua_tostring(L, -1));
  else if (lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1)) mrn_output_set_series(&b->out, NULL);
  else mrn_lua_error(L, where, "series must be a file name or false, got %s", luaL_typename(L, -1));
  lua_pop(L, 1);

  if (mrn_lua_has(L, 1, "output")) {
    lua_getfield(L, 1, "output");
    read_output(L, -1, where, b);
    lua_pop(L, 1);
  }
  mrn_lua_check_outputs(L, where, &b->out, b->name);
  const char *integrator = mrn_lua_get_string(L, 1, where, sim_specs, MRN_COUNT(sim_specs), "integrator");
  const int implicit = integrator && !strcmp(integrator, "implicit");
  if (mrn_lua_has(L, 1, "implicit") && !implicit)
    mrn_lua_error(L, where, "implicit: the implicit integrator's options need integrator = \"implicit\"");
  if (implicit) {
    lua_getfield(L, 1, "implicit");
    mrn_lua_implicit_configure(L, self, lua_isnil(L, -1) ? 0 : lua_gettop(L), "simulation{} implicit");
    lua_pop(L, 1);
  }
  lua_pushvalue(L, self);
  return 1;
}

/* ------------------------------------------------------- particles */

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
  sim_box *b = check_sim(L, 1);
  const char *where = "add_particles()";
  size_t first = (size_t)lua_tointeger(L, 3);
  long count = (long)lua_tointeger(L, 4);
  mrn_particles *ps = &b->sim->particles;
  if (mrn_lua_has(L, 2, "velocity")) {
    lua_getfield(L, 2, "velocity");
    init_vector_field(L, -1, where, "velocity", b, first, count, ps->v, 3, b->sim->dim);
    lua_pop(L, 1);
    b->sim->affine_pending = 1; /* grad v / C follow at the next run (000 §3.2) */
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

static int l_add_particles(lua_State *L) {
  const char *where = "add_particles()";
  sim_box *b = check_idle(L, 1, where);
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
  size_t first = 0;
  long count = 0;
  mrn_lua_active = L;
  b->busy = where; /* region functions run inside the seeding */
  int seeded = mrn_sim_seed(b->sim, region, mat_index, per_axis, pl, &first, &count);
  b->busy = NULL;
  if (seeded != MRN_OK) mrn_lua_engine_error(L, where);
  if (count == 0) mrn_lua_error(L, where, "the region seeds no particle on this grid (is it inside the domain?)");
  mrn_suspicious_seed(b->sim, per_axis, count);

  /* the initial fields call deck functions that may fail: on any error the
   * particles just seeded are removed again, so a caught error leaves the
   * simulation as it was */
  lua_pushcfunction(L, init_particle_fields);
  lua_pushvalue(L, 1);
  lua_pushvalue(L, 3);
  lua_pushinteger(L, (lua_Integer)first);
  lua_pushinteger(L, count);
  b->busy = where; /* and so do the velocity and stress functions */
  int status = lua_pcall(L, 4, 0, 0);
  b->busy = NULL;
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
  lua_pushinteger(L, count);
  return 1;
}

/* ------------------------------------------------------- running */

static int call_hook(void *ctx, mrn_sim *sim) {
  (void)sim;
  lua_State *L = mrn_lua_active;
  mrn_lua_callback_push(L, ctx);
  lua_pushvalue(L, 1);
  return mrn_lua_callback_pcall(L, 1, 0);
}

static int call_stop_when(void *ctx, mrn_sim *sim) {
  (void)sim;
  lua_State *L = mrn_lua_active;
  mrn_lua_callback_push(L, ctx);
  lua_pushvalue(L, 1);
  int rc = mrn_lua_callback_pcall(L, 1, 1);
  if (rc != MRN_OK) return rc;
  int stop = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return stop ? MRN_STOP : MRN_OK;
}

/* When a run stops on an invalid state or a signal, the state it reached is
 * kept: a checkpoint OUTDIR/<name>_<why>.h5, when a VTK series is set a last
 * snapshot, and every CSV and series row on disk. A failed state may hold
 * non-finite values, which mpm.load refuses; h5py and h5dump read it for the
 * post-mortem. Fills `note` for the message with what was written and what
 * could not be (its file and reason); MRN_ERR_IO when something could not. */
static void note_add(char *note, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void note_add(char *note, size_t len, const char *fmt, ...) {
  size_t used = strlen(note);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(note + used, len - used, fmt, ap);
  va_end(ap);
}

static int write_final_state(sim_box *b, const char *why, char *note, size_t len) {
  note[0] = '\0';
  char file[96];
  snprintf(file, sizeof file, "%s_%s.h5", b->name, why);
  char *path = mrn_path_join(b->out.dir, file);
  char saved[2048];
  snprintf(saved, sizeof saved, "%s", mrn_error_message()); /* the writes may overwrite it */
  int rc = mrn_mkdir_p(b->out.dir);
  if (rc == MRN_OK) rc = mrn_checkpoint_save(b->sim, path);
  if (rc == MRN_OK) note_add(note, len, "; the state at step %ld is in %s", b->sim->step, path);
  else note_add(note, len, "; the state at step %ld could not be saved: %s", b->sim->step, mrn_error_message());
  if (b->out.vtk_name && b->out.vtk_last_step != b->sim->step) {
    if (mrn_output_write_vtk(&b->out, b->sim) == MRN_OK) {
      note_add(note, len, "%s a last VTK snapshot was written", rc == MRN_OK ? " and" : ";");
    } else {
      note_add(note, len, "; no last VTK snapshot: %s", mrn_error_message());
      rc = MRN_ERR_IO;
    }
  }
  if (mrn_output_flush(&b->out) != MRN_OK) {
    note_add(note, len, "; %s", mrn_error_message());
    rc = MRN_ERR_IO;
  }
  free(path);
  mrn_error_code(MRN_ERR_STATE, "%s", saved);
  return rc == MRN_OK ? MRN_OK : MRN_ERR_IO;
}

/* raise the engine's message; a hook's own error already carries its location */
static int raise_engine_error(lua_State *L, int rc, const char *where, sim_box *b) {
  if (rc == MRN_ERR_HOOK) {
    lua_pushstring(L, mrn_error_message());
    return lua_error(L);
  }
  if (rc == MRN_ERR_IO) return mrn_lua_engine_output_error(L, where);
  if (rc == MRN_ERR_STATE || rc == MRN_ERR_INTERRUPTED) {
    char note[1536];
    int written = write_final_state(b, rc == MRN_ERR_STATE ? "failed" : "interrupted", note, sizeof note);
    b->interrupted = rc == MRN_ERR_INTERRUPTED;
    char message[2048];
    snprintf(message, sizeof message, "%s%s", mrn_error_message(), note);
    /* a state the grid cannot hold (a particle outside it) may not be stepped
     * or measured on the grid again: run{} and dt_estimate() refuse it */
    if (rc == MRN_ERR_STATE && mrn_sim_check_state(b->sim) != MRN_OK)
      b->invalid_step = b->sim->step > 0 ? b->sim->step : 1;
    /* what a stopped run promises to leave could not be written: exit status 3 */
    if (written != MRN_OK) return mrn_lua_output_error(L, where, "%s", message);
    return mrn_lua_error(L, where, "%s", message);
  }
  return mrn_lua_engine_error(L, where);
}

static int l_run(lua_State *L) {
  const char *where = "run{}";
  check_valid(L, 1, where);
  sim_box *b = check_idle(L, 1, where);
  mrn_lua_check_table(L, 2, where, run_specs, MRN_COUNT(run_specs));
  if (!mrn_lua_has(L, 2, "time") && !mrn_lua_has(L, 2, "steps"))
    mrn_lua_error(L, where, "give time = <seconds> and/or steps = <count>");
  if (b->sim->particles.n == 0) mrn_lua_error(L, where, "the simulation has no particles (add_particles first)");
  mrn_lua_implicit_prepare(L, 1, where); /* integrator = "implicit": made at the first run */
  if (mrn_lua_has(L, 2, "output")) {
    lua_getfield(L, 2, "output");
    read_output(L, -1, where, b);
    lua_pop(L, 1);
  }
  mrn_run_options opt;
  memset(&opt, 0, sizeof opt);
  opt.time = mrn_lua_has(L, 2, "time") ? mrn_lua_get_number(L, 2, where, run_specs, MRN_COUNT(run_specs), "time") : 0;
  opt.steps = mrn_lua_has(L, 2, "steps") ? mrn_lua_get_integer(L, 2, where, run_specs, MRN_COUNT(run_specs), "steps") : 0;
  opt.thermo_every = mrn_lua_has(L, 2, "thermo") ? mrn_lua_get_integer(L, 2, where, run_specs, MRN_COUNT(run_specs), "thermo")
                                                 : b->thermo_every;
  int progress = mrn_lua_get_boolean(L, 2, where, run_specs, MRN_COUNT(run_specs), "progress", b->progress);
  opt.progress = progress && !mrn_log_quiet() && isatty(2);
  opt.hooks = b->hooks;
  opt.nhooks = b->nhooks;
  mrn_lua_callback *stop_cb = NULL;
  if (mrn_lua_has(L, 2, "stop_when")) {
    lua_getfield(L, 2, "stop_when");
    stop_cb = mrn_lua_callback_new(L, -1, "stop_when");
    lua_pop(L, 1);
    opt.stop_when = call_stop_when;
    opt.stop_ctx = stop_cb;
  }
  lua_settop(L, 2); /* callbacks find the simulation at index 1 */
  mrn_lua_active = L;
  mrn_suspicious_run(b->sim);
  b->busy = where;
  int rc = mrn_run(b->sim, &b->out, &opt);
  b->busy = NULL;
  mrn_lua_callback_release(stop_cb);
  if (rc != MRN_OK) return raise_engine_error(L, rc, where, b);
  return 0;
}

static int l_hook(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  const char *where = "hook{}";
  mrn_lua_check_table(L, 2, where, hook_specs, MRN_COUNT(hook_specs));
  int has_steps = mrn_lua_has(L, 2, "every_steps"), has_time = mrn_lua_has(L, 2, "every_time");
  int at_output = mrn_lua_get_boolean(L, 2, where, hook_specs, MRN_COUNT(hook_specs), "at_output", 0);
  if (has_steps + has_time + at_output != 1)
    mrn_lua_error(L, where, "give exactly one of every_steps, every_time or at_output = true");
  if (b->nhooks == MAX_HOOKS) mrn_lua_error(L, where, "at most %d hooks per simulation", MAX_HOOKS);
  mrn_hook *h = &b->hooks[b->nhooks];
  memset(h, 0, sizeof *h);
  if (has_steps) h->every_steps = mrn_lua_get_integer(L, 2, where, hook_specs, MRN_COUNT(hook_specs), "every_steps");
  if (has_time) h->every_time = mrn_lua_get_number(L, 2, where, hook_specs, MRN_COUNT(hook_specs), "every_time");
  h->at_output = at_output;
  lua_getfield(L, 2, "fn");
  b->hook_cb[b->nhooks] = mrn_lua_callback_new(L, -1, "hook");
  lua_pop(L, 1);
  h->fn = call_hook;
  h->ctx = b->hook_cb[b->nhooks];
  b->nhooks++;
  lua_pushinteger(L, b->nhooks);
  return 1;
}

/* ------------------------------------------------------- changing a simulation */

/* the checks of simulation{gravity}, on the value given alone */
static int l_set_gravity(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  double g[3] = {0, 0, 0};
  mrn_lua_to_vector(L, 2, "set_gravity()", mrn_spec_find(sim_specs, MRN_COUNT(sim_specs), "gravity"), b->sim->dim, g);
  memcpy(b->sim->gravity, g, sizeof g);
  return 0;
}

static int l_set_boundary(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  read_boundary(L, 2, "set_boundary()", b->sim);
  return 0;
}

static int l_set_scheme(lua_State *L) {
  sim_box *b = check_idle(L, 1, "set_scheme()");
  read_scheme(L, 2, "set_scheme()", b->sim);
  return 0;
}

static int l_set_dt(lua_State *L) {
  sim_box *b = check_idle(L, 1, "set_dt()");
  read_dt(L, 2, "set_dt()", b->sim);
  return 0;
}

static void push_vec(lua_State *L, const double *v, int n) {
  lua_createtable(L, n, 0);
  for (int i = 0; i < n; i++) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

/* ------------------------------------------------------- constraints */

static const mrn_spec constrain_specs[] = {
    {"region", MRN_SPEC_ANY, 1, 0, 0, 0, 0, 0, NULL, "the grid nodes inside this region are constrained", NULL},
    {"vx", MRN_SPEC_NUMBER, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s", "prescribed x velocity (absent: free)", NULL},
    {"vy", MRN_SPEC_NUMBER, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s", "prescribed y velocity (absent: free)", NULL},
    {"vz", MRN_SPEC_NUMBER, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s", "prescribed z velocity, 3D (absent: free)", NULL},
};

/* reads vx, vy, vz into v and mask; returns the number given */
static int read_components(lua_State *L, int idx, const char *where, int dim, double v[3], unsigned *mask) {
  static const char *keys[] = {"vx", "vy", "vz"};
  int given = 0;
  for (int d = 0; d < 3; d++) {
    if (!mrn_lua_has(L, idx, keys[d])) continue;
    if (d >= dim) mrn_lua_error(L, where, "%s is not a component in %dD", keys[d], dim);
    v[d] = mrn_lua_get_number(L, idx, where, constrain_specs, MRN_COUNT(constrain_specs), keys[d]);
    *mask |= 1u << d;
    given++;
  }
  return given;
}

/* sim:constrain{region = r, vx = ..., vy = ...} -> index */
static int l_constrain(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  const char *where = "constrain{}";
  mrn_lua_check_table(L, 2, where, constrain_specs, MRN_COUNT(constrain_specs));
  lua_getfield(L, 2, "region");
  mrn_region *region = mrn_lua_check_region(L, -1, where);
  lua_pop(L, 1);
  double v[3] = {0, 0, 0};
  unsigned mask = 0;
  if (!read_components(L, 2, where, b->sim->dim, v, &mask)) mrn_lua_error(L, where, "give at least one of vx, vy, vz");
  mrn_lua_active = L;
  int i = mrn_sim_add_constraint(b->sim, region, mask, v);
  if (i < 0) mrn_lua_engine_error(L, where);
  lua_pushinteger(L, i + 1);
  return 1;
}

static mrn_constraint *check_constraint(lua_State *L, sim_box *b, int idx, const char *where) {
  lua_Integer i = luaL_checkinteger(L, idx);
  if (i < 1 || i > b->sim->nconstraints)
    mrn_lua_error(L, where, "no constraint %d (the simulation has %d)", (int)i, b->sim->nconstraints);
  return &b->sim->constraints[i - 1];
}

/* sim:reaction(i) -> force the constraint exerted on the material in the last step */
static int l_reaction(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  mrn_constraint *c = check_constraint(L, b, 2, "reaction()");
  push_vec(L, c->reaction, b->sim->dim);
  return 1;
}

/* sim:set_constraint(i, {vx = ..., ...}): new prescribed values for the components given */
static int l_set_constraint(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  const char *where = "set_constraint()";
  mrn_constraint *c = check_constraint(L, b, 2, where);
  mrn_lua_check_table(L, 3, where, constrain_specs + 1, MRN_COUNT(constrain_specs) - 1);
  double v[3] = {c->velocity[0], c->velocity[1], c->velocity[2]};
  unsigned mask = c->mask;
  read_components(L, 3, where, b->sim->dim, v, &mask);
  memcpy(c->velocity, v, sizeof v);
  c->mask = mask;
  return 0;
}

/* ------------------------------------------------------- checkpoints */

static const char *output_path(lua_State *L, sim_box *b, const char *path) {
  if (path[0] == '/') return path;
  char *joined = mrn_path_join(b->out.dir, path);
  lua_pushstring(L, joined);
  free(joined);
  return lua_tostring(L, -1);
}

/* sim:save(path): the complete state, relative paths in the output directory */
static int l_save(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  const char *path = output_path(L, b, luaL_checkstring(L, 2));
  mrn_lua_check_write(L, "save()", path);
  if (mrn_mkdir_p(b->out.dir) != MRN_OK) mrn_lua_engine_error(L, "save()");
  if (mrn_checkpoint_save(b->sim, path) != MRN_OK) mrn_lua_engine_output_error(L, "save()");
  lua_pushstring(L, path);
  return 1;
}

static const mrn_spec load_specs[] = {
    {"name", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "label of the loaded simulation", NULL},
    {"thermo", MRN_SPEC_INTEGER, 0, 100, 0, 1e12, 0, 0, "steps", "thermo line every N steps", NULL},
    {"diagnostics", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "CSV file name, or false", NULL},
    {"output", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "VTK output settings, as in simulation{}", NULL},
    {"on_leave", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "a particle leaving the grid: stop or delete (default: as saved)", NULL},
    {"sort_every", MRN_SPEC_INTEGER, 0, 0, 0, 1e12, 0, 0, "steps",
     "reorder the particles by grid block every N explicit steps (default: as saved)", NULL},
};

/* mpm.load(path [, options]): a simulation continuing from a checkpoint */
static int l_load(lua_State *L) {
  const char *where = "load()";
  const char *path = luaL_checkstring(L, 1);
  int has_opts = !lua_isnoneornil(L, 2);
  if (has_opts) mrn_lua_check_table(L, 2, where, load_specs, MRN_COUNT(load_specs));
  /* a relative path is looked for as given, then in the output directory */
  if (path[0] != '/' && access(path, F_OK) != 0) {
    char *joined = mrn_path_join(output_dir(L), path);
    if (access(joined, F_OK) == 0) {
      lua_pushstring(L, joined);
      path = lua_tostring(L, -1);
    }
    free(joined);
  }
  sim_box *b = push_sim_box(L);
  int self = lua_gettop(L);
  mrn_checkpoint_info info;
  b->sim = mrn_checkpoint_load_info(path, &info);
  if (!b->sim) mrn_lua_engine_error(L, where);
  if (info.dt_function_dropped) mrn_warn("%s", info.note);
  snprintf(b->name, sizeof b->name, "%s", "loaded");
  mrn_output_set_csv(&b->out, "diagnostics.csv", 10);
  mrn_output_set_series(&b->out, "diagnostics.h5");
  if (has_opts) {
    const char *name = mrn_lua_get_string(L, 2, where, load_specs, MRN_COUNT(load_specs), "name");
    if (name) snprintf(b->name, sizeof b->name, "%s", name);
    b->thermo_every = mrn_lua_get_integer(L, 2, where, load_specs, MRN_COUNT(load_specs), "thermo");
    lua_getfield(L, 2, "diagnostics");
    if (lua_type(L, -1) == LUA_TSTRING) mrn_output_set_csv(&b->out, lua_tostring(L, -1), 10);
    else if (lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1)) {
      mrn_output_set_csv(&b->out, NULL, 10);
      mrn_output_set_series(&b->out, NULL);
    }
    lua_pop(L, 1);
    if (mrn_lua_has(L, 2, "output")) {
      lua_getfield(L, 2, "output");
      read_output(L, -1, where, b);
      lua_pop(L, 1);
    }
    read_on_leave(L, 2, where, load_specs, MRN_COUNT(load_specs), b->sim);
    if (mrn_lua_has(L, 2, "sort_every"))
      mrn_blocks_set_sort_every(&b->sim->grid,
                                mrn_lua_get_integer(L, 2, where, load_specs, MRN_COUNT(load_specs), "sort_every"));
  }
  mrn_lua_check_outputs(L, where, &b->out, b->name);
  lua_pushvalue(L, self);
  return 1;
}

static const mrn_spec import_specs[] = {
    {"material", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "a material for every imported particle (default: the saved ones)", NULL},
    {"offset", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "added to every position", NULL},
};

/* sim:import(path [, {material = m, offset = {...}}]): particles of a checkpoint */
static int l_import(lua_State *L) {
  const char *where = "import()";
  sim_box *b = check_idle(L, 1, where);
  const char *path = luaL_checkstring(L, 2);
  mrn_material *override = NULL;
  double offset[3] = {0, 0, 0};
  if (!lua_isnoneornil(L, 3)) {
    mrn_lua_check_table(L, 3, where, import_specs, MRN_COUNT(import_specs));
    if (mrn_lua_has(L, 3, "material")) {
      lua_getfield(L, 3, "material");
      override = mrn_lua_check_material(L, -1, where);
      lua_pop(L, 1);
    }
    mrn_lua_get_vector(L, 3, where, import_specs, MRN_COUNT(import_specs), "offset", b->sim->dim, offset, 0);
  }
  if (path[0] != '/' && access(path, F_OK) != 0) path = output_path(L, b, path);
  long count = 0;
  if (mrn_checkpoint_import(b->sim, path, override, offset, &count) != MRN_OK)
    mrn_lua_engine_error(L, where);
  lua_pushinteger(L, count);
  return 1;
}

static int l_set_damping(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  read_damping(L, 2, "set_damping()", b->sim);
  return 0;
}

/* the critical steps the CFL policies use, without their Courant number */
static int l_dt_estimate(lua_State *L) {
  sim_box *b = check_valid(L, 1, "dt_estimate()");
  lua_createtable(L, 0, 3);
  lua_pushnumber(L, mrn_dt_particle_critical(b->sim));
  lua_setfield(L, -2, "cfl");
  lua_pushnumber(L, mrn_dt_grid_critical(b->sim));
  lua_setfield(L, -2, "grid_cfl");
  lua_pushnumber(L, b->sim->grid.cell * mrn_sim_slowness(b->sim));
  lua_setfield(L, -2, "a_tau");
  return 1;
}

static int l_set_output(lua_State *L) {
  sim_box *b = check_idle(L, 1, "output()");
  read_output(L, 2, "output()", b);
  mrn_lua_check_outputs(L, "output()", &b->out, b->name);
  return 0;
}

static int l_write_vtk(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  if (!b->out.vtk_name) mrn_lua_error(L, "write_vtk()", "no VTK series configured (output{vtk = name})");
  if (mrn_output_write_vtk(&b->out, b->sim) != MRN_OK)
    mrn_lua_engine_output_error(L, "write_vtk()");
  return 0;
}

/* ------------------------------------------------------- reading state */

static int l_time(lua_State *L) { lua_pushnumber(L, check_sim(L, 1)->sim->time); return 1; }
static int l_step(lua_State *L) { lua_pushinteger(L, check_sim(L, 1)->sim->step); return 1; }
static int l_dt(lua_State *L) { lua_pushnumber(L, check_sim(L, 1)->sim->dt); return 1; }
static int l_count(lua_State *L) { lua_pushinteger(L, (lua_Integer)check_sim(L, 1)->sim->particles.n); return 1; }
static int l_dim(lua_State *L) { lua_pushinteger(L, check_sim(L, 1)->sim->dim); return 1; }


static int l_energy(lua_State *L) {
  sim_box *b = check_sim(L, 1);
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
  lua_pushnumber(L, d.mpm_error); lua_setfield(L, -2, "mpm_error");
  return 1;
}

static int l_diagnostics(lua_State *L) {
  sim_box *b = check_sim(L, 1);
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
  push_vec(L, d.momentum, dim); lua_setfield(L, -2, "momentum");
  push_vec(L, d.angular, 3); lua_setfield(L, -2, "angular_momentum");
  push_vec(L, d.com, dim); lua_setfield(L, -2, "center_of_mass");
  push_vec(L, d.com_velocity, dim); lua_setfield(L, -2, "com_velocity");
  lua_pushnumber(L, b->sim->time); lua_setfield(L, -2, "time");
  lua_pushinteger(L, b->sim->step); lua_setfield(L, -2, "step");
  lua_pushnumber(L, b->sim->dt); lua_setfield(L, -2, "dt");
  lua_pushinteger(L, b->sim->outflow_particles); lua_setfield(L, -2, "outflow_particles");
  lua_pushnumber(L, b->sim->outflow_mass); lua_setfield(L, -2, "outflow_mass");
  lua_pushnumber(L, b->sim->energy_outflow); lua_setfield(L, -2, "energy_outflow");
  return 1;
}

/* sim:field(name) -> flat array of n * ncomp values */
static int l_field(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  const char *name = luaL_checkstring(L, 2);
  mrn_field_ref f;
  if (!mrn_field_lookup(b->sim, name, &f)) mrn_lua_check_choice(L, "field()", "name", name, mrn_output_field_names());
  size_t n = b->sim->particles.n;
  size_t total = n * f.ncomp;
  void *buf = lua_newuserdatauv(L, (total ? total : 1) * 8, 0);
  mrn_field_fill(b->sim, &f, buf);
  lua_createtable(L, (int)total, 0);
  for (size_t i = 0; i < total; i++) {
    if (f.type == MRN_VTK_FLOAT64) lua_pushnumber(L, ((double *)buf)[i]);
    else if (f.type == MRN_VTK_INT32) lua_pushinteger(L, ((int32_t *)buf)[i]);
    else lua_pushinteger(L, ((int64_t *)buf)[i]);
    lua_rawseti(L, -2, (lua_Integer)i + 1);
  }
  lua_pushinteger(L, f.ncomp);
  return 2;
}

/* sim:record(name, value): a value for the next row of the HDF5 series */
static int l_record(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  const char *name = luaL_checkstring(L, 2);
  double v = luaL_checknumber(L, 3);
  if (!name[0] || strchr(name, '/')) mrn_lua_error(L, "record()", "'%s' is not a valid series name", name);
  if (mrn_output_record(&b->out, name, v) != MRN_OK) mrn_lua_engine_output_error(L, "record()");
  return 0;
}

/* ------------------------------------------------------- reductions */

static const char *const reduce_ops[] = {"min", "max", "sum", "mean", "count", NULL};
static const mrn_spec reduce_specs[] = {
    {"component", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "component index from 1, or \"norm\" (default: 1, or the norm for vectors)", NULL},
    {"material", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "only particles of this material", NULL},
    {"region", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "only particles inside this region", NULL},
    {"where", MRN_SPEC_FUNCTION, 0, 0, 0, 0, 0, 0, NULL, "only particles for which where(x, y, z) is true", NULL},
};

/* sim:reduce(op, field [, options]): min, max, sum, mean or count of a
 * particle quantity over all particles, a material, a region or a predicate.
 * field: a particle field name, or x / y / z for the positions. */
static int l_reduce(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  const char *where = "reduce()";
  const char *op = luaL_checkstring(L, 2);
  mrn_lua_check_choice(L, where, "op", op, reduce_ops);
  const char *field = luaL_checkstring(L, 3);
  int has_opts = !lua_isnoneornil(L, 4);
  if (has_opts) mrn_lua_check_table(L, 4, where, reduce_specs, MRN_COUNT(reduce_specs));
  const mrn_particles *ps = &b->sim->particles;
  const size_t n = ps->n;
  /* the values: positions directly, or a field computed into a buffer */
  int ncomp = 1, axis = -1;
  const double *data = NULL;
  if (!strcmp(field, "x") || !strcmp(field, "y") || !strcmp(field, "z")) {
    axis = field[0] - 'x';
    if (axis >= b->sim->dim) mrn_lua_error(L, where, "field '%s' does not exist in %dD", field, b->sim->dim);
    data = ps->x;
    ncomp = 3;
  } else {
    static const char *const extra[] = {"x", "y", "z", NULL};
    mrn_field_ref f;
    if (!mrn_field_lookup(b->sim, field, &f)) {
      const char *hint = mrn_suggest_from(mrn_output_field_names(), field);
      if (!hint) hint = mrn_suggest_from(extra, field);
      mrn_lua_error(L, where, "unknown field '%s'%s (fields: x, y, z and those of sim:field)", field, mrn_hint(hint).s);
    }
    ncomp = f.ncomp;
    double *buf = lua_newuserdatauv(L, (n ? n : 1) * ncomp * sizeof(double), 0);
    if (f.type == MRN_VTK_FLOAT64) {
      mrn_field_fill(b->sim, &f, buf);
    } else { /* integer fields, widened */
      int64_t *tmp = lua_newuserdatauv(L, (n ? n : 1) * sizeof(int64_t), 0);
      mrn_field_fill(b->sim, &f, tmp);
      for (size_t i = 0; i < n; i++) buf[i] = f.type == MRN_VTK_INT32 ? ((int32_t *)tmp)[i] : (double)tmp[i];
      lua_pop(L, 1);
    }
    data = buf;
  }
  int use_norm = 0, comp = 0;
  if (axis >= 0) {
    comp = axis;
  } else {
    use_norm = ncomp == 3; /* vectors: their length unless a component is asked for */
    if (has_opts && mrn_lua_has(L, 4, "component")) {
      lua_getfield(L, 4, "component");
      if (lua_type(L, -1) == LUA_TSTRING && !strcmp(lua_tostring(L, -1), "norm")) {
        use_norm = 1;
      } else if (lua_isinteger(L, -1) && lua_tointeger(L, -1) >= 1 && lua_tointeger(L, -1) <= ncomp) {
        use_norm = 0;
        comp = (int)lua_tointeger(L, -1) - 1;
      } else {
        mrn_lua_error(L, where, "component must be 1..%d or \"norm\" for '%s'", ncomp, field);
      }
      lua_pop(L, 1);
    }
  }
  int mat = -1;
  mrn_region *region = NULL;
  int pred = 0;
  if (has_opts) {
    if (mrn_lua_has(L, 4, "material")) {
      lua_getfield(L, 4, "material");
      mrn_material *m = mrn_lua_check_material(L, -1, where);
      lua_pop(L, 1);
      for (int i = 0; i < b->sim->nmaterials; i++)
        if (b->sim->materials[i] == m) mat = i;
      if (mat < 0) mat = MRN_MAX_MATERIALS; /* a material no particle has */
    }
    if (mrn_lua_has(L, 4, "region")) {
      lua_getfield(L, 4, "region");
      region = mrn_lua_check_region(L, -1, where);
      lua_pop(L, 1);
    }
    if (mrn_lua_has(L, 4, "where")) {
      lua_getfield(L, 4, "where");
      pred = lua_gettop(L);
    }
  }
  double lo = HUGE_VAL, hi = -HUGE_VAL, sum = 0.0;
  long count = 0;
  mrn_lua_active = L;
  for (size_t p = 0; p < n; p++) {
    if (mat >= 0 && ps->material[p] != mat) continue;
    const double *x = ps->x + 3 * p;
    if (region) {
      int in = mrn_region_contains(region, x);
      if (in < 0) mrn_lua_engine_error(L, where);
      if (!in) continue;
    }
    if (pred) {
      lua_pushvalue(L, pred);
      for (int d = 0; d < 3; d++) lua_pushnumber(L, x[d]);
      lua_call(L, 3, 1);
      int keep = lua_toboolean(L, -1);
      lua_pop(L, 1);
      if (!keep) continue;
    }
    const double *row = data + (size_t)ncomp * p;
    double v = use_norm ? sqrt(row[0] * row[0] + row[1] * row[1] + row[2] * row[2]) : row[comp];
    lo = fmin(lo, v);
    hi = fmax(hi, v);
    sum += v;
    count++;
  }
  if (!strcmp(op, "count")) lua_pushinteger(L, count);
  else if (count == 0) lua_pushnil(L); /* min, max, mean of nothing */
  else if (!strcmp(op, "min")) lua_pushnumber(L, lo);
  else if (!strcmp(op, "max")) lua_pushnumber(L, hi);
  else if (!strcmp(op, "sum")) lua_pushnumber(L, sum);
  else lua_pushnumber(L, sum / count);
  return 1;
}

/* sim:particle(i) -> table of one particle's state (1-based index) */
static int l_particle(lua_State *L) {
  sim_box *b = check_sim(L, 1);
  lua_Integer i = luaL_checkinteger(L, 2);
  mrn_particles *ps = &b->sim->particles;
  if (i < 1 || (size_t)i > ps->n)
    return luaL_error(L, "particle(): index %I outside 1..%I", (lua_Integer)i, (lua_Integer)ps->n);
  size_t p = (size_t)i - 1;
  int dim = b->sim->dim;
  lua_createtable(L, 0, 8);
  push_vec(L, ps->x + 3 * p, dim); lua_setfield(L, -2, "x");
  push_vec(L, ps->v + 3 * p, dim); lua_setfield(L, -2, "v");
  push_vec(L, ps->stress + 6 * p, 6); lua_setfield(L, -2, "stress");
  push_vec(L, ps->strain + 6 * p, 6); lua_setfield(L, -2, "strain");
  lua_pushnumber(L, ps->mass[p]); lua_setfield(L, -2, "mass");
  lua_pushnumber(L, mrn_particle_volume(ps, p)); lua_setfield(L, -2, "volume");
  lua_pushinteger(L, ps->id[p]); lua_setfield(L, -2, "id");
  lua_pushinteger(L, ps->material[p] + 1); lua_setfield(L, -2, "material");
  return 1;
}

static int l_info(lua_State *L) {
  sim_box *b = check_sim(L, 1);
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
  lua_pushnumber(L, s->grid.cell); lua_setfield(L, -2, "cell");
  push_vec(L, s->grid.origin, s->dim); lua_setfield(L, -2, "origin");
  push_vec(L, s->grid.size, s->dim); lua_setfield(L, -2, "size");
  push_vec(L, s->gravity, s->dim); lua_setfield(L, -2, "gravity");
  lua_pushinteger(L, s->grid.blocks->sort_every); lua_setfield(L, -2, "sort_every");
  lua_pushstring(L, b->out.dir); lua_setfield(L, -2, "output_dir");
  return 1;
}

/* free everything; 0, or MRN_ERR_IO when the last outputs (the series'
 * last rewrite, closing the CSV) could not be written */
static int release_sim(lua_State *L) {
  sim_box *b = luaL_checkudata(L, 1, MRN_LUA_SIM);
  /* __gc never comes while running (the run holds the simulation); free() and __close can */
  if (b->busy) check_idle(L, 1, "free()");
  for (int i = 0; i < b->nhooks; i++) mrn_lua_callback_release(b->hook_cb[i]);
  b->nhooks = 0;
  int rc = b->out_ready ? mrn_output_free(&b->out) : MRN_OK;
  b->out_ready = 0;
  mrn_sim_free(b->sim);
  b->sim = NULL;
  return rc;
}

/* sim:free() and the end of a `<close>` variable: a failure is raised */
static int l_free(lua_State *L) {
  if (release_sim(L) != MRN_OK) mrn_lua_engine_output_error(L, "free()");
  return 0;
}

/* the collector, at the latest when the deck ends: nothing can be raised */
static int l_gc(lua_State *L) {
  sim_box *b = luaL_checkudata(L, 1, MRN_LUA_SIM);
  if (release_sim(L) != MRN_OK) mrn_lua_late_output_error("closing simulation '%s': %s", b->name, mrn_error_message());
  return 0;
}

static int l_tostring(lua_State *L) {
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

/* A simulation worth a checkpoint when a signal stops the deck: it holds
 * particles, no call of its own is under way (its state is whole), its run
 * did not write one already and it is not left on a state its grid cannot
 * hold (which has <name>_failed.h5). */
static int wants_checkpoint(const sim_box *b) {
  return b->sim && b->sim->particles.n > 0 && !b->busy && !b->interrupted && !b->invalid_step;
}

/* pushes the table name -> true of the names in use by checkpoints already
 * written, so that a second simulation of the same name does not overwrite one */
static void push_names_written(lua_State *L, int sims) {
  lua_newtable(L);
  lua_pushnil(L);
  while (lua_next(L, sims)) {
    lua_pop(L, 1);
    const sim_box *b = lua_touserdata(L, -1);
    if (b->sim && b->interrupted) {
      lua_pushboolean(L, 1);
      lua_setfield(L, -3, b->name);
    }
  }
}

void mrn_lua_save_interrupted(lua_State *L) {
  lua_gc(L, LUA_GCCOLLECT, 0); /* the simulations the deck no longer holds go first */
  if (lua_getfield(L, LUA_REGISTRYINDEX, SIMULATIONS) != LUA_TTABLE) {
    lua_pop(L, 1);
    return;
  }
  int sims = lua_gettop(L), message = sims - 1;
  /* an output error stays one when notes are added; a checkpoint that
   * cannot be written makes it one (exit status 3) */
  int output = mrn_lua_is_output_error(L, message);
  push_names_written(L, sims);
  int written = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, sims)) {
    lua_pop(L, 1);
    sim_box *b = lua_touserdata(L, -1);
    if (!wants_checkpoint(b)) continue;
    int taken = lua_getfield(L, written, b->name) != LUA_TNIL;
    lua_pop(L, 1);
    if (taken) continue;
    char note[1536];
    if (write_final_state(b, "interrupted", note, sizeof note) != MRN_OK) output = 1;
    b->interrupted = 1;
    lua_pushboolean(L, 1);
    lua_setfield(L, written, b->name);
    lua_pushvalue(L, message);
    lua_pushstring(L, note);
    lua_concat(L, 2);
    lua_replace(L, message);
  }
  lua_pop(L, 2);
  if (output) mrn_lua_mark_output_error(L, message);
}

void mrn_lua_open_simulation(lua_State *L, int module) {
  luaL_newmetatable(L, MRN_LUA_SIM);
  static const luaL_Reg meta[] = {{"__gc", l_gc}, {"__close", l_free}, {"__tostring", l_tostring}, {NULL, NULL}};
  luaL_setfuncs(L, meta, 0);
  static const luaL_Reg methods[] = {
      {"add_particles", l_add_particles}, {"run", l_run}, {"hook", l_hook}, {"set_gravity", l_set_gravity},
      {"set_boundary", l_set_boundary}, {"set_scheme", l_set_scheme}, {"set_dt", l_set_dt}, {"constrain", l_constrain}, {"reaction", l_reaction}, {"set_constraint", l_set_constraint}, {"save", l_save}, {"import", l_import}, {"set_damping", l_set_damping}, {"dt_estimate", l_dt_estimate},
      {"output", l_set_output}, {"write_vtk", l_write_vtk}, {"time", l_time}, {"step", l_step}, {"dt", l_dt},
      {"particle_count", l_count}, {"dim", l_dim}, {"energy", l_energy}, {"diagnostics", l_diagnostics},
      {"field", l_field}, {"reduce", l_reduce}, {"record", l_record}, {"particle", l_particle}, {"info", l_info}, {"free", l_free}, {NULL, NULL}};
  lua_newtable(L);
  luaL_setfuncs(L, methods, 0);
  mrn_lua_add_field_methods(L, lua_gettop(L));
  mrn_lua_add_load_methods(L, lua_gettop(L));
  mrn_lua_add_watchdog_methods(L, lua_gettop(L));
  mrn_lua_strict(L, -1, "simulation", "method");
  lua_setfield(L, -2, "__index");
  lua_pop(L, 1);
  lua_pushcfunction(L, l_simulation);
  lua_setfield(L, module, "simulation");
  lua_pushcfunction(L, l_load);
  lua_setfield(L, module, "load");

  mrn_spec_register_group("simulation{}", sim_specs, MRN_COUNT(sim_specs));
  mrn_spec_register_group("simulation{} grid", grid_specs, MRN_COUNT(grid_specs));
  mrn_spec_register_group("simulation{} scheme", scheme_specs, MRN_COUNT(scheme_specs));
  mrn_spec_register_group("simulation{} output", output_specs, MRN_COUNT(output_specs));
  mrn_spec_register_group("simulation{} boundary", boundary_specs, MRN_COUNT(boundary_specs));
  mrn_spec_register_group("boundary face", face_specs, MRN_COUNT(face_specs));
  mrn_spec_register_group("simulation{} dt", dt_specs, MRN_COUNT(dt_specs));
  mrn_spec_register_group("simulation{} damping", damping_specs, MRN_COUNT(damping_specs));
  mrn_spec_register_group("run{}", run_specs, MRN_COUNT(run_specs));
  mrn_spec_register_group("hook{}", hook_specs, MRN_COUNT(hook_specs));
  mrn_spec_register_group("add_particles()", particle_specs, MRN_COUNT(particle_specs));
  mrn_spec_register_group("load()", load_specs, MRN_COUNT(load_specs));
  mrn_spec_register_group("constrain{}", constrain_specs, MRN_COUNT(constrain_specs));
  mrn_spec_register_group("reduce()", reduce_specs, MRN_COUNT(reduce_specs));
  mrn_spec_register_group("import()", import_specs, MRN_COUNT(import_specs));
}
