/* moraine: the end-of-run summary.
 *
 *   summary:
 *     status            ok (exit status 0)
 *     simulation        'drop': 3000 steps (0 -> 3000), t = 0 -> 0.6 s, 1024 particles
 *     wall time         0:00:12 (12.3 s), 2.47e+06 particle-steps/s
 *     time per phase    p2g 4.1 s (41.0 %), grid ..., other 0.2 s (1.9 %)
 *     peak memory       123.4 MB
 *     files written     23, 4.5 MB (besides the log)
 *
 * The command line starts it before the deck runs (the phase timers of
 * transfer/profile.h are on from then), the caller of each run adds what
 * the run did, and the command line prints it once the deck has ended,
 * however it ended. Every file moraine writes is noted as it is completed:
 * the count and the size of the distinct files, the run log aside. */
#ifndef MRN_IO_SUMMARY_H
#define MRN_IO_SUMMARY_H

#include "solver/run.h"

/* start the wall clock and the phase timers; forget what an earlier start saw */
void mrn_summary_start(void);
/* What a run of simulation `name` did: from step0 at time t0 to sim's state.
 * `*record` is 0 for a simulation that has not run yet, and is then set to
 * its record: the runs of one simulation make one line of the summary. */
void mrn_summary_add_run(int *record, const char *name, long step0, double t0, const mrn_sim *sim,
                         const mrn_run_stats *st);
/* a file written whole (or opened, for a file that is appended to) */
void mrn_summary_note_file(const char *path);
/* print it (an information message: the log always, the screen unless quiet);
 * `status` says how the run ended, with the exit status */
void mrn_summary_print(const char *status);
/* free what it holds and turn the phase timers off */
void mrn_summary_end(void);

#endif
