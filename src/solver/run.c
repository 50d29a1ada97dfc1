#include "solver/run.h"
#include "solver/dist.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/log.h"

/* ---- thermo lines ----------------------------------------------------------
 * A column is one of the run's own (below) or, from THERMO_OWN on, a column
 * of the diagnostics table (solver/diagnostics.c) */
static const char *const own_columns[] = {"step", "time", "dt", "steps_per_s"};
enum { THERMO_STEP, THERMO_TIME, THERMO_DT, THERMO_RATE, THERMO_OWN };
/* the columns of a run that names none */
static const char *const default_columns[] = {"step", "time", "dt", "E_kinetic", "E_gravity", "E_elastic", "E_total",
                                              "W_friction"};

int mrn_thermo_column_count(void) { return THERMO_OWN + mrn_diagnostics_column_count(); }

const char *mrn_thermo_column_name(int i) {
  if (i < 0 || i >= mrn_thermo_column_count()) return NULL;
  return i < THERMO_OWN ? own_columns[i] : mrn_diagnostics_column_name(i - THERMO_OWN);
}

int mrn_thermo_column(const char *name) {
  for (int i = 0; i < mrn_thermo_column_count(); i++)
    if (!strcmp(mrn_thermo_column_name(i), name)) return i;
  return -1;
}

int mrn_thermo_default_columns(int *columns) {
  const int n = (int)(sizeof default_columns / sizeof default_columns[0]);
  for (int i = 0; i < n; i++) columns[i] = mrn_thermo_column(default_columns[i]);
  return n;
}

/* the width of a column: those of the default line, which has always had them */
static int column_width(int c) { return c == THERMO_DT || c == THERMO_RATE ? 11 : c == THERMO_STEP ? 10 : 13; }

/* the run's columns: its own, or the defaults written into `buf` */
static int thermo_columns(const mrn_run_options *opt, int *buf, const int **columns) {
  if (opt->thermo_ncolumns > 0) {
    *columns = opt->thermo_columns;
    return opt->thermo_ncolumns;
  }
  *columns = buf;
  return mrn_thermo_default_columns(buf);
}

/* the screen's stream for thermo output: none with --quiet (the log still gets it) */
static FILE *thermo_screen(void) { return mrn_log_quiet() ? NULL : stdout; }

static void thermo_header(const mrn_run_options *opt) {
  int buf[MRN_THERMO_MAX_COLUMNS];
  const int *columns;
  const int n = thermo_columns(opt, buf, &columns);
  char line[MRN_THERMO_MAX_COLUMNS * 24 + 2];
  size_t len = 0;
  for (int i = 0; i < n; i++)
    len += (size_t)snprintf(line + len, sizeof line - len, "%s%*s", i ? " " : "", column_width(columns[i]),
                            mrn_thermo_column_name(columns[i]));
  line[len++] = '\n';
  mrn_log_text(thermo_screen(), line, len);
}

/* one value of a thermo line */
static int thermo_value(char *out, size_t size, int c, const mrn_sim *sim, const double *diag, double rate) {
  const int w = column_width(c);
  switch (c) {
  case THERMO_STEP: return snprintf(out, size, "%*ld", w, sim->step);
  case THERMO_TIME: return snprintf(out, size, "%*.6e", w, sim->time);
  case THERMO_DT: return snprintf(out, size, "%*.4e", w, sim->dt);
  case THERMO_RATE: return snprintf(out, size, "%*.4g", w, rate);
  default: break;
  }
  if (!strcmp(mrn_thermo_column_name(c), "particles")) return snprintf(out, size, "%*.0f", w, diag[c - THERMO_OWN]);
  return snprintf(out, size, "%*.6e", w, diag[c - THERMO_OWN]);
}

static void thermo_line(const mrn_run_options *opt, const mrn_sim *sim, const mrn_diagnostics *d, double rate) {
  int buf[MRN_THERMO_MAX_COLUMNS];
  const int *columns;
  const int n = thermo_columns(opt, buf, &columns);
  double diag[64];
  mrn_diagnostics_values(d, diag);
  char line[MRN_THERMO_MAX_COLUMNS * 40 + 2];
  size_t len = 0;
  for (int i = 0; i < n; i++) {
    if (i) line[len++] = ' ';
    len += (size_t)thermo_value(line + len, sizeof line - len - 1, columns[i], sim, diag, rate);
  }
  line[len++] = '\n';
  mrn_log_text(thermo_screen(), line, len);
}

static double wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* what a run keeps between its steps */
typedef struct run_clock {
  double wall_start, last_draw;
  double t_start, t_end; /* the run's model time span (t_end HUGE_VAL: none) */
  long step_start;
  long thermo_step;   /* the step of the last thermo line */
  double thermo_wall; /* and when it was printed */
} run_clock;

/* ---- the progress bar ------------------------------------------------------ */

static void draw_progress(double fraction, double elapsed) {
  if (fraction < 0) fraction = 0;
  if (fraction > 1) fraction = 1;
  enum { WIDTH = 30 };
  int filled = (int)(fraction * WIDTH);
  long eta = fraction > 1e-6 ? lround(elapsed * (1 - fraction) / fraction) : 0;
  char text[WIDTH + 64];
  int len = snprintf(text, sizeof text, "[");
  for (int i = 0; i < WIDTH; i++) text[len++] = i < filled ? '#' : '.';
  snprintf(text + len, sizeof text - (size_t)len, "] %5.1f%%  ETA %ld:%02ld:%02ld", 100 * fraction, eta / 3600,
           eta / 60 % 60, eta % 60);
  mrn_log_bar(text);
}

static void update_progress(const mrn_sim *sim, const mrn_run_options *opt, run_clock *clk) {
  double now = wall_seconds();
  if (now - clk->last_draw <= 0.25) return;
  double f_time = clk->t_end < HUGE_VAL ? (sim->time - clk->t_start) / (clk->t_end - clk->t_start) : 0;
  double f_steps = opt->steps > 0 ? (double)(sim->step - clk->step_start) / opt->steps : 0;
  draw_progress(f_time > f_steps ? f_time : f_steps, now - clk->wall_start);
  clk->last_draw = now;
}

static int due_hook(mrn_hook *h, const mrn_sim *sim) {
  int due = 0;
  if (h->every_steps > 0 && sim->step % h->every_steps == 0) due = 1;
  if (h->every_time > 0) {
    double tol = 1e-9 * h->every_time;
    if (sim->time >= h->next_time - tol) {
      due = 1;
      while (h->next_time <= sim->time + tol) h->next_time += h->every_time;
    }
  }
  return due;
}

static int call_hooks_at_output(mrn_sim *sim, mrn_run_options *opt) {
  int rc;
  for (int i = 0; i < opt->nhooks; i++)
    if (opt->hooks[i].at_output && (rc = opt->hooks[i].fn(opt->hooks[i].ctx, sim)) != 0) return rc;
  return MRN_OK;
}

/* the observers' snapshots; the hooks that follow a snapshot run once after
 * them when any observer wrote one */
static int report_snapshots(mrn_sim *sim, mrn_run_options *opt) {
  int rc, wrote = 0;
  for (int i = 0; i < opt->nobservers; i++) {
    const mrn_run_observer *ob = &opt->observers[i];
    int w = 0;
    if (ob->snapshot && (rc = ob->snapshot(ob->ctx, sim, &w)) != MRN_OK) return rc;
    wrote |= w;
  }
  return wrote ? call_hooks_at_output(sim, opt) : MRN_OK;
}

static int row_due(const mrn_run_observer *ob, const mrn_sim *sim, mrn_run_moment when) {
  return ob->row && (!ob->row_due || ob->row_due(ob->ctx, sim, when));
}

/* the thermo output is due when a line goes to the screen or the log */
static int thermo_on(const mrn_run_options *opt) {
  return opt->thermo_every > 0 && (!mrn_log_quiet() || mrn_log_fd() >= 0);
}

/* steps per second of wall time since the last thermo line (0 for the first) */
static double thermo_rate(const mrn_sim *sim, run_clock *clk) {
  const double now = wall_seconds(), span = now - clk->thermo_wall;
  const double rate = sim->step > clk->thermo_step && span > 0 ? (sim->step - clk->thermo_step) / span : 0.0;
  clk->thermo_step = sim->step;
  clk->thermo_wall = now;
  return rate;
}

/* The thermo line and the observers' rows of this state. The diagnostics sum
 * over every particle: computed once, and only when a line or a row is due.
 * The thermo line comes on its cadence and at the start; at the end only when
 * the cadence has not just printed this state. */
static int report_rows(mrn_sim *sim, mrn_run_options *opt, mrn_run_moment when, run_clock *clk) {
  const long every = opt->thermo_every;
  const int on_cadence = every > 0 && sim->step % every == 0;
  const int thermo = thermo_on(opt) && (when == MRN_RUN_START || (when == MRN_RUN_STEP ? on_cadence : !on_cadence));
  int due = thermo;
  for (int i = 0; i < opt->nobservers && !due; i++) due = row_due(&opt->observers[i], sim, when);
  if (!due) return MRN_OK;
  mrn_diagnostics d;
  mrn_sim_diagnostics(sim, &d);
  if (thermo) thermo_line(opt, sim, &d, thermo_rate(sim, clk));
  for (int i = 0; i < opt->nobservers; i++) {
    const mrn_run_observer *ob = &opt->observers[i];
    int rc;
    if (row_due(ob, sim, when) && (rc = ob->row(ob->ctx, sim, &d)) != MRN_OK) return rc;
  }
  return MRN_OK;
}

/* hooks, observers and thermo for the state just reached; returns 0, MRN_STOP or an error */
static int after_step(mrn_sim *sim, mrn_run_options *opt, int first, run_clock *clk) {
  int rc = MRN_OK;
  for (int i = 0; i < opt->nhooks && rc == MRN_OK; i++)
    if (due_hook(&opt->hooks[i], sim)) rc = opt->hooks[i].fn(opt->hooks[i].ctx, sim);
  /* a hook that failed or stopped on one process stops all before the
   * snapshots and rows, which every process takes part in */
  if ((rc = mrn_dist_agree(sim, rc)) != MRN_OK) return rc;
  if ((rc = report_snapshots(sim, opt)) != MRN_OK) return rc;
  if ((rc = report_rows(sim, opt, first ? MRN_RUN_START : MRN_RUN_STEP, clk)) != MRN_OK) return rc;
  if (!first && opt->stop_when && (rc = opt->stop_when(opt->stop_ctx, sim)) != 0) return rc;
  return MRN_OK;
}

/* one step of either integrator: MRN_OK, MRN_STEP_NONE when the run is over, or an error */
static int take_step(mrn_sim *sim, const mrn_run_options *opt, double t_end) {
  if (sim->integrator.step) return sim->integrator.step(sim->integrator.ctx, sim, t_end);
  double dt;
  int rc;
  if ((rc = mrn_dt_compute(sim, &dt)) != MRN_OK) return rc;
  if (t_end < HUGE_VAL) {
    double remaining = t_end - sim->time;
    /* a sliver of time left over by round-off is not worth a step */
    if (remaining <= 1e-9 * dt) return MRN_STEP_NONE;
    if (dt > remaining) dt = remaining;
  }
  return mrn_sim_step_dt(sim, dt);
}

/* the first error a step's end finds: the watchdog, the hooks, a signal, the log */
static int end_of_step(mrn_sim *sim, mrn_run_options *opt, run_clock *clk) {
  int rc = mrn_dist_agree(sim, mrn_watchdog_check(&sim->watch, sim, sim->step == clk->step_start + 1));
  if (rc == MRN_OK) {
    rc = after_step(sim, opt, 0, clk);
    if (rc != MRN_OK && rc != MRN_STOP) opt->cut_short = 1;
  }
  if (rc == MRN_OK && mrn_interrupt_pending()) rc = MRN_ERR_INTERRUPTED;
  /* the run log is an output like the others: a run that cannot write it stops */
  if (rc == MRN_OK && mrn_log_failed()) rc = mrn_error_code(MRN_ERR_IO, "%s", mrn_log_failure());
  return mrn_dist_agree(sim, rc); /* a signal or a hook's error on one process stops all */
}

/* the every_time hooks' schedule from the run's start; a resumed run past
 * the calls made, up to this state when they are made again for it */
static void schedule_hooks(const mrn_sim *sim, mrn_run_options *opt, double t_start) {
  for (int i = 0; i < opt->nhooks; i++) {
    mrn_hook *h = &opt->hooks[i];
    if (!(h->every_time > 0)) continue;
    h->next_time = t_start;
    if (opt->resume && !opt->resume_hooks) due_hook(h, sim);
    while (opt->resume && opt->resume_hooks && h->next_time < sim->time - 1e-9 * h->every_time)
      h->next_time += h->every_time;
  }
}

/* Before the first step: the hooks' schedule, what the step needs set up,
 * and the reports of the starting state. 0, or what ended the run. */
static int start_run(mrn_sim *sim, mrn_run_options *opt, run_clock *clk) {
  /* the affine matrices belong to the explicit transfers; found while every
   * process still holds every particle, as on one (solver/dist.h) */
  if (!sim->integrator.step && sim->affine_pending && sim->scheme.grid_velocity != MRN_VGRID_PLAIN)
    mrn_sim_init_affine(sim);
  int rc = mrn_dist_start(sim); /* each process keeps its own particles from here on */
  if (rc != MRN_OK) return rc;
  schedule_hooks(sim, opt, clk->t_start);
  opt->cut_short = 0;
  if (!sim->energy_ref_set) mrn_sim_energy_balance_start(sim);
  mrn_watchdog_start(&sim->watch, sim);
  if (thermo_on(opt)) thermo_header(opt);
  /* a resumed run's state was reached before the stop, which may have cut
   * its reports short: the observers get it again as a step (each writes
   * only what it lacks); the hooks too when the stop came inside them */
  rc = !opt->resume           ? after_step(sim, opt, 1, clk)
           : opt->resume_hooks ? after_step(sim, opt, 0, clk)
                               : report_snapshots(sim, opt);
  if (rc == MRN_OK && opt->resume && !opt->resume_hooks) rc = report_rows(sim, opt, MRN_RUN_STEP, clk);
  if (rc != MRN_OK && rc != MRN_STOP) opt->cut_short = 1;
  return rc;
}

int mrn_run(mrn_sim *sim, mrn_run_options *opt) {
  memset(&opt->stats, 0, sizeof opt->stats);
  if (!(opt->time > 0) && !(opt->steps > 0) && !(opt->until > 0))
    return mrn_error("run: give a positive time, end time or number of steps");
  const double t_start = opt->resume ? opt->start_time : sim->time;
  const long step_start = opt->resume ? opt->start_step : sim->step;
  const double t_end = opt->until > 0 ? opt->until : opt->time > 0 ? t_start + opt->time : HUGE_VAL;
  const long step_end = opt->steps > 0 ? step_start + opt->steps : -1;
  run_clock clk = {wall_seconds(), 0, t_start, t_end, step_start, sim->step, 0};
  clk.last_draw = clk.thermo_wall = clk.wall_start;
  int rc = start_run(sim, opt, &clk);
  while (rc == MRN_OK) {
    if (step_end >= 0 && sim->step >= step_end) break;
    if ((rc = take_step(sim, opt, t_end)) == MRN_STEP_NONE) {
      rc = MRN_OK;
      break;
    }
    if (rc != MRN_OK) break;
    opt->stats.steps++;
    opt->stats.particle_steps += (double)sim->particles.n;
    rc = end_of_step(sim, opt, &clk);
    if (opt->progress) update_progress(sim, opt, &clk);
  }
  /* seen between steps, or by a hook or dt function the signal stopped:
   * the state is that of the last whole step */
  if (rc == MRN_ERR_INTERRUPTED)
    rc = mrn_error_code(MRN_ERR_INTERRUPTED, "interrupted by signal %d after step %ld (t = %g s)",
                        mrn_interrupt_pending(), sim->step, sim->time);
  /* a run that stopped short leaves no full bar behind */
  const int done = rc == MRN_OK || rc == MRN_STOP;
  if (opt->progress) {
    if (done) draw_progress(1.0, wall_seconds() - clk.wall_start);
    mrn_log_bar_end(done);
  }
  /* the final state always reaches the thermo output and the observers' rows */
  if (done) rc = report_rows(sim, opt, MRN_RUN_END, &clk);
  opt->stats.wall = wall_seconds() - clk.wall_start;
  return rc;
}
