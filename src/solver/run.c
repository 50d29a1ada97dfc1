#include "solver/run.h"

#include <math.h>
#include <stdio.h>
#include <time.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/log.h"

void mrn_thermo_header(FILE *f) {
  fprintf(f, "%10s %13s %11s %13s %13s %13s %13s %13s\n", "step", "time", "dt", "E_kinetic", "E_gravity", "E_elastic",
          "E_total", "W_friction");
}

void mrn_thermo_line(FILE *f, const mrn_sim *sim, const mrn_diagnostics *d) {
  fprintf(f, "%10ld %13.6e %11.4e %13.6e %13.6e %13.6e %13.6e %13.6e\n", sim->step, sim->time, sim->dt, d->kinetic,
          d->gravity, d->elastic, d->total, d->friction);
  fflush(f);
}

static double wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void draw_progress(double fraction, double elapsed) {
  if (fraction < 0) fraction = 0;
  if (fraction > 1) fraction = 1;
  int width = 30, filled = (int)(fraction * width);
  double eta = fraction > 1e-6 ? elapsed * (1 - fraction) / fraction : 0;
  fprintf(stderr, "\r[");
  for (int i = 0; i < width; i++) fputc(i < filled ? '#' : '.', stderr);
  fprintf(stderr, "] %5.1f%%  ETA %6.0f s ", 100 * fraction, eta);
  fflush(stderr);
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

/* The thermo line and the observers' rows of this state. The diagnostics sum
 * over every particle: computed once, and only when a line or a row is due.
 * The thermo line comes on its cadence and at the start; at the end only when
 * the cadence has not just printed this state. */
static int report_rows(mrn_sim *sim, mrn_run_options *opt, mrn_run_moment when) {
  const long every = opt->thermo_every;
  const int on_cadence = every > 0 && sim->step % every == 0;
  const int thermo = every > 0 && !mrn_log_quiet() &&
                     (when == MRN_RUN_START || (when == MRN_RUN_STEP ? on_cadence : !on_cadence));
  int due = thermo;
  for (int i = 0; i < opt->nobservers && !due; i++) due = row_due(&opt->observers[i], sim, when);
  if (!due) return MRN_OK;
  mrn_diagnostics d;
  mrn_sim_diagnostics(sim, &d);
  if (thermo) mrn_thermo_line(stdout, sim, &d);
  for (int i = 0; i < opt->nobservers; i++) {
    const mrn_run_observer *ob = &opt->observers[i];
    int rc;
    if (row_due(ob, sim, when) && (rc = ob->row(ob->ctx, sim, &d)) != MRN_OK) return rc;
  }
  return MRN_OK;
}

/* hooks, observers and thermo for the state just reached; returns 0, MRN_STOP or an error */
static int after_step(mrn_sim *sim, mrn_run_options *opt, int first) {
  int rc;
  for (int i = 0; i < opt->nhooks; i++)
    if (due_hook(&opt->hooks[i], sim) && (rc = opt->hooks[i].fn(opt->hooks[i].ctx, sim)) != 0) return rc;
  if ((rc = report_snapshots(sim, opt)) != MRN_OK) return rc;
  if ((rc = report_rows(sim, opt, first ? MRN_RUN_START : MRN_RUN_STEP)) != MRN_OK) return rc;
  if (!first && opt->stop_when && (rc = opt->stop_when(opt->stop_ctx, sim)) != 0) return rc;
  return MRN_OK;
}

/* Before the first step: the hooks' schedule, what the step needs set up,
 * and the reports of the starting state. 0, or what ended the run. */
static int start_run(mrn_sim *sim, mrn_run_options *opt, double t_start) {
  /* every_time hooks from the run's start; a resumed run past the calls
   * made, up to this state when they are made again for it */
  for (int i = 0; i < opt->nhooks; i++) {
    mrn_hook *h = &opt->hooks[i];
    if (!(h->every_time > 0)) continue;
    h->next_time = t_start;
    if (opt->resume && !opt->resume_hooks) due_hook(h, sim);
    while (opt->resume && opt->resume_hooks && h->next_time < sim->time - 1e-9 * h->every_time)
      h->next_time += h->every_time;
  }
  opt->cut_short = 0;

  /* the affine matrices belong to the explicit transfers */
  if (!sim->integrator.step && sim->affine_pending && sim->scheme.grid_velocity != MRN_VGRID_PLAIN)
    mrn_sim_init_affine(sim);
  if (!sim->energy_ref_set) mrn_sim_energy_balance_start(sim);
  mrn_watchdog_start(&sim->watch, sim);
  if (opt->thermo_every > 0 && !mrn_log_quiet()) mrn_thermo_header(stdout);
  /* a resumed run's state was reached before the stop, which may have cut
   * its reports short: the observers get it again as a step (each writes
   * only what it lacks); the hooks too when the stop came inside them */
  int rc = !opt->resume       ? after_step(sim, opt, 1)
           : opt->resume_hooks ? after_step(sim, opt, 0)
                               : report_snapshots(sim, opt);
  if (rc == MRN_OK && opt->resume && !opt->resume_hooks) rc = report_rows(sim, opt, MRN_RUN_STEP);
  if (rc != MRN_OK && rc != MRN_STOP) opt->cut_short = 1;
  return rc;
}

int mrn_run(mrn_sim *sim, mrn_run_options *opt) {
  if (!(opt->time > 0) && !(opt->steps > 0) && !(opt->until > 0))
    return mrn_error("run: give a positive time, end time or number of steps");
  const double t_start = opt->resume ? opt->start_time : sim->time;
  const long step_start = opt->resume ? opt->start_step : sim->step;
  const double t_end = opt->until > 0 ? opt->until : opt->time > 0 ? t_start + opt->time : HUGE_VAL;
  const long step_end = opt->steps > 0 ? step_start + opt->steps : -1;
  const double wall_start = wall_seconds();
  double last_draw = wall_start;
  int rc = start_run(sim, opt, t_start);
  while (rc == MRN_OK) {
    if (step_end >= 0 && sim->step >= step_end) break;
    if (sim->integrator.step) {
      rc = sim->integrator.step(sim->integrator.ctx, sim, t_end);
      if (rc == MRN_STEP_NONE) {
        rc = MRN_OK;
        break;
      }
      if (rc != MRN_OK) break;
    } else {
      double dt;
      if ((rc = mrn_dt_compute(sim, &dt)) != MRN_OK) break;
      if (t_end < HUGE_VAL) {
        double remaining = t_end - sim->time;
        /* a sliver of time left over by round-off is not worth a step */
        if (remaining <= 1e-9 * dt) break;
        if (dt > remaining) dt = remaining;
      }
      if ((rc = mrn_sim_step_dt(sim, dt)) != MRN_OK) break;
    }
    if ((rc = mrn_watchdog_check(&sim->watch, sim, sim->step == step_start + 1)) != MRN_OK) break;
    rc = after_step(sim, opt, 0);
    if (rc != MRN_OK && rc != MRN_STOP) opt->cut_short = 1;
    if (rc == MRN_OK && mrn_interrupt_pending()) rc = MRN_ERR_INTERRUPTED;
    if (opt->progress) {
      double now = wall_seconds();
      if (now - last_draw > 0.25) {
        double f_time = t_end < HUGE_VAL ? (sim->time - t_start) / (t_end - t_start) : 0;
        double f_steps = opt->steps > 0 ? (double)(sim->step - step_start) / opt->steps : 0;
        draw_progress(f_time > f_steps ? f_time : f_steps, now - wall_start);
        last_draw = now;
      }
    }
  }
  /* seen between steps, or by a hook or dt function the signal stopped:
   * the state is that of the last whole step */
  if (rc == MRN_ERR_INTERRUPTED)
    rc = mrn_error_code(MRN_ERR_INTERRUPTED, "interrupted by signal %d after step %ld (t = %g s)",
                        mrn_interrupt_pending(), sim->step, sim->time);
  if (opt->progress) {
    draw_progress(1.0, wall_seconds() - wall_start);
    fputc('\n', stderr);
  }
  /* the final state always reaches the thermo output and the observers' rows */
  if (rc == MRN_OK || rc == MRN_STOP) return report_rows(sim, opt, MRN_RUN_END);
  return rc;
}
