/* moraine: mpm.simulation{...}, the constructor of the simulation object,
 * and the output options it shares with run{}, output() and mpm.load(). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "io/particle_fields.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"
#include "lua/lua_safe.h"

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
    {"split", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "particle splitting {stretch, max_level}, or false (default none)", NULL},
    {"watchdog", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL,
     "physical-sanity bounds {energy, dt, speed, every}, or false (default on)", NULL},
    {"thermo", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "steps",
     "thermo line every N steps (default 100, 0: none), or {every, columns}", NULL},
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
    {"mass_scaling", MRN_SPEC_NUMBER, 0, 1, 1, 1e12, 0, 0, "",
     "factor on the particles' inertial mass (explicit; gravity acts on the true mass; stable dt x sqrt)", NULL},
};

static const mrn_spec grid_specs[] = {
    {"origin", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "lower corner (default 0)", NULL},
    {"size", MRN_SPEC_VECTOR, 1, 0, 0, HUGE_VAL, 1, 0, "m", "extent along each axis (whole cells)", NULL},
    {"cell", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "m", "cell size (square/cubic cells)", NULL},
};

static const char *const format_choices[] = {"binary", "ascii", "vtkhdf", NULL};
static const mrn_spec output_specs[] = {
    {"vtk", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL,
     "series name (files <vtk>_NNNNNN.vtp and <vtk>.pvd, or .vtkhdf and .vtkhdf.series), or false", NULL},
    {"every", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "write every this much model time", NULL},
    {"every_steps", MRN_SPEC_INTEGER, 0, 0, 1, 1e12, 0, 0, "steps", "write every N steps", NULL},
    {"fields", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "list of particle fields (default all)", NULL},
    {"format", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "binary (.vtp, default), ascii (.vtp as text) or vtkhdf (.vtkhdf files in a .vtkhdf.series)", format_choices},
    {"compress", MRN_SPEC_INTEGER, 0, 0, 0, 9, 0, 0, "", "zlib level of the particle files, 1 to 9 (0: raw, default)",
     NULL},
    {"float32", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL,
     "store the Float64 fields and the positions as Float32 (default false)", NULL},
    {"grid", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL, "also write the grid (.vti: nodal mass, velocity, force)", NULL},
    {"gather", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL,
     "under MPI, one .vtp per snapshot gathered on process 0 instead of a piece per process and a .pvtp "
     "(default false)", NULL},
};

#define OUTPUT_SPECS output_specs, MRN_COUNT(output_specs)

/* format, compress, float32, grid and gather: how each snapshot is written (absent: unchanged) */
static void read_vtk_form(lua_State *L, int idx, const char *sub, mrn_output *o) {
  if (mrn_lua_has(L, idx, "grid")) o->grid_vtk = mrn_lua_get_boolean(L, idx, sub, OUTPUT_SPECS, "grid", 0);
  if (mrn_lua_has(L, idx, "gather")) o->vtk_gather = mrn_lua_get_boolean(L, idx, sub, OUTPUT_SPECS, "gather", 0);
  const char *format = mrn_lua_get_string(L, idx, sub, OUTPUT_SPECS, "format");
  if (format) {
    /* the grid's .vti files stay binary beside .vtkhdf particle files */
    o->encoding = strcmp(format, "ascii") == 0 ? MRN_VTK_ASCII : MRN_VTK_BINARY;
    mrn_output_set_vtkhdf(o, strcmp(format, "vtkhdf") == 0);
  }
  if (mrn_lua_has(L, idx, "compress")) o->vtk_compress = (int)mrn_lua_get_integer(L, idx, sub, OUTPUT_SPECS, "compress");
  if (mrn_lua_has(L, idx, "float32")) o->vtk_float32 = mrn_lua_get_boolean(L, idx, sub, OUTPUT_SPECS, "float32", 0);
}

void mrn_lua_read_output(lua_State *L, int idx, const char *where, sim_box *b) {
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
  read_vtk_form(L, idx, sub, o);
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

/* the whole text of the file at path, or NULL (free it) */
static char *read_text(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  char *text = NULL;
  size_t len = 0, cap = 0;
  for (;;) {
    if (cap - len < 4096) {
      char *grown = realloc(text, cap = 2 * cap + 4096);
      if (!grown) break;
      text = grown;
    }
    size_t n = fread(text + len, 1, cap - len - 1, f);
    len += n;
    if (n == 0) {
      text[len] = '\0';
      if (ferror(f)) break;
      fclose(f);
      return text;
    }
  }
  fclose(f);
  free(text);
  return NULL;
}

void mrn_lua_describe_run(lua_State *L, const char *where, sim_box *b) {
  lua_getfield(L, LUA_REGISTRYINDEX, MRN_LUA_DECK_KEY);
  const char *deck = lua_tostring(L, -1);
  /* read again here: the deck is loaded before any simulation exists */
  char *text = deck ? read_text(deck) : NULL, *full = deck ? realpath(deck, NULL) : NULL;
  int rc = mrn_output_describe(&b->out, b->name, full ? full : deck, text);
  free(text);
  free(full);
  lua_pop(L, 1);
  if (rc != MRN_OK) mrn_lua_engine_error(L, where);
}

/* on_leave = "stop" | "delete" in the table at idx (absent: unchanged) */
void mrn_lua_read_on_leave(lua_State *L, int idx, const char *where, const mrn_spec *specs, int nspecs, mrn_sim *sim) {
  const char *policy = mrn_lua_get_string(L, idx, where, specs, nspecs, "on_leave");
  if (!policy) return;
  mrn_lua_check_choice(L, where, "on_leave", policy, mrn_leave_policy_names());
  for (int k = 0; mrn_leave_policy_names()[k]; k++)
    if (!strcmp(policy, mrn_leave_policy_names()[k])) sim->on_leave = (mrn_leave_policy)k;
}

/* the spec arguments of the getters for a key of simulation{} */
#define SIM_SPECS sim_specs, MRN_COUNT(sim_specs)

/* dim, grid, shape, gravity and shape_boundary: what mrn_sim_new needs */
static void read_config(lua_State *L, const char *where, mrn_sim_config *cfg) {
  memset(cfg, 0, sizeof *cfg);
  const int dim = (int)mrn_lua_get_integer(L, 1, where, SIM_SPECS, "dim");
  cfg->dim = dim;
  lua_getfield(L, 1, "grid");
  char gwhere[] = "simulation{} grid";
  mrn_lua_check_table(L, -1, gwhere, grid_specs, MRN_COUNT(grid_specs));
  mrn_lua_get_vector(L, -1, gwhere, grid_specs, MRN_COUNT(grid_specs), "origin", dim, cfg->origin, 0);
  mrn_lua_get_vector(L, -1, gwhere, grid_specs, MRN_COUNT(grid_specs), "size", dim, cfg->size, 1);
  cfg->cell = mrn_lua_get_number(L, -1, gwhere, grid_specs, MRN_COUNT(grid_specs), "cell");
  lua_pop(L, 1);

  cfg->shape = MRN_SHAPE_QUADRATIC_BSPLINE;
  const char *shape = mrn_lua_get_string(L, 1, where, SIM_SPECS, "shape");
  if (shape) {
    mrn_lua_check_choice(L, where, "shape", shape, mrn_shape_names());
    mrn_shape_from_name(shape, &cfg->shape);
  }
  mrn_lua_get_vector(L, 1, where, SIM_SPECS, "gravity", dim, cfg->gravity, 0);
  const char *sb = mrn_lua_get_string(L, 1, where, SIM_SPECS, "shape_boundary");
  cfg->kernel_boundary = MRN_KERNEL_EXTENDED;
  if (sb) {
    mrn_lua_check_choice(L, where, "shape_boundary", sb, mrn_kernel_boundary_names());
    mrn_kernel_boundary_from_name(sb, &cfg->kernel_boundary);
  }
}

typedef void (*option_reader)(lua_State *L, int idx, const char *where, mrn_sim *sim);

/* the key of simulation{} read by `read`, when present */
static void read_option(lua_State *L, const char *key, const char *where, mrn_sim *sim, option_reader read) {
  if (!mrn_lua_has(L, 1, key)) return;
  lua_getfield(L, 1, key);
  read(L, -1, where, sim);
  lua_pop(L, 1);
}

/* diagnostics = "file.csv" | false and series = "file.h5" | false */
static void read_diagnostics(lua_State *L, const char *where, sim_box *b) {
  long csv_every = mrn_lua_get_integer(L, 1, where, SIM_SPECS, "diagnostics_every");
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
}

/* integrator = "implicit" with its options, for the simulation at self */
static void read_integrator(lua_State *L, const char *where, int self) {
  const char *integrator = mrn_lua_get_string(L, 1, where, SIM_SPECS, "integrator");
  const int implicit = integrator && !strcmp(integrator, "implicit");
  if (mrn_lua_has(L, 1, "implicit") && !implicit)
    mrn_lua_error(L, where, "implicit: the implicit integrator's options need integrator = \"implicit\"");
  if (implicit) {
    lua_getfield(L, 1, "implicit");
    mrn_lua_implicit_configure(L, self, lua_isnil(L, -1) ? 0 : lua_gettop(L), "simulation{} implicit");
    lua_pop(L, 1);
  }
}

/* mpm.simulation{...}: the keys are read in a fixed order, so that of two
 * wrong keys the same one is always reported */
int l_simulation(lua_State *L) {
  const char *where = "simulation{}";
  mrn_lua_check_table(L, 1, where, SIM_SPECS);
  mrn_sim_config cfg;
  read_config(L, where, &cfg);

  sim_box *b = mrn_lua_sim_push(L);
  int self = lua_gettop(L);
  b->sim = mrn_sim_new(&cfg);
  if (!b->sim) mrn_lua_engine_error(L, where);
  mrn_lua_read_on_leave(L, 1, where, SIM_SPECS, b->sim);
  mrn_sim_set_sort_every(b->sim, mrn_lua_get_integer(L, 1, where, SIM_SPECS, "sort_every"));
  b->sim->mass_scaling = mrn_lua_get_number(L, 1, where, SIM_SPECS, "mass_scaling");
  for (int i = 0; i < MRN_FACE_COUNT; i++) b->sim->boundary.face[i].kind = MRN_BC_SLIP;
  mrn_output_set_csv(&b->out, "diagnostics.csv", 10);
  const char *name = mrn_lua_get_string(L, 1, where, SIM_SPECS, "name");
  snprintf(b->name, sizeof b->name, "%s", name ? name : "simulation");

  read_option(L, "scheme", "simulation{} scheme", b->sim, mrn_lua_read_scheme);
  read_option(L, "boundary", where, b->sim, mrn_lua_read_boundary);
  read_option(L, "dt", where, b->sim, mrn_lua_read_dt);
  read_option(L, "damping", where, b->sim, mrn_lua_read_damping);
  read_option(L, "split", where, b->sim, mrn_lua_read_split);
  read_option(L, "watchdog", where, b->sim, mrn_lua_read_watchdog);
  if (mrn_lua_has(L, 1, "thermo")) {
    lua_getfield(L, 1, "thermo");
    mrn_lua_read_thermo(L, -1, where, &b->thermo);
    lua_pop(L, 1);
  }
  b->progress = mrn_lua_get_boolean(L, 1, where, SIM_SPECS, "progress", 1);
  read_diagnostics(L, where, b);

  if (mrn_lua_has(L, 1, "output")) {
    lua_getfield(L, 1, "output");
    mrn_lua_read_output(L, -1, where, b);
    lua_pop(L, 1);
  }
  mrn_lua_check_outputs(L, where, &b->out, b->name);
  mrn_lua_describe_run(L, where, b);
  read_integrator(L, where, self);
  lua_pushvalue(L, self);
  return 1;
}

const mrn_spec_group mrn_lua_simulation_group = {"simulation{}", sim_specs, MRN_COUNT(sim_specs)};
const mrn_spec_group mrn_lua_grid_group = {"simulation{} grid", grid_specs, MRN_COUNT(grid_specs)};
const mrn_spec_group mrn_lua_output_group = {"simulation{} output", output_specs, MRN_COUNT(output_specs)};
