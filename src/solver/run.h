/* moraine: driving a simulation through time.
 *
 * mrn_run() steps until the requested model time has passed or the requested
 * number of steps is done (whichever comes first), calling hooks on their
 * schedule, reporting each state to its observers (the writers of io/, which
 * the caller registers), printing thermo lines and a progress bar (through
 * core/log.h: on the screen and in the run log). The last
 * step is shortened so a `time` run ends exactly on time. */
#ifndef MRN_SOLVER_RUN_H
#define MRN_SOLVER_RUN_H

#include "solver/diagnostics.h"
#include "solver/simulation.h"

/* a hook returns 0 to go on, MRN_STOP to end the run cleanly, or an error code */
#define MRN_STOP (-1)
typedef int (*mrn_hook_fn)(void *ctx, mrn_sim *sim);

typedef struct mrn_hook {
  long every_steps;   /* > 0: call every this many steps */
  double every_time;  /* > 0: call every this much model time */
  int at_output;      /* 1: call after each snapshot an observer writes */
  double next_time;
  mrn_hook_fn fn;
  void *ctx;
} mrn_hook;

/* Which state the run reports: the one it starts from, one a step reached,
 * or the one it ends on (also after a hook or stop_when ended it). */
typedef enum mrn_run_moment { MRN_RUN_START, MRN_RUN_STEP, MRN_RUN_END } mrn_run_moment;

/* Whoever records a run: the solver knows no file format, so io/ hands its
 * writers in as observers (mrn_output_observer) and the caller lists them in
 * the options. Each callback may be NULL and returns 0 or an error code,
 * which ends the run. For the starting state and after every step, once the
 * hooks due have run:
 *   snapshot()  may write a snapshot of the state, and then sets *wrote
 *               (the hooks with at_output follow it);
 *   row_due()   says whether it records a row of diagnostics of this state
 *               (none: a row of every state);
 *   row()       records it: the diagnostics are computed once for all the
 *               observers and the thermo line.
 * The state the run ends on gets row_due(MRN_RUN_END) and row() only. */
typedef struct mrn_run_observer {
  int (*snapshot)(void *ctx, const mrn_sim *sim, int *wrote);
  int (*row_due)(void *ctx, const mrn_sim *sim, mrn_run_moment when);
  int (*row)(void *ctx, const mrn_sim *sim, const mrn_diagnostics *d);
  void *ctx;
} mrn_run_observer;

#define MRN_THERMO_MAX_COLUMNS 32

/* what a run did, for the end-of-run summary */
typedef struct mrn_run_stats {
  long steps;            /* steps taken */
  double particle_steps; /* the particles of each step, summed over the steps */
  double wall;           /* seconds of wall time */
} mrn_run_stats;

typedef struct mrn_run_options {
  double time;        /* > 0: run this much model time */
  long steps;         /* > 0: run this many steps */
  double until;       /* > 0: run until this model time (absolute; instead of time) */
  /* 1: the run continues one that started at (start_time, start_step) and
   * was stopped (a checkpoint): time and steps count from that start, the
   * hooks keep its schedule and are not called for the state it continues
   * from, which the observers get as that of a step (MRN_RUN_STEP) */
  int resume;
  double start_time;
  long start_step;
  /* with resume: the stop cut the hooks or reports of the state short (see
   * cut_short), so they are all made again for it, the hooks included */
  int resume_hooks;
  /* set by mrn_run when it ended on an error inside the hooks, reports or
   * stop_when of a state: not all of them were made for the state it left */
  int cut_short;
  long thermo_every;  /* thermo line every N steps (0: none) */
  const int *thermo_columns; /* mrn_thermo_column() of each column (NULL: the default ones) */
  int thermo_ncolumns;
  int progress;       /* draw a progress bar on stderr (a terminal) */
  mrn_hook *hooks;
  int nhooks;
  const mrn_run_observer *observers; /* called in this order */
  int nobservers;
  mrn_hook_fn stop_when; /* checked after every step: MRN_STOP ends the run */
  void *stop_ctx;
  mrn_run_stats stats; /* filled by mrn_run, whatever it returns */
} mrn_run_options;

/* 0 when the run completed (or a hook/stop_when ended it), otherwise an error
 * code with the message set; the state is left at the last completed step. */
int mrn_run(mrn_sim *sim, mrn_run_options *opt);

/* The thermo columns: "step", "time", "dt", "steps_per_s" (steps per second
 * of wall time since the previous line) and every column of the diagnostics
 * table (solver/diagnostics.h), by index from 0 to mrn_thermo_column_count() - 1. */
int mrn_thermo_column_count(void);
const char *mrn_thermo_column_name(int i);
/* the index of a column by name, -1 when there is none */
int mrn_thermo_column(const char *name);
/* the default columns into `columns` (MRN_THERMO_MAX_COLUMNS): their count */
int mrn_thermo_default_columns(int *columns);

#endif
