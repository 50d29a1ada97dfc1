/* moraine: sim:run{} and sim:hook{}, and the errors a run raises. */
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "core/error.h"
#include "core/log.h"
#include "io/output.h"
#include "io/summary.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"
#include "solver/suspicious.h"

static const mrn_spec run_specs[] = {
    {"time", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "model time to advance", NULL},
    {"end_time", MRN_SPEC_NUMBER, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "s", "model time to end at (absolute; instead of time)", NULL},
    {"checkpoint", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "periodic checkpoints {every, wall, keep}", NULL},
    {"steps", MRN_SPEC_INTEGER, 0, 0, 1, 1e15, 0, 0, "steps", "number of steps", NULL},
    {"thermo", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "steps",
     "thermo interval for this run, or {every, columns} (absent keys: the simulation's)", NULL},
    {"stop_when", MRN_SPEC_FUNCTION, 0, 0, 0, 0, 0, 0, NULL, "function(sim) -> true to stop", NULL},
    {"progress", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL, "progress bar for this run", NULL},
    {"output", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "VTK output settings from now on (as in simulation{})", NULL},
};

static const mrn_spec checkpoint_specs[] = {
    {"every", MRN_SPEC_INTEGER, 0, 0, 1, 1e15, 0, 0, "steps", "a checkpoint every N steps", NULL},
    {"wall", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "a checkpoint every this much wall-clock time", NULL},
    {"keep", MRN_SPEC_INTEGER, 0, 2, 0, 1e9, 0, 0, "", "the newest files kept (0: all)", NULL},
};

static const mrn_spec hook_specs[] = {
    {"every_steps", MRN_SPEC_INTEGER, 0, 0, 1, 1e15, 0, 0, "steps", "call every N steps", NULL},
    {"every_time", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "call every T of model time", NULL},
    {"at_output", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL, "call after each VTK snapshot a run writes", NULL},
    {"fn", MRN_SPEC_FUNCTION, 1, 0, 0, 0, 0, 0, NULL, "function(sim)", NULL},
};

/* hooks and stop_when run between steps: they may add particles */
static int call_between_steps(lua_State *L, int nresults) {
  sim_box *b = lua_touserdata(L, 1);
  b->between_steps = 1;
  int rc = mrn_lua_callback_pcall(L, 1, nresults);
  b->between_steps = 0;
  return rc;
}

static int call_hook(void *ctx, mrn_sim *sim) {
  (void)sim;
  lua_State *L = mrn_lua_active;
  mrn_lua_callback_push(L, ctx);
  lua_pushvalue(L, 1);
  return call_between_steps(L, 0);
}

static int call_stop_when(void *ctx, mrn_sim *sim) {
  (void)sim;
  lua_State *L = mrn_lua_active;
  mrn_lua_callback_push(L, ctx);
  lua_pushvalue(L, 1);
  int rc = call_between_steps(L, 1);
  if (rc != MRN_OK) return rc;
  int stop = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return stop ? MRN_STOP : MRN_OK;
}

/* raise the engine's message; a hook's own error already carries its location */
static int raise_engine_error(lua_State *L, int rc, const char *where, sim_box *b) {
  /* in a distributed run the hook may have failed on another process, out
   * of the deck's sight here: the state every process stopped in is kept */
  if (rc == MRN_ERR_HOOK && b->sim->dist) rc = MRN_ERR_STATE;
  if (rc == MRN_ERR_HOOK) {
    lua_pushstring(L, mrn_error_message());
    return lua_error(L);
  }
  if (rc == MRN_ERR_IO) return mrn_lua_engine_output_error(L, where);
  if (rc == MRN_ERR_STATE || rc == MRN_ERR_INTERRUPTED) {
    char note[1536];
    int written = mrn_lua_sim_write_final_state(b, rc == MRN_ERR_STATE ? "failed" : "interrupted", note, sizeof note);
    b->run.active = 0;
    b->interrupted = rc == MRN_ERR_INTERRUPTED;
    char message[2048];
    snprintf(message, sizeof message, "%s%s", mrn_error_message(), note);
    /* a state the grid cannot hold (a particle outside it) has no grid
     * values to step from or to estimate a time step on: run{} and
     * dt_estimate() refuse it */
    if (rc == MRN_ERR_STATE && mrn_sim_check_state(b->sim) != MRN_OK)
      b->invalid_step = b->sim->step > 0 ? b->sim->step : 1;
    /* what a stopped run promises to leave could not be written: exit status 3 */
    if (written != MRN_OK) return mrn_lua_output_error(L, where, "%s", message);
    return mrn_lua_error(L, where, "%s", message);
  }
  return mrn_lua_engine_error(L, where);
}

#define RUN_SPECS run_specs, MRN_COUNT(run_specs)

/* checkpoint = {every, wall, keep} of run{} at idx into the run record */
static void read_checkpoint(lua_State *L, int idx, const char *where, mrn_lua_run_record *r) {
  r->ckpt_every = 0, r->ckpt_wall = 0, r->ckpt_keep = 2;
  if (!mrn_lua_has(L, idx, "checkpoint")) return;
  lua_getfield(L, idx, "checkpoint");
  char sub[64];
  snprintf(sub, sizeof sub, "%s checkpoint", where);
  mrn_lua_check_table(L, -1, sub, checkpoint_specs, MRN_COUNT(checkpoint_specs));
  if (!mrn_lua_has(L, -1, "every") && !mrn_lua_has(L, -1, "wall"))
    mrn_lua_error(L, sub, "give every = <steps> and/or wall = <seconds>");
  if (mrn_lua_has(L, -1, "every"))
    r->ckpt_every = mrn_lua_get_integer(L, -1, sub, checkpoint_specs, MRN_COUNT(checkpoint_specs), "every");
  if (mrn_lua_has(L, -1, "wall"))
    r->ckpt_wall = mrn_lua_get_number(L, -1, sub, checkpoint_specs, MRN_COUNT(checkpoint_specs), "wall");
  r->ckpt_keep = mrn_lua_get_integer(L, -1, sub, checkpoint_specs, MRN_COUNT(checkpoint_specs), "keep");
  lua_pop(L, 1);
}

/* The target of run{} into opt and the run record. The first run{} after a
 * resume continues the run the checkpoint was in: its time and steps count
 * from that run's start, and without a target it keeps that run's. */
static void read_target(lua_State *L, const char *where, sim_box *b, mrn_run_options *opt) {
  mrn_lua_run_record *r = &b->run;
  const int continuing = b->resumed && r->active;
  const int given = mrn_lua_has(L, 2, "time") || mrn_lua_has(L, 2, "steps") || mrn_lua_has(L, 2, "end_time");
  if (mrn_lua_has(L, 2, "time") && mrn_lua_has(L, 2, "end_time"))
    mrn_lua_error(L, where, "give time (to advance) or end_time (to end at), not both");
  if (!given && !continuing) mrn_lua_error(L, where, "give time = <seconds>, end_time = <model time> and/or steps = <count>");
  if (given) {
    r->time = mrn_lua_has(L, 2, "time") ? mrn_lua_get_number(L, 2, where, RUN_SPECS, "time") : 0;
    r->steps = mrn_lua_has(L, 2, "steps") ? mrn_lua_get_integer(L, 2, where, RUN_SPECS, "steps") : 0;
    r->until = mrn_lua_has(L, 2, "end_time") ? mrn_lua_get_number(L, 2, where, RUN_SPECS, "end_time") : 0;
    read_checkpoint(L, 2, where, r);
  }
  if (!continuing) {
    r->index++;
    r->start_time = b->sim->time;
    r->start_step = b->sim->step;
    if (mrn_lua_has(L, 2, "end_time") && !(r->until > b->sim->time))
      mrn_lua_error(L, where, "end_time = %.10g is not after the simulation's time t = %.10g s", r->until, b->sim->time);
  }
  opt->time = r->time;
  opt->steps = r->steps;
  opt->until = r->until;
  /* the state a resumed simulation starts from was reported before the checkpoint */
  opt->resume = b->resumed;
  opt->resume_hooks = continuing && r->cut_short;
  opt->start_time = r->start_time;
  opt->start_step = r->start_step;
  r->active = 1;
}

/* the options of run{} at index 2 besides its target; the run's thermo
 * settings go to *thermo, which opt points into while the run lasts */
static mrn_lua_callback *read_options(lua_State *L, const char *where, sim_box *b, mrn_lua_thermo *thermo,
                                      mrn_run_options *opt) {
  *thermo = b->thermo;
  if (mrn_lua_has(L, 2, "thermo")) {
    lua_getfield(L, 2, "thermo");
    mrn_lua_read_thermo(L, -1, where, thermo);
    lua_pop(L, 1);
  }
  mrn_lua_thermo_apply(thermo, opt);
  int progress = mrn_lua_get_boolean(L, 2, where, RUN_SPECS, "progress", b->progress);
  opt->progress = progress && !mrn_log_quiet() && isatty(2);
  opt->hooks = b->hooks;
  opt->nhooks = b->nhooks;
  if (!mrn_lua_has(L, 2, "stop_when")) return NULL;
  lua_getfield(L, 2, "stop_when");
  mrn_lua_callback *stop_cb = mrn_lua_callback_new(L, -1, "stop_when");
  lua_pop(L, 1);
  opt->stop_when = call_stop_when;
  opt->stop_ctx = stop_cb;
  return stop_cb;
}

int l_sim_run(lua_State *L) {
  const char *where = "run{}";
  mrn_lua_sim_check_valid(L, 1, where);
  sim_box *b = mrn_lua_sim_check_idle(L, 1, where);
  mrn_lua_check_table(L, 2, where, RUN_SPECS);
  if (mrn_lua_restart_at_run(L, b, where) == MRN_LUA_RESTART_SKIP) return 0;
  if (b->sim->particles.n == 0 && b->sim->nsources == 0)
    mrn_lua_error(L, where, "the simulation has no particles (add_particles or add_source first)");
  mrn_lua_implicit_prepare(L, 1, where); /* integrator = "implicit": made at the first run */
  /* a resumed simulation keeps the outputs the checkpoint continues */
  if (mrn_lua_has(L, 2, "output") && !b->resumed) {
    lua_getfield(L, 2, "output");
    mrn_lua_read_output(L, -1, where, b);
    lua_pop(L, 1);
  }
  if (!b->resumed && mrn_output_claim(&b->out, mrn_lua_overwrite(L)) != MRN_OK) mrn_lua_engine_error(L, where);
  mrn_run_options opt;
  memset(&opt, 0, sizeof opt);
  read_target(L, where, b, &opt);
  mrn_lua_thermo thermo;
  mrn_lua_callback *stop_cb = read_options(L, where, b, &thermo, &opt);
  lua_settop(L, 2); /* callbacks find the simulation at index 1 */
  mrn_lua_active = L;
  mrn_suspicious_run(b->sim);
  b->busy = where;
  /* the run knows no file format; the checkpoints follow the outputs' rows */
  mrn_run_observer observers[2] = {mrn_output_observer(&b->out), mrn_lua_checkpoint_observer(b)};
  opt.observers = observers;
  opt.nobservers = b->run.ckpt_every > 0 || b->run.ckpt_wall > 0 ? 2 : 1;
  const long step0 = b->sim->step;
  const double t0 = b->sim->time;
  int rc = mrn_run(b->sim, &opt);
  mrn_summary_add_run(&b->summary_record, b->name, step0, t0, b->sim, &opt.stats);
  b->run.cut_short = opt.cut_short; /* kept by the checkpoint a stop writes */
  b->busy = NULL;
  b->resumed = 0;
  mrn_lua_callback_release(stop_cb);
  if (rc != MRN_OK) return raise_engine_error(L, rc, where, b);
  b->run.active = 0;
  return 0;
}

int l_sim_hook(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *where = "hook{}";
  mrn_lua_check_table(L, 2, where, hook_specs, MRN_COUNT(hook_specs));
  int has_steps = mrn_lua_has(L, 2, "every_steps"), has_time = mrn_lua_has(L, 2, "every_time");
  int at_output = mrn_lua_get_boolean(L, 2, where, hook_specs, MRN_COUNT(hook_specs), "at_output", 0);
  if (has_steps + has_time + at_output != 1)
    mrn_lua_error(L, where, "give exactly one of every_steps, every_time or at_output = true");
  if (b->nhooks == MRN_LUA_MAX_HOOKS) mrn_lua_error(L, where, "at most %d hooks per simulation", MRN_LUA_MAX_HOOKS);
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

const mrn_spec_group mrn_lua_run_group = {"run{}", run_specs, MRN_COUNT(run_specs)};
const mrn_spec_group mrn_lua_checkpoint_group = {"run{} checkpoint", checkpoint_specs, MRN_COUNT(checkpoint_specs)};
const mrn_spec_group mrn_lua_hook_group = {"hook{}", hook_specs, MRN_COUNT(hook_specs)};
