/* moraine: checkpoints of the simulation object — sim:save(), mpm.load(),
 * sim:import() — and those a stopped run or a signal leaves behind. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/error.h"
#include "core/log.h"
#include "io/atomic_file.h"
#include "io/checkpoint.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"
#include "lua/lua_safe.h"

/* a relative path is in the output directory; the joined path stays on the stack */
static const char *output_path(lua_State *L, sim_box *b, const char *path) {
  if (path[0] == '/') return path;
  char *joined = mrn_path_join(b->out.dir, path);
  lua_pushstring(L, joined);
  free(joined);
  return lua_tostring(L, -1);
}

/* sim:save(path): the complete state, relative paths in the output directory */
int l_sim_save(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *path = output_path(L, b, luaL_checkstring(L, 2));
  mrn_lua_check_write(L, "save()", path);
  if (mrn_mkdir_p(b->out.dir) != MRN_OK) mrn_lua_engine_error(L, "save()");
  /* between runs the file also holds what mpm.resume needs; inside one the
   * step's outputs are not written yet, so it holds the state only */
  int rc = b->busy ? mrn_checkpoint_save(b->sim, path) : mrn_lua_sim_save(b, path);
  if (rc != MRN_OK) mrn_lua_engine_output_error(L, "save()");
  lua_pushstring(L, path);
  return 1;
}

static const mrn_spec load_specs[] = {
    {"name", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "label of the loaded simulation", NULL},
    {"thermo", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "steps",
     "thermo line every N steps (default 100, 0: none), or {every, columns}", NULL},
    {"diagnostics", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "CSV file name, or false", NULL},
    {"output", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "VTK output settings, as in simulation{}", NULL},
    {"on_leave", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "a particle leaving the grid: stop or delete (default: as saved)", NULL},
    {"sort_every", MRN_SPEC_INTEGER, 0, 0, 0, 1e12, 0, 0, "steps",
     "reorder the particles by grid block every N explicit steps (default: as saved)", NULL},
};

/* mpm.load(path [, options]): a simulation continuing from a checkpoint */
int l_load(lua_State *L) {
  const char *where = "load()";
  const char *path = luaL_checkstring(L, 1);
  int has_opts = !lua_isnoneornil(L, 2);
  if (has_opts) mrn_lua_check_table(L, 2, where, load_specs, MRN_COUNT(load_specs));
  /* a relative path is looked for as given, then in the output directory */
  if (path[0] != '/' && access(path, F_OK) != 0) {
    char *joined = mrn_path_join(mrn_lua_output_dir(L), path);
    if (access(joined, F_OK) == 0) {
      lua_pushstring(L, joined);
      path = lua_tostring(L, -1);
    }
    free(joined);
  }
  sim_box *b = mrn_lua_sim_push(L);
  int self = lua_gettop(L);
  mrn_checkpoint_info info;
  b->sim = mrn_checkpoint_load_info(path, &info);
  if (!b->sim) mrn_lua_engine_error(L, where);
  mrn_lua_rebind_user_materials(L, b->sim, where);
  if (info.dt_function_dropped) mrn_warn("%s", info.note);
  snprintf(b->name, sizeof b->name, "%s", "loaded");
  mrn_output_set_csv(&b->out, "diagnostics.csv", 10);
  mrn_output_set_series(&b->out, "diagnostics.h5");
  if (has_opts) {
    const char *name = mrn_lua_get_string(L, 2, where, load_specs, MRN_COUNT(load_specs), "name");
    if (name) snprintf(b->name, sizeof b->name, "%s", name);
    if (mrn_lua_has(L, 2, "thermo")) {
      lua_getfield(L, 2, "thermo");
      mrn_lua_read_thermo(L, -1, where, &b->thermo);
      lua_pop(L, 1);
    }
    lua_getfield(L, 2, "diagnostics");
    if (lua_type(L, -1) == LUA_TSTRING) mrn_output_set_csv(&b->out, lua_tostring(L, -1), 10);
    else if (lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1)) {
      mrn_output_set_csv(&b->out, NULL, 10);
      mrn_output_set_series(&b->out, NULL);
    }
    lua_pop(L, 1);
    if (mrn_lua_has(L, 2, "output")) {
      lua_getfield(L, 2, "output");
      mrn_lua_read_output(L, -1, where, b);
      lua_pop(L, 1);
    }
    mrn_lua_read_on_leave(L, 2, where, load_specs, MRN_COUNT(load_specs), b->sim);
    if (mrn_lua_has(L, 2, "sort_every"))
      mrn_sim_set_sort_every(b->sim, mrn_lua_get_integer(L, 2, where, load_specs, MRN_COUNT(load_specs), "sort_every"));
  }
  mrn_lua_check_outputs(L, where, &b->out, b->name);
  mrn_lua_describe_run(L, where, b);
  lua_pushvalue(L, self);
  return 1;
}

static const mrn_spec import_specs[] = {
    {"material", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "a material for every imported particle (default: the saved ones)", NULL},
    {"offset", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "added to every position", NULL},
};

/* sim:import(path [, {material = m, offset = {...}}]): particles of a checkpoint */
int l_sim_import(lua_State *L) {
  const char *where = "import()";
  sim_box *b = mrn_lua_sim_check_idle(L, 1, where);
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

int mrn_lua_sim_write_final_state(sim_box *b, const char *why, char *note, size_t len) {
  note[0] = '\0';
  char file[96];
  snprintf(file, sizeof file, "%s_%s.h5", b->name, why);
  char *path = mrn_path_join(b->out.dir, file);
  char saved[2048];
  snprintf(saved, sizeof saved, "%s", mrn_error_message()); /* the writes may overwrite it */
  int rc = mrn_mkdir_p(b->out.dir);
  if (rc == MRN_OK) rc = mrn_lua_sim_save(b, path);
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
  if (lua_getfield(L, LUA_REGISTRYINDEX, MRN_LUA_SIMULATIONS) != LUA_TTABLE) {
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
    if (mrn_lua_sim_write_final_state(b, "interrupted", note, sizeof note) != MRN_OK) output = 1;
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

const mrn_spec_group mrn_lua_load_group = {"load()", load_specs, MRN_COUNT(load_specs)};
const mrn_spec_group mrn_lua_import_group = {"import()", import_specs, MRN_COUNT(import_specs)};
