#include "io/summary.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>

#include "core/log.h"
#include "solver/dist.h"
#include "transfer/profile.h"

/* ---- the simulations' runs ------------------------------------------------ */

typedef struct sim_record {
  char name[64];
  long step0, step1;
  double t0, t1;
  long particles; /* at the end of the last run */
  mrn_run_stats total;
} sim_record;

static struct {
  double wall_start;
  double phase[MRN_PHASE_COUNT];
  sim_record *sims;
  int nsims, cap;
} sum;

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* the record *id (from 1), or a new one */
static sim_record *record_of(int *id, const char *name) {
  if (*id > 0 && *id <= sum.nsims) return &sum.sims[*id - 1];
  if (sum.nsims == sum.cap) {
    int cap = sum.cap ? 2 * sum.cap : 8;
    sim_record *grown = realloc(sum.sims, (size_t)cap * sizeof *grown);
    if (!grown) return NULL; /* the summary leaves it out */
    sum.sims = grown;
    sum.cap = cap;
  }
  sim_record *r = &sum.sims[sum.nsims++];
  memset(r, 0, sizeof *r);
  snprintf(r->name, sizeof r->name, "%s", name);
  r->step0 = -1;
  *id = sum.nsims;
  return r;
}

void mrn_summary_add_run(int *record, const char *name, long step0, double t0, const mrn_sim *sim,
                         const mrn_run_stats *st) {
  sim_record *r = record_of(record, name);
  if (!r) return;
  if (r->step0 < 0) {
    r->step0 = step0;
    r->t0 = t0;
  }
  r->step1 = sim->step;
  r->t1 = sim->time;
  /* every process's particles (collective in a distributed run) */
  double v[2] = {(double)sim->particles.n, st->particle_steps};
  mrn_dist_reduce(sim, v, 2, MRN_COMM_SUM);
  r->particles = (long)v[0];
  r->total.steps += st->steps;
  r->total.particle_steps += v[1];
  r->total.wall += st->wall;
}

/* ---- the files written: a set of paths ------------------------------------ */

static struct {
  char **slot; /* open addressing; NULL: free */
  size_t cap, count;
} files;

static size_t hash(const char *s) {
  uint64_t h = 1469598103934665603u; /* FNV-1a */
  for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211u;
  return (size_t)h;
}

static int grow_files(void) {
  size_t cap = files.cap ? 2 * files.cap : 256;
  char **slot = calloc(cap, sizeof *slot);
  if (!slot) return 0;
  for (size_t i = 0; i < files.cap; i++) {
    if (!files.slot[i]) continue;
    size_t k = hash(files.slot[i]) & (cap - 1);
    while (slot[k]) k = (k + 1) & (cap - 1);
    slot[k] = files.slot[i];
  }
  free(files.slot);
  files.slot = slot;
  files.cap = cap;
  return 1;
}

void mrn_summary_note_file(const char *path) {
  if (2 * (files.count + 1) > files.cap && !grow_files()) return;
  size_t k = hash(path) & (files.cap - 1);
  for (; files.slot[k]; k = (k + 1) & (files.cap - 1))
    if (!strcmp(files.slot[k], path)) return;
  if ((files.slot[k] = strdup(path)) != NULL) files.count++;
}

/* the files still there and their bytes now */
static void file_totals(long *count, double *bytes) {
  *count = 0;
  *bytes = 0;
  struct stat st;
  for (size_t i = 0; i < files.cap; i++)
    if (files.slot[i] && stat(files.slot[i], &st) == 0) {
      (*count)++;
      *bytes += (double)st.st_size;
    }
}

/* ---- start, print, end ------------------------------------------------------ */

void mrn_summary_start(void) {
  mrn_summary_end();
  sum.wall_start = now();
  mrn_profile_seconds = sum.phase;
}

void mrn_summary_end(void) {
  if (mrn_profile_seconds == sum.phase) mrn_profile_seconds = NULL;
  free(sum.sims);
  for (size_t i = 0; i < files.cap; i++) free(files.slot[i]);
  free(files.slot);
  memset(&sum, 0, sizeof sum);
  memset(&files, 0, sizeof files);
}

static const char *size_text(double bytes, char *buf, size_t len) {
  static const char *const unit[] = {"B", "kB", "MB", "GB", "TB"};
  int u = 0;
  while (bytes >= 1000 && u < 4) {
    bytes /= 1000;
    u++;
  }
  snprintf(buf, len, u ? "%.1f %s" : "%.0f %s", bytes, unit[u]);
  return buf;
}

static void print_sims(double *run_wall, double *particle_steps) {
  *run_wall = *particle_steps = 0;
  if (sum.nsims == 0) mrn_info("  simulations       none ran");
  for (int i = 0; i < sum.nsims; i++) {
    const sim_record *r = &sum.sims[i];
    mrn_info("  simulation        '%s': %ld step%s (%ld -> %ld), t = %g -> %g s, %ld particles", r->name,
             r->total.steps, r->total.steps == 1 ? "" : "s", r->step0, r->step1, r->t0, r->t1, r->particles);
    *run_wall += r->total.wall;
    *particle_steps += r->total.particle_steps;
  }
}

/* each phase's share of the time spent running; "other": the rest of it */
static void print_phases(double run_wall) {
  static const char *const names[MRN_PHASE_COUNT] = {"p2g", "grid", "g2p", "stress", "sort"};
  char line[512];
  size_t len = 0;
  double timed = 0;
  for (int p = 0; p <= MRN_PHASE_COUNT; p++) {
    double s = p < MRN_PHASE_COUNT ? sum.phase[p] : run_wall - timed;
    if (s < 0) s = 0;
    if (p < MRN_PHASE_COUNT) timed += s;
    len += (size_t)snprintf(line + len, sizeof line - len, "%s%s %.3g s (%.1f %%)", p ? ", " : "",
                            p < MRN_PHASE_COUNT ? names[p] : "other", s, run_wall > 0 ? 100 * s / run_wall : 0.0);
  }
  mrn_info("  time per phase    %s", line);
}

void mrn_summary_print(const char *status) {
  const double wall = now() - sum.wall_start;
  const long secs = (long)(wall + 0.5);
  double run_wall, particle_steps, bytes;
  long nfiles;
  char size[32];
  mrn_info("summary:");
  mrn_info("  status            %s", status);
  print_sims(&run_wall, &particle_steps);
  mrn_info("  wall time         %ld:%02ld:%02ld (%.3g s), %.3g particle-steps/s", secs / 3600, secs / 60 % 60,
           secs % 60, wall, run_wall > 0 ? particle_steps / run_wall : 0.0);
  if (run_wall > 0) print_phases(run_wall);
  struct rusage ru;
  if (getrusage(RUSAGE_SELF, &ru) == 0) /* Linux counts the peak resident set in KiB */
    mrn_info("  peak memory       %s", size_text(1024.0 * (double)ru.ru_maxrss, size, sizeof size));
  file_totals(&nfiles, &bytes);
  mrn_info("  files written     %ld, %s (besides the log)", nfiles, size_text(bytes, size, sizeof size));
}
