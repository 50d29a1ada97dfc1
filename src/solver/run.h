/* moraine: driving a simulation through time.
 *
 * mrn_run() steps until the requested model time has passed or the requested
 * number of steps is done (whichever comes first), calling hooks on their
 * schedule, writing outputs, thermo lines and a progress bar. The last step is
 * shortened so a `time` run ends exactly on time. */
#ifndef MRN_SOLVER_RUN_H
#define MRN_SOLVER_RUN_H

#include "io/output.h"
#include "solver/simulation.h"

/* a hook returns 0 to go on, MRN_STOP to end the run cleanly, or an error code */
#define MRN_STOP (-1)
typedef int (*mrn_hook_fn)(void *ctx, mrn_sim *sim);

typedef struct mrn_hook {
  long every_steps;   /* > 0: call every this many steps */
  double every_time;  /* > 0: call every this much model time */
  int at_output;      /* 1: call after each VTK snapshot the run writes */
  double next_time;
  mrn_hook_fn fn;
  void *ctx;
} mrn_hook;

typedef struct mrn_run_options {
  double time;        /* > 0: run this much model time */
  long steps;         /* > 0: run this many steps */
  long thermo_every;  /* thermo line every N steps (0: none) */
  int progress;       /* draw a progress bar on stderr */
  mrn_hook *hooks;
  int nhooks;
  mrn_hook_fn stop_when; /* checked after every step: MRN_STOP ends the run */
  void *stop_ctx;
} mrn_run_options;

/* 0 when the run completed (or a hook/stop_when ended it), otherwise an error
 * code with the message set; the state is left at the last completed step. */
int mrn_run(mrn_sim *sim, mrn_output *out, mrn_run_options *opt);

void mrn_thermo_header(FILE *f);
void mrn_thermo_line(FILE *f, const mrn_sim *sim, const mrn_diagnostics *d);

#endif
