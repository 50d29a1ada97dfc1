/* moraine: the rigid walls and bodies of a distributed run (dist.h,
 * grid/wall.h).
 *
 * A wall's contact column gathers the nodes of one patch of its surface,
 * which may lie on both sides of a cut, beyond the band the neighbours
 * share. So every process works on the columns of all (the union of their
 * patches, in one order), and what a column decides with is summed over
 * the processes: its normal and velocity when it is formed, N, M and P when
 * it acts, each node counted by the process that owns its row. The nodes of
 * the bands a neighbour's material touches are touched on both sides, so
 * that each holds every node its particles read. The reactions and works
 * are booked on owned rows and summed at the end of the step: every process
 * then holds the same reaction and moves a rigid body the same way. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "grid/wall.h"
#include "solver/dist.h"
#include "solver/simulation.h"

static int share_agree(void *ctx, int rc) { return mrn_dist_agree(ctx, rc); }

static void share_reduce(void *ctx, double *v, size_t n, mrn_comm_op op) {
  if (n) mrn_dist_reduce(ctx, v, (int)n, op);
}

static int share_band_or(void *ctx, unsigned char *bits, unsigned char mask, int (*fresh)(void *arg, size_t node),
                         void *arg) {
  return mrn_dist_or_bands(ctx, bits, mask, fresh, arg);
}

static int by_key(const void *a, const void *b) {
  const long long *p = a, *q = b;
  for (int d = 0; d < 3; d++)
    if (p[d] != q[d]) return p[d] < q[d] ? -1 : 1;
  return 0;
}

/* every process's keys on every process, sorted and made unique */
static long long *share_union_keys(void *ctx, const long long *keys, size_t n, size_t *total) {
  unsigned char *bytes = NULL;
  size_t all = 0;
  if (mrn_dist_allgather(ctx, keys, 3 * n * sizeof *keys, &bytes, &all, MRN_OK) != MRN_OK) return NULL;
  long long *out = (long long *)bytes;
  const size_t k = all / (3 * sizeof *out);
  qsort(out, k, 3 * sizeof *out, by_key);
  size_t m = 0;
  for (size_t i = 0; i < k; i++)
    if (m == 0 || by_key(out + 3 * i, out + 3 * (m - 1)) != 0) memmove(out + 3 * m++, out + 3 * i, 3 * sizeof *out);
  *total = m;
  return out;
}

void mrn_dist_walls_attach(mrn_sim *sim) {
  mrn_walls *ws = sim->boundary.walls;
  if (!ws) return;
  ws->share = NULL;
  if (!sim->dist) return;
  sim->dist->walls = (mrn_walls_share){sim, share_agree, share_reduce, share_band_or, share_union_keys};
  ws->share = &sim->dist->walls;
}

/* the nodes in contact with wall w on any process, as a list *nodes of
 * *count (every process the same) */
static int contact_union(mrn_sim *sim, const mrn_wall *w, size_t **nodes, size_t *count) {
  const size_t n = sim->grid.n;
  double *on = calloc(n, sizeof *on);
  *nodes = NULL, *count = 0;
  int rc = mrn_dist_agree(sim, on ? MRN_OK : mrn_error("parallel: out of memory for a wall's contacts"));
  if (rc) {
    free(on);
    return rc;
  }
  for (size_t k = 0; k < w->count; k++)
    if (w->state[w->node[k]] & MRN_WALL_CONTACT) on[w->node[k]] = 1.0;
  mrn_comm_allreduce(on, (int)n, MRN_COMM_MAX);
  for (size_t i = 0; i < n; i++) *count += on[i] > 0.0;
  *nodes = malloc((*count + 1) * sizeof **nodes);
  if (*nodes) {
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
      if (on[i] > 0.0) (*nodes)[k++] = i;
  }
  free(on);
  return mrn_dist_agree(sim, *nodes ? MRN_OK : mrn_error("parallel: out of memory for a wall's contacts"));
}

/* A re-cut gives a process rows whose contacts another kept: every process
 * takes the contacts of all, and its next touch keeps those its material
 * (or a neighbour's, on the bands) still touches. */
int mrn_dist_walls_recut(mrn_sim *sim) {
  mrn_walls *ws = sim->boundary.walls;
  int rc = MRN_OK;
  for (int i = 0; ws && rc == MRN_OK && i < ws->count; i++) {
    size_t *nodes, count;
    rc = contact_union(sim, &ws->wall[i], &nodes, &count);
    if (rc == MRN_OK) rc = mrn_dist_agree(sim, mrn_wall_reset_contacts(&ws->wall[i], nodes, count));
    free(nodes);
  }
  return rc;
}

/* For a checkpoint, process 0's walls hold the contacts of every process
 * (kept aside in d->held_walls until mrn_dist_walls_gather_end). */
int mrn_dist_walls_gather(mrn_sim *sim) {
  mrn_walls *ws = sim->boundary.walls;
  mrn_dist *d = sim->dist;
  if (!ws || !ws->count) return MRN_OK;
  unsigned char **held = d->rank == 0 ? calloc((size_t)ws->count, sizeof *held) : NULL;
  int rc = mrn_dist_agree(sim, d->rank != 0 || held ? MRN_OK : mrn_error("parallel: out of memory for the walls"));
  for (int i = 0; rc == MRN_OK && i < ws->count; i++) {
    size_t *nodes, count;
    rc = contact_union(sim, &ws->wall[i], &nodes, &count);
    unsigned char *state = held && rc == MRN_OK ? calloc(sim->grid.n, 1) : NULL;
    if (state) {
      for (size_t k = 0; k < count; k++) state[nodes[k]] = MRN_WALL_CONTACT;
      held[i] = ws->wall[i].state;
      ws->wall[i].state = state;
    }
    free(nodes);
    if (held && rc == MRN_OK && !state) rc = mrn_error("parallel: out of memory for the walls");
    rc = mrn_dist_agree(sim, rc);
  }
  d->held_walls = held;
  return rc;
}

void mrn_dist_walls_gather_end(mrn_sim *sim) {
  mrn_walls *ws = sim->boundary.walls;
  mrn_dist *d = sim->dist;
  if (!d->held_walls) return;
  for (int i = 0; ws && i < ws->count; i++)
    if (d->held_walls[i]) {
      free(ws->wall[i].state);
      ws->wall[i].state = d->held_walls[i];
    }
  free(d->held_walls);
  d->held_walls = NULL;
}
