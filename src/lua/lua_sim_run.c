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
    {"steps", MRN_SPEC_INTEGER, 0, 0, 1, 1e15, 0, 0, "steps", "number of steps", NULL},
    {"thermo", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, "steps",
     "thermo interval for this run, or {every, columns} (absent keys: the simulation's)", NULL},
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

/* raise the engine's message; a hook's own error already carries its location */
static int raise_engine_error(lua_State *L, int rc, const char *where, sim_box *b) {
  if (rc == MRN_ERR_HOOK) {
    lua_pushstring(L, mrn_error_message());
    return lua_error(L);
  }
  if (rc == MRN_ERR_IO) return mrn_lua_engine_output_error(L, where);
  if (rc == MRN_ERR_STATE || rc == MRN_ERR_INTERRUPTED) {
    char note[1536];
    int written = mrn_lua_sim_write_final_state(b, rc == MRN_ERR_STATE ? "failed" : "interrupted", note, sizeof note);
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

int l_sim_run(lua_State *L) {
  const char *where = "run{}";
  mrn_lua_sim_check_valid(L, 1, where);
  sim_box *b = mrn_lua_sim_check_idle(L, 1, where);
  mrn_lua_check_table(L, 2, where, run_specs, MRN_COUNT(run_specs));
  if (!mrn_lua_has(L, 2, "time") && !mrn_lua_has(L, 2, "steps"))
    mrn_lua_error(L, where, "give time = <seconds> and/or steps = <count>");
  if (b->sim->particles.n == 0) mrn_lua_error(L, where, "the simulation has no particles (add_particles first)");
  mrn_lua_implicit_prepare(L, 1, where); /* integrator = "implicit": made at the first run */
  if (mrn_lua_has(L, 2, "output")) {
    lua_getfield(L, 2, "output");
    mrn_lua_read_output(L, -1, where, b);
    lua_pop(L, 1);
  }
  mrn_run_options opt;
  memset(&opt, 0, sizeof opt);
  opt.time = mrn_lua_has(L, 2, "time") ? mrn_lua_get_number(L, 2, where, run_specs, MRN_COUNT(run_specs), "time") : 0;
  opt.steps = mrn_lua_has(L, 2, "steps") ? mrn_lua_get_integer(L, 2, where, run_specs, MRN_COUNT(run_specs), "steps") : 0;
  mrn_lua_thermo thermo = b->thermo;
  if (mrn_lua_has(L, 2, "thermo")) {
    lua_getfield(L, 2, "thermo");
    mrn_lua_read_thermo(L, -1, where, &thermo);
    lua_pop(L, 1);
  }
  mrn_lua_thermo_apply(&thermo, &opt);
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
  mrn_run_observer writers = mrn_output_observer(&b->out); /* the run knows no file format */
  opt.observers = &writers;
  opt.nobservers = 1;
  const long step0 = b->sim->step;
  const double t0 = b->sim->time;
  int rc = mrn_run(b->sim, &opt);
  mrn_summary_add_run(&b->summary_record, b->name, step0, t0, b->sim, &opt.stats);
  b->busy = NULL;
  mrn_lua_callback_release(stop_cb);
  if (rc != MRN_OK) return raise_engine_error(L, rc, where, b);
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
const mrn_spec_group mrn_lua_hook_group = {"hook{}", hook_specs, MRN_COUNT(hook_specs)};
