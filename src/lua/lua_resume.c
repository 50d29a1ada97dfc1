/* moraine: continuing a run from a checkpoint — mpm.resume(), the plan of
 * --restart FILE, the values a checkpoint keeps for them, and the periodic
 * checkpoints of run{ checkpoint = ... }. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "core/error.h"
#include "grid/wall.h"
#include "core/log.h"
#include "io/atomic_file.h"
#include "io/checkpoint.h"
#include "lua/lua_check.h"
#include "lua/lua_safe.h"
#include "lua/lua_sim.h"

#define RESTART_KEY "moraine.restart"   /* registry: the plan of --restart, a table */
#define OVERWRITE_KEY "moraine.overwrite" /* registry: true with --overwrite */

/* ---- what a checkpoint keeps ------------------------------------------------------ */

static void stash_run(mrn_lua_run_record *r, mrn_stash *s) {
  mrn_stash_long(s, "run.index", &r->index);
  mrn_stash_int(s, "run.active", &r->active);
  mrn_stash_int(s, "run.cut_short", &r->cut_short);
  mrn_stash_real(s, "run.start_time", &r->start_time);
  mrn_stash_long(s, "run.start_step", &r->start_step);
  mrn_stash_real(s, "run.time", &r->time);
  mrn_stash_long(s, "run.steps", &r->steps);
  mrn_stash_real(s, "run.end_time", &r->until);
  mrn_stash_long(s, "run.checkpoint_every", &r->ckpt_every);
  mrn_stash_real(s, "run.checkpoint_wall", &r->ckpt_wall);
  mrn_stash_long(s, "run.checkpoint_keep", &r->ckpt_keep);
}

/* the thermo settings: the interval, and the columns as one text "a,b,c"
 * ("" for the default ones) */
static void stash_thermo(mrn_lua_thermo *t, mrn_stash *s) {
  mrn_stash_long(s, "thermo", &t->every);
  char joined[MRN_THERMO_MAX_COLUMNS * 32] = "";
  for (int i = 0; i < t->ncolumns; i++) {
    if (i) strcat(joined, ",");
    strncat(joined, mrn_thermo_column_name(t->columns[i]), 30);
  }
  char *text = strdup(joined);
  mrn_stash_text(s, "thermo_columns", &text);
  if (s->loading) {
    t->ncolumns = 0;
    for (char *c = text ? strtok(text, ",") : NULL; c && t->ncolumns < MRN_THERMO_MAX_COLUMNS; c = strtok(NULL, ","))
      if (mrn_thermo_column(c) >= 0) t->columns[t->ncolumns++] = mrn_thermo_column(c);
  }
  free(text);
}

void mrn_lua_sim_stash(sim_box *b, mrn_stash *s) {
  char *name = strdup(b->name);
  mrn_stash_text(s, "name", &name);
  if (s->loading && name) snprintf(b->name, sizeof b->name, "%s", name);
  free(name);
  stash_thermo(&b->thermo, s);
  stash_run(&b->run, s);
  mrn_output_stash(&b->out, s);
}

int mrn_lua_sim_save(sim_box *b, const char *path) {
  mrn_stash s;
  mrn_stash_init(&s, 0);
  mrn_lua_sim_stash(b, &s);
  int rc = mrn_checkpoint_save_stash(b->sim, &s, path);
  mrn_stash_free(&s);
  return rc;
}

/* ---- taking a checkpoint ------------------------------------------------------------ */

/* What a deck sets on its simulation that a checkpoint does not hold — the
 * regions' velocity constraints, the sources, the watchdog's bounds, a dt
 * function, the walls' motion functions, the bodies and contact pairs —
 * carried from the deck's simulation to the loaded one. */
static void carry_deck_settings(mrn_sim *to, mrn_sim *from, int dt_function_dropped) {
  if (!from) return;
  to->constraints = from->constraints, to->nconstraints = from->nconstraints;
  from->constraints = NULL, from->nconstraints = 0;
  mrn_sim_move_sources(to, from); /* each takes up its progress from the checkpoint */
  to->watchdog = from->watchdog;
  /* the bodies' names and contact pairs: the checkpoint holds only each
   * particle's body index, which the deck's names follow in its order */
  if (from->contact && !to->contact) to->contact = from->contact, from->contact = NULL;
  /* a wall's motion function, to the loaded wall of the same name */
  for (int i = 0; from->boundary.walls && i < from->boundary.walls->count; i++) {
    mrn_wall *f = &from->boundary.walls->wall[i], *t = mrn_walls_find(to->boundary.walls, f->spec.name);
    if (!t || !f->motion || t->motion) continue;
    t->motion = f->motion, t->motion_ctx = f->motion_ctx, t->motion_release = f->motion_release;
    f->motion = NULL, f->motion_ctx = NULL, f->motion_release = NULL;
  }
  if (dt_function_dropped && from->dt_policy.kind == MRN_DT_CALLBACK) {
    mrn_dt_policy keep = to->dt_policy;
    to->dt_policy = from->dt_policy;
    from->dt_policy = keep;
  }
}

/* the checkpoint at path into b: its state (replacing b's simulation, if
 * any), name, outputs and run record; its files continued */
static void take_checkpoint(lua_State *L, sim_box *b, const char *path, const char *where) {
  mrn_stash *s = &b->taking;
  mrn_stash_free(s);
  if (mrn_checkpoint_read_stash(path, s) != MRN_OK) mrn_lua_engine_error(L, where);
  if (!mrn_stash_find(s, "run.index") || !mrn_stash_find(s, "output.vtk_count"))
    mrn_lua_error(L, where, "'%s' holds no run to continue (a checkpoint of sim:save() made inside a run, or of an "
                  "older moraine): load it with mpm.load", path);
  mrn_checkpoint_info info;
  mrn_sim *sim = mrn_checkpoint_load_info(path, &info);
  if (!sim) mrn_lua_engine_error(L, where);
  carry_deck_settings(sim, b->sim, info.dt_function_dropped);
  mrn_lua_rebind_user_materials(L, sim, where);
  if (b->sim) mrn_sim_free(b->sim);
  b->sim = sim;
  char *dir = strdup(b->out.dir);
  mrn_output_free(&b->out);
  mrn_output_init(&b->out, dir);
  free(dir);
  memset(&b->run, 0, sizeof b->run);
  mrn_lua_sim_stash(b, s);
  mrn_lua_describe_run(L, where, b); /* the series' record of the run, as a new simulation has it */
  const char *names[] = {b->out.vtk_name, b->out.csv_name, b->out.series_name, b->out.series_file};
  for (int i = 0; i < 4; i++)
    if (names[i] && (names[i][0] == '/' || strstr(names[i], "..")))
      mrn_lua_error(L, where, "'%s': output file '%s' is not inside the output directory", path, names[i]);
  mrn_lua_check_outputs(L, where, &b->out, b->name);
  int rc = mrn_output_resume(&b->out, s);
  mrn_stash_free(s);
  if (rc != MRN_OK) mrn_lua_engine_output_error(L, where);
  b->resumed = 1;
  b->ckpt_last_step = sim->step;
  b->interrupted = 0;
  b->invalid_step = 0;
}

/* a relative path as given, else in the output directory; the result stays on the stack */
static const char *find_checkpoint(lua_State *L, const char *path) {
  if (path[0] == '/' || access(path, F_OK) == 0) {
    lua_pushstring(L, path);
  } else {
    char *joined = mrn_path_join(mrn_lua_output_dir(L), path);
    lua_pushstring(L, access(joined, F_OK) == 0 ? joined : path);
    free(joined);
  }
  return lua_tostring(L, -1);
}

/* mpm.resume(path): the simulation of a checkpoint, continuing its run and files */
int l_resume(lua_State *L) {
  const char *where = "resume()";
  const char *path = find_checkpoint(L, luaL_checkstring(L, 1));
  sim_box *b = mrn_lua_sim_push(L);
  take_checkpoint(L, b, path, where);
  return 1;
}

/* ---- --restart FILE ------------------------------------------------------------------ */

int mrn_lua_overwrite(lua_State *L) {
  lua_getfield(L, LUA_REGISTRYINDEX, OVERWRITE_KEY);
  int on = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return on;
}

void mrn_lua_restart_open(lua_State *L, const char *path) {
  const char *where = "--restart";
  mrn_stash s;
  if (mrn_checkpoint_read_stash(path, &s) != MRN_OK) mrn_lua_engine_error(L, where);
  const mrn_stash_value *name = mrn_stash_find(&s, "name"), *index = mrn_stash_find(&s, "run.index");
  const mrn_stash_value *active = mrn_stash_find(&s, "run.active");
  if (!name || !index || !active || name->kind != MRN_STASH_TEXT) {
    mrn_stash_free(&s);
    mrn_lua_error(L, where, "'%s' holds no run to continue (a checkpoint of sim:save() made inside a run, or of an "
                  "older moraine)", path);
  }
  lua_createtable(L, 0, 5);
  lua_pushstring(L, path), lua_setfield(L, -2, "path");
  lua_pushstring(L, name->text), lua_setfield(L, -2, "name");
  /* the deck's run{} call the checkpoint is in, or the one after those it finished */
  lua_pushinteger(L, (lua_Integer)index->integer + (active->integer ? 0 : 1)), lua_setfield(L, -2, "run");
  lua_pushboolean(L, 0), lua_setfield(L, -2, "done");
  lua_setfield(L, LUA_REGISTRYINDEX, RESTART_KEY);
  mrn_stash_free(&s);
}

int mrn_lua_restart_at_run(lua_State *L, sim_box *b, const char *where) {
  if (lua_getfield(L, LUA_REGISTRYINDEX, RESTART_KEY) != LUA_TTABLE) {
    lua_pop(L, 1);
    return MRN_LUA_RESTART_NONE;
  }
  int plan = lua_gettop(L);
  lua_getfield(L, plan, "done");
  lua_getfield(L, plan, "name");
  int mine = !lua_toboolean(L, -2) && !strcmp(lua_tostring(L, -1), b->name);
  lua_pop(L, 2);
  if (!mine) {
    lua_pop(L, 1);
    return MRN_LUA_RESTART_NONE;
  }
  lua_getfield(L, plan, "run");
  long target = (long)lua_tointeger(L, -1), call = b->run.index + 1;
  lua_getfield(L, plan, "path");
  const char *path = lua_tostring(L, -1);
  if (call < target) {
    mrn_info("--restart: run{} #%ld of '%s' skipped (the checkpoint continues run{} #%ld)", call, b->name, target);
    b->run.index = call;
    lua_pop(L, 3);
    return MRN_LUA_RESTART_SKIP;
  }
  mrn_info("--restart: '%s' continues from %s", b->name, path);
  take_checkpoint(L, b, path, where);
  lua_pushboolean(L, 1);
  lua_setfield(L, plan, "done");
  lua_pop(L, 3);
  return MRN_LUA_RESTART_HERE;
}

const char *mrn_lua_restart_unfinished(lua_State *L) {
  if (lua_getfield(L, LUA_REGISTRYINDEX, RESTART_KEY) != LUA_TTABLE) {
    lua_pop(L, 1);
    return NULL;
  }
  lua_getfield(L, -1, "done");
  int done = lua_toboolean(L, -1);
  lua_pop(L, 1);
  if (done) {
    lua_pop(L, 1);
    return NULL;
  }
  lua_getfield(L, -1, "path");
  lua_getfield(L, -2, "name");
  lua_getfield(L, -3, "run");
  const char *msg = lua_pushfstring(L, "--restart '%s': the deck never reached run{} #%I of a simulation named '%s', "
                                    "which the checkpoint continues (give the deck that wrote it)",
                                    lua_tostring(L, -3), lua_tointeger(L, -1), lua_tostring(L, -2));
  lua_replace(L, -5);
  lua_pop(L, 3);
  return msg;
}

/* ---- periodic checkpoints -------------------------------------------------------------- */

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int checkpoint_due(void *ctx, const mrn_sim *sim, mrn_run_moment when) {
  const sim_box *b = ctx;
  if (when != MRN_RUN_STEP || sim->step == b->ckpt_last_step) return 0;
  if (b->run.ckpt_every > 0 && sim->step % b->run.ckpt_every == 0) return 1;
  return b->run.ckpt_wall > 0 && wall_now() >= b->ckpt_next_wall;
}

static int newest_first(const void *a, const void *b) { return strcmp(*(char *const *)b, *(char *const *)a); }

/* the newest `keep` of OUTDIR/<name>_checkpoint_NNNNNNNNNN.h5 stay */
static void prune_checkpoints(const sim_box *b) {
  char prefix[96];
  int len = snprintf(prefix, sizeof prefix, "%s_checkpoint_", b->name);
  DIR *d = opendir(b->out.dir);
  char *names[256];
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d)) && n < 256;)
    if (!strncmp(e->d_name, prefix, (size_t)len) && strspn(e->d_name + len, "0123456789") == 10 &&
        !strcmp(e->d_name + len + 10, ".h5"))
      names[n++] = strdup(e->d_name);
  if (d) closedir(d);
  qsort(names, (size_t)n, sizeof *names, newest_first);
  for (int i = 0; i < n; i++) {
    if (i >= b->run.ckpt_keep) {
      char *path = mrn_path_join(b->out.dir, names[i]);
      unlink(path);
      free(path);
    }
    free(names[i]);
  }
}

/* after the outputs' row of the step (observers run in order): every row
 * and snapshot so far on disk, then the checkpoint */
static int checkpoint_now(void *ctx, const mrn_sim *sim, const mrn_diagnostics *d) {
  (void)d;
  sim_box *b = ctx;
  char file[128];
  snprintf(file, sizeof file, "%s_checkpoint_%010ld.h5", b->name, sim->step);
  char *path = mrn_path_join(b->out.dir, file);
  int rc = mrn_output_flush(&b->out);
  if (rc == MRN_OK) rc = mrn_mkdir_p(b->out.dir);
  if (rc == MRN_OK) rc = mrn_lua_sim_save(b, path);
  free(path);
  if (rc == MRN_OK && b->run.ckpt_keep > 0) prune_checkpoints(b);
  b->ckpt_next_wall = wall_now() + b->run.ckpt_wall;
  b->ckpt_last_step = sim->step;
  return rc;
}

mrn_run_observer mrn_lua_checkpoint_observer(sim_box *b) {
  b->ckpt_next_wall = wall_now() + b->run.ckpt_wall;
  return (mrn_run_observer){NULL, checkpoint_due, checkpoint_now, b};
}
