/* moraine: a simulation spread over the processes of an MPI run (dist.h). */
#include "solver/dist.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "grid/active.h"
#include "solver/contact.h"
#include "solver/simulation.h"

/* the implicit integrator is a limitation of distributed runs, not a
 * feature still to come to them (doc/implicit.md) */
/* what the distributed step does not do: the implicit integrator, a
 * limitation named (doc/implicit.md) */
static int refuse(const mrn_sim *sim) {
  if (!sim->integrator.step) return MRN_OK;
  return mrn_error("parallel: the implicit integrator (simulation{integrator}) does not run on several processes: "
                   "its Newton system is assembled and solved on one process by a sequential solver, a limitation "
                   "of moraine's implicit integrator; run this deck without mpirun (doc/implicit.md)");
}

/* the cell row along the cut axis of a position, clamped to the grid */
static int row_of(const mrn_grid *g, int axis, const double *x) {
  const double t = (x[axis] - g->origin[axis]) * g->inv_cell;
  if (!(t >= 0.0)) return 0; /* below the grid, or not a number: the end-of-step check reports it */
  if (t >= g->ncell[axis]) return g->ncell[axis] - 1;
  return (int)t;
}

static int owner_of(const mrn_dist *d, int row) {
  int r = 0;
  while (r + 1 < d->size && row >= d->cut[r + 1]) r++;
  return r;
}

/* the rows whose nodal work this process books: its cells' rows, and the
 * ghost layers beyond the grid's ends for the first and the last */
static void set_own(mrn_sim *sim, const mrn_dist *d) {
  mrn_grid *g = &sim->grid;
  g->own_lo = d->rank == 0 ? -g->pad : d->cut[d->rank];
  g->own_hi = d->rank == d->size - 1 ? g->ncell[d->axis] + g->pad + 1 : d->cut[d->rank + 1];
}

/* the thinnest slab a cut makes: MRN_DIST_MIN_CELLS, or as many as the
 * band width needs between two bands (mrn_dist_halo) where the grid has
 * room for it */
static int slab_min(const mrn_grid *g, const mrn_dist *d) {
  const int need = 2 * d->halo + 1;
  return need > MRN_DIST_MIN_CELLS && need * d->size <= g->ncell[d->axis] ? need : MRN_DIST_MIN_CELLS;
}

/* Cuts at the particle-count quantiles along the axis, then pushed apart
 * to slab_min rows: neighbouring bands must not overlap, so that no node
 * row is reached by three processes. `replicated`: every process holds
 * every particle (the count is not summed). */
static int cut_by_count(mrn_sim *sim, mrn_dist *d, int replicated) {
  const mrn_grid *g = &sim->grid;
  const int nc = g->ncell[d->axis];
  double *count = calloc((size_t)nc, sizeof *count);
  if (!count) return mrn_error("parallel: out of memory");
  for (size_t p = 0; p < sim->particles.n; p++) count[row_of(g, d->axis, sim->particles.x + 3 * p)] += 1.0;
  if (!replicated) mrn_comm_allreduce(count, nc, MRN_COMM_SUM);
  double total = 0.0;
  for (int j = 0; j < nc; j++) total += count[j];
  d->cut[0] = 0;
  d->cut[d->size] = nc;
  double below = 0.0;
  int j = 0;
  for (int r = 1; r < d->size; r++) {
    while (j < nc && below < total * r / d->size) below += count[j++];
    d->cut[r] = j;
  }
  free(count);
  const int min = slab_min(g, d);
  for (int r = 1; r < d->size; r++)
    if (d->cut[r] < d->cut[r - 1] + min) d->cut[r] = d->cut[r - 1] + min;
  for (int r = d->size - 1; r > 0; r--)
    if (d->cut[r] > d->cut[r + 1] - min) d->cut[r] = d->cut[r + 1] - min;
  set_own(sim, d);
  return MRN_OK;
}

/* keep only the particles [first, n) this process owns (those before stay) */
int mrn_dist_adopt(mrn_sim *sim, size_t first) {
  mrn_particles *ps = &sim->particles;
  const mrn_dist *d = sim->dist;
  unsigned char *keep = malloc(ps->n + 1);
  if (!keep) return mrn_error("parallel: out of memory");
  for (size_t p = 0; p < ps->n; p++)
    keep[p] = p < first || owner_of(d, row_of(&sim->grid, d->axis, ps->x + 3 * p)) == d->rank;
  mrn_particles_compact(ps, keep);
  free(keep);
  if (sim->blocks) mrn_blocks_forget(sim->blocks);
  return MRN_OK;
}

static void books_set(mrn_sim *sim, const mrn_books *b);
static int reserve(mrn_sim *sim); /* room for the halo exchanges (below) */

int mrn_dist_start(mrn_sim *sim) {
  if (sim->dist || mrn_comm_size() < 2) return MRN_OK;
  /* what is refused is refused by every process alike: process 0 says it */
  mrn_comm_set_shared_error(1);
  int rc = refuse(sim);
  if (rc) return rc;
  const int axis = sim->dim - 1, nc = sim->grid.ncell[axis];
  if (nc < MRN_DIST_MIN_CELLS * mrn_comm_size())
    return mrn_error("parallel: %d processes need at least %d cells along %c (%d per process); the grid has %d",
                     mrn_comm_size(), MRN_DIST_MIN_CELLS * mrn_comm_size(), "xyz"[axis], MRN_DIST_MIN_CELLS, nc);
  mrn_comm_set_shared_error(0);
  mrn_dist *d = calloc(1, sizeof *d);
  if (d) d->cut = calloc((size_t)mrn_comm_size() + 1, sizeof *d->cut);
  if (!d || !d->cut) {
    mrn_dist_free(d);
    return mrn_error("parallel: out of memory");
  }
  d->rank = mrn_comm_rank();
  d->size = mrn_comm_size();
  d->axis = axis;
  d->halo = 1;
  sim->dist = d;
  if ((rc = reserve(sim)) || (rc = cut_by_count(sim, d, 1)) || (rc = mrn_dist_adopt(sim, 0))) return rc;
  /* the books kept so far are process 0's; the others start at 0 */
  if (d->rank != 0) books_set(sim, &(mrn_books){0});
  return MRN_OK;
}

void mrn_dist_free(mrn_dist *d) {
  if (!d) return;
  free(d->cut);
  free(d->buf);
  free(d);
}

int mrn_dist_owns_point(const mrn_sim *sim, const double x[3]) {
  const mrn_dist *d = sim->dist;
  return !d || owner_of(d, row_of(&sim->grid, d->axis, x)) == d->rank;
}

void mrn_dist_reduce(const mrn_sim *sim, double *v, int n, mrn_comm_op op) {
  if (sim->dist) mrn_comm_allreduce(v, n, op);
}

int mrn_dist_agree(const mrn_sim *sim, int rc) {
  if (!sim->dist) return rc;
  const int failed = rc != MRN_OK; /* an error, or a stop asked for */
  long first = failed ? sim->dist->rank : sim->dist->size;
  mrn_comm_allreduce_long(&first, 1, MRN_COMM_MIN);
  if (first == sim->dist->size) return rc;
  struct {
    int code;
    char text[1024];
  } m = {rc, ""};
  if (first == sim->dist->rank) snprintf(m.text, sizeof m.text, "%s", mrn_error_message());
  mrn_comm_bcast(&m, sizeof m, (int)first);
  mrn_comm_set_shared_error(1);
  if (first == sim->dist->rank) return rc;
  return mrn_error_code(m.code, "%s", m.text);
}

static unsigned char *buffer(mrn_dist *d, size_t bytes) {
  if (bytes > d->buf_cap) {
    unsigned char *b = realloc(d->buf, bytes);
    if (!b) return NULL;
    d->buf = b;
    d->buf_cap = bytes;
  }
  return d->buf;
}

/* 1 when the cut axis is periodic: the last slab and the first then meet
 * at cut 0, through the wrap (the faces may change between steps) */
static int wraps(const mrn_sim *sim) { return mrn_boundary_periodic(&sim->boundary, sim->dist->axis); }

/* The band around cut c: the node planes [c - h, c + h] across the cut
 * axis, h = d->halo, wrapped around a periodic axis (the band of cut 0 is
 * then the last h planes and the first h + 1: a kernel wraps node ncell
 * onto node 0, so no process touches plane ncell). A plane is `nodes`
 * consecutive nodes and `rows` rows of the active spans (grid/active.h). */
typedef struct band {
  int first, count; /* planes first .. first + count - 1, domain numbering */
  int period;       /* ncell along a periodic cut axis, else 0 */
  long nodes;
  size_t rows;
} band;

static band band_at(const mrn_sim *sim, int c) {
  const mrn_grid *g = &sim->grid;
  const mrn_dist *d = sim->dist;
  const band b = {c - d->halo, 2 * d->halo + 1, wraps(sim) ? g->ncell[d->axis] : 0, g->stride[d->axis],
                  g->dim == 3 ? (size_t)g->nnode[1] : 1};
  return b;
}

/* the storage index of the band's k-th plane */
static long band_plane(const band *b, const mrn_grid *g, int k) {
  int j = b->first + k;
  if (b->period) j = (j % b->period + b->period) % b->period;
  return j + g->pad;
}

/* one nodal array's band into the message, or the message's added to it */
static double *put(double *m, const double *a, const mrn_grid *g, const band *b, int nc) {
  const size_t n = (size_t)nc * (size_t)b->nodes;
  for (int k = 0; k < b->count; k++, m += n) memcpy(m, a + nc * band_plane(b, g, k) * b->nodes, n * sizeof *m);
  return m;
}

static const double *add(const double *m, double *a, const mrn_grid *g, const band *b, int nc) {
  const long n = nc * b->nodes;
  for (int k = 0; k < b->count; k++, m += n) {
    double *t = a + band_plane(b, g, k) * n;
    for (long i = 0; i < n; i++) t[i] += m[i]; /* a + b == b + a: both sides hold the same sum */
  }
  return m;
}

/* a nodal array and its values per node */
typedef struct nodal {
  double *a;
  int nc;
} nodal;

/* Room for the exchanges of this band width, made before they start so
 * that none fails halfway (a process leaving one would leave its peer
 * waiting): the largest message, the spans and the mass, momentum and
 * force, sent and received. 0 or an error code. */
static int reserve(mrn_sim *sim) {
  const band b = band_at(sim, 0);
  const size_t bytes = (size_t)b.count * (b.rows * 2 * sizeof(int) + 7 * (size_t)b.nodes * sizeof(double));
  if (buffer(sim->dist, 2 * bytes)) return MRN_OK;
  return mrn_error("parallel: out of memory for the halo exchange (%d node rows around each cut)", b.count);
}

/* Sum the band around cut c with process `peer`: the message holds the
 * spans of its rows, then the arrays. A node the peer's span covers and
 * this one's did not held zero here, so the span widens to it before the
 * sum. */
static int exchange_band(mrn_sim *sim, int peer, int c, const nodal *arr, int narr) {
  mrn_grid *g = &sim->grid;
  mrn_dist *d = sim->dist;
  const band b = band_at(sim, c);
  int nd = 0;
  for (int k = 0; k < narr; k++) nd += arr[k].nc;
  const size_t rows = (size_t)b.count * b.rows;
  const size_t bytes = rows * 2 * sizeof(int) + (size_t)nd * (size_t)b.count * (size_t)b.nodes * sizeof(double);
  unsigned char *out = buffer(d, 2 * bytes), *in = out + bytes;
  if (!out) return mrn_error("parallel: out of memory for the halo exchange");
  const mrn_grid_active *a = g->active;
  int *span = (int *)out;
  for (int k = 0; k < b.count; k++)
    for (size_t r = 0, row = (size_t)band_plane(&b, g, k) * b.rows; r < b.rows; r++, row++, span += 2) {
      span[0] = a->lo[row];
      span[1] = a->hi[row];
    }
  double *m = (double *)(out + rows * 2 * sizeof(int));
  for (int k = 0; k < narr; k++) m = put(m, arr[k].a, g, &b, arr[k].nc);
  mrn_comm_exchange(peer, out, bytes, in, bytes);
  d->halo_bytes += (double)bytes;
  const int *theirs = (const int *)in;
  for (int k = 0; k < b.count; k++)
    for (size_t r = 0, row = (size_t)band_plane(&b, g, k) * b.rows; r < b.rows; r++, row++, theirs += 2)
      mrn_grid_active_widen(g, row, theirs[0], theirs[1]);
  mrn_grid_active_refresh(g);
  const double *q = (const double *)(in + rows * 2 * sizeof(int));
  for (int k = 0; k < narr; k++) q = add(q, arr[k].a, g, &b, arr[k].nc);
  return MRN_OK;
}

/* The cuts this process shares, ordered so that pairs of processes meet
 * at once: even ranks first up, odd ranks first down; then, on a periodic
 * cut axis, the wrap between the last slab and the first (cut 0), which
 * both do last. With two processes the same peer is met twice, at its cut
 * and at the wrap, in that order on both. */
static int neighbours(const mrn_sim *sim, int peer[2], int cut[2]) {
  const mrn_dist *d = sim->dist;
  int n = 0;
  const int up = d->rank + 1 < d->size, down = d->rank > 0;
  for (int pass = 0; pass < 2; pass++) {
    const int go_up = (d->rank % 2 == 0) == (pass == 0);
    if (go_up && up) {
      peer[n] = d->rank + 1;
      cut[n++] = d->cut[d->rank + 1];
    } else if (!go_up && down) {
      peer[n] = d->rank - 1;
      cut[n++] = d->cut[d->rank];
    }
  }
  if (wraps(sim) && (!up || !down)) {
    peer[n] = up ? d->size - 1 : 0;
    cut[n++] = 0;
  }
  return n;
}

static int sum_arrays(mrn_sim *sim, const nodal *arr, int narr) {
  int peer[2], cut[2], rc = MRN_OK;
  const int n = neighbours(sim, peer, cut);
  for (int k = 0; k < n && rc == MRN_OK; k++) rc = exchange_band(sim, peer[k], cut[k], arr, narr);
  return rc;
}

int mrn_dist_sum_halo(mrn_sim *sim, unsigned what, int rc) {
  if (!sim->dist || (rc = mrn_dist_agree(sim, rc)) != MRN_OK) return rc;
  mrn_grid *g = &sim->grid;
  nodal arr[3];
  int narr = 0;
  if (what & MRN_CLEAR_MASS_MOM) {
    arr[narr++] = (nodal){g->mass, 1};
    arr[narr++] = (nodal){g->mom, 3};
  }
  if (what & MRN_CLEAR_FORCE) arr[narr++] = (nodal){g->force, 3};
  return mrn_dist_agree(sim, sum_arrays(sim, arr, narr));
}

void mrn_dist_sum_nodal(void *ctx, double *values, int ncomp) {
  mrn_sim *sim = ctx;
  if (!sim->dist) return;
  const nodal arr = {values, ncomp};
  (void)mrn_dist_agree(sim, sum_arrays(sim, &arr, 1));
}

int mrn_dist_sum_bodies(mrn_sim *sim, unsigned what, int rc) {
  if (!sim->dist || (rc = mrn_dist_agree(sim, rc)) != MRN_OK) return rc;
  const mrn_contact *c = sim->contact;
  const size_t n = c->nnode;
  nodal arr[4 * MRN_MAX_BODIES];
  int narr = 0;
  for (size_t b = 0; b < (size_t)c->nbodies; b++) {
    if (what & MRN_CLEAR_MASS_MOM) {
      arr[narr++] = (nodal){c->mass + b * n, 1};
      arr[narr++] = (nodal){c->mom + 3 * b * n, 3};
      arr[narr++] = (nodal){c->grad + 3 * b * n, 3};
    }
    if (what & MRN_CLEAR_FORCE) arr[narr++] = (nodal){c->force + 3 * b * n, 3};
  }
  return mrn_dist_agree(sim, sum_arrays(sim, arr, narr));
}

double mrn_dist_once(const mrn_sim *sim, double value) { return !sim->dist || sim->dist->rank == 0 ? value : 0.0; }

int mrn_dist_or_bands(mrn_sim *sim, unsigned char *bits, unsigned char mask, int (*fresh)(void *arg, size_t node),
                      void *arg) {
  mrn_dist *d = sim->dist;
  const mrn_grid *g = &sim->grid;
  int peer[2], cut[2], rc = MRN_OK;
  const int n = neighbours(sim, peer, cut);
  for (int k = 0; k < n; k++) {
    const band b = band_at(sim, cut[k]);
    const size_t plane = (size_t)b.nodes, bytes = (size_t)b.count * plane;
    unsigned char *out = buffer(d, 2 * bytes), *in = out + bytes;
    if (!out) return mrn_error("parallel: out of memory for the halo exchange");
    for (int j = 0; j < b.count; j++) memcpy(out + j * plane, bits + band_plane(&b, g, j) * b.nodes, plane);
    mrn_comm_exchange(peer[k], out, bytes, in, bytes);
    d->halo_bytes += (double)bytes;
    for (int j = 0; j < b.count; j++) {
      const size_t first = band_plane(&b, g, j) * (size_t)b.nodes;
      for (size_t i = 0; i < plane; i++) {
        const unsigned char gain = in[j * plane + i] & mask & (unsigned char)~bits[first + i];
        bits[first + i] |= gain;
        if (gain && fresh && rc == MRN_OK) rc = fresh(arg, first + i);
      }
    }
  }
  return rc;
}

void mrn_dist_touch(mrn_sim *sim) {
  if (!sim->dist) return;
  int friction = 0;
  for (int f = 0; f < 2 * sim->dim; f++) friction |= sim->boundary.face[f].kind == MRN_BC_FRICTION;
  /* out of memory: this band's contacts stay one-sided for a step */
  if (friction) (void)mrn_dist_or_bands(sim, sim->grid.touch, 0xff, NULL, NULL);
}

int mrn_dist_or_marks(void *ctx, unsigned char *marks, int narrays, int rc) {
  mrn_sim *sim = ctx;
  if (!sim->dist || (rc = mrn_dist_agree(sim, rc)) != MRN_OK) return rc;
  const size_t n = sim->grid.n;
  for (int a = 0; a < narrays && rc == MRN_OK; a++) rc = mrn_dist_or_bands(sim, marks + (size_t)a * n, 0xff, NULL, NULL);
  return rc;
}

/* the cells slab r needs for bands of half width h: 2 h + 1 between two
 * bands, so that no node row is in two of them (a row three processes
 * reach would miss one's share); h + 1 at an end of the axis that does
 * not wrap */
static int slab_need(const mrn_sim *sim, int r, int h) {
  const mrn_dist *d = sim->dist;
  return (r == 0 || r == d->size - 1) && !wraps(sim) ? h + 1 : 2 * h + 1;
}

/* The half width h for shape functions that reach `reach` cells from a
 * particle: one in cell row j reaches, strictly within it, node rows
 * j + 1 - ceil(reach) to j + ceil(reach) (the friction faces' touch marks
 * those too), so the rows of a cut c that both sides reach are c - h to
 * c + h with h = ceil(reach) - 1, at least 1. The tracked domains (CPDI's
 * corners, cpGIMP's boxes) come with round-off: a margin. Beyond the grid
 * (or NaN) no slab holds it, as mrn_dist_halo then says. */
static int halo_for(const mrn_sim *sim, double reach) {
  const double margin = mrn_shape_tracks_domain(sim->shape) ? 1e-9 : 0.0;
  const double rows = ceil(reach + margin) - 1.0, most = sim->grid.ncell[sim->dist->axis] + 1;
  return rows <= most ? (int)fmax(1.0, rows) : (int)most;
}

int mrn_dist_halo(mrn_sim *sim, double reach, int rc) {
  mrn_dist *d = sim->dist;
  if (!d) return rc;
  if (!mrn_shape_tracks_domain(sim->shape)) { /* the same on every process: 1, the room mrn_dist_start reserved */
    d->halo = halo_for(sim, reach);
    return rc;
  }
  /* CPDI's and cpGIMP's grow with each process's domains */
  if ((rc = mrn_dist_agree(sim, rc)) != MRN_OK) return rc;
  mrn_comm_allreduce(&reach, 1, MRN_COMM_MAX);
  const int h = halo_for(sim, reach);
  for (int r = 0; r < d->size; r++) {
    const int have = d->cut[r + 1] - d->cut[r];
    if (have >= slab_need(sim, r, h)) continue;
    mrn_comm_set_shared_error(1); /* every process finds it alike */
    const char *what = sim->shape == MRN_SHAPE_CPGIMP ? "cpGIMP's boxes" : "CPDI's domains";
    return mrn_error("parallel: step %ld: %s have stretched until its shape functions reach %s cells "
                     "from their particles: the halo bands take node rows [cut - %d, cut + %d], and the slabs at "
                     "least %d cells (%d at an end of the axis); process %d's slab has %d: run on fewer processes "
                     "(doc/parallel.md)", sim->step + 1, what, mrn_num(reach).s, h, h, 2 * h + 1, h + 1, r, have);
  }
  d->halo = h;
  return mrn_dist_agree(sim, reserve(sim));
}

/* particles leaving this process: their destinations, the bytes for each
 * process and the offsets of each one's share (all P-long) */
typedef struct moves {
  size_t P, rec;
  int *dest;
  unsigned char *keep;
  size_t *cnt, *sdispl, *rcnt, *rdispl;
  size_t sent, got;
} moves;

static int plan_moves(mrn_sim *sim, moves *m) {
  const mrn_dist *d = sim->dist;
  const mrn_particles *ps = &sim->particles;
  m->P = (size_t)d->size;
  m->rec = mrn_particles_record_bytes(ps);
  m->cnt = calloc(4 * m->P, sizeof *m->cnt);
  m->dest = malloc((ps->n + 1) * sizeof *m->dest);
  m->keep = malloc(ps->n + 1);
  if (!m->cnt || !m->dest || !m->keep) return mrn_error("parallel: out of memory moving particles");
  m->sdispl = m->cnt + m->P;
  m->rcnt = m->cnt + 2 * m->P;
  m->rdispl = m->cnt + 3 * m->P;
  for (size_t p = 0; p < ps->n; p++) {
    m->dest[p] = owner_of(d, row_of(&sim->grid, d->axis, ps->x + 3 * p));
    m->keep[p] = m->dest[p] == d->rank;
    if (!m->keep[p]) m->cnt[m->dest[p]] += m->rec;
  }
  /* how much comes from each process: one size_t from each to each */
  size_t *one = calloc(2 * m->P, sizeof *one);
  if (!one) return mrn_error("parallel: out of memory moving particles");
  for (size_t r = 0; r < m->P; r++) {
    one[r] = sizeof(size_t);
    one[m->P + r] = r * sizeof(size_t);
  }
  mrn_comm_alltoallv(m->cnt, one, one + m->P, m->rcnt, one, one + m->P);
  free(one);
  for (size_t r = 0; r < m->P; r++) {
    m->sdispl[r] = m->sent;
    m->rdispl[r] = m->got;
    m->sent += m->cnt[r];
    m->got += m->rcnt[r];
  }
  return MRN_OK;
}

/* the records of the leaving particles, by destination */
static unsigned char *pack_moves(const mrn_particles *ps, const moves *m) {
  unsigned char *out = malloc(m->sent + 1);
  size_t *at = malloc(m->P * sizeof *at);
  if (out && at) {
    memcpy(at, m->sdispl, m->P * sizeof *at);
    for (size_t p = 0; p < ps->n; p++)
      if (!m->keep[p]) {
        mrn_particles_pack(ps, p, out + at[m->dest[p]]);
        at[m->dest[p]] += m->rec;
      }
  }
  free(at);
  if (!at) {
    free(out);
    return NULL;
  }
  return out;
}

/* Send every particle to the process owning its cell row; the arrivals
 * are appended in the order of their senders' ranks. */
static int move_particles(mrn_sim *sim) {
  mrn_dist *d = sim->dist;
  mrn_particles *ps = &sim->particles;
  moves m = {0};
  int rc = plan_moves(sim, &m);
  unsigned char *out = rc == MRN_OK ? pack_moves(ps, &m) : NULL, *in = rc == MRN_OK ? malloc(m.got + 1) : NULL;
  if (rc == MRN_OK && (!out || !in)) rc = mrn_error("parallel: out of memory moving particles");
  if (rc == MRN_OK) {
    mrn_comm_alltoallv(out, m.cnt, m.sdispl, in, m.rcnt, m.rdispl);
    d->migrate_bytes += (double)m.sent;
    d->migrated += (long)(m.sent / m.rec);
    if (m.sent > 0) mrn_particles_compact(ps, m.keep);
    for (size_t at = 0; at < m.got && rc == MRN_OK; at += m.rec)
      if (mrn_particles_unpack(ps, in + at) < 0) rc = MRN_ERR;
    /* a step without arrivals or departures keeps the binning's incremental update */
    if (sim->blocks && (m.sent > 0 || m.got > 0)) mrn_blocks_forget(sim->blocks);
  }
  free(m.cnt);
  free(m.dest);
  free(m.keep);
  free(out);
  free(in);
  return rc;
}

/* A re-cut gives a process rows whose contacts (grid.contact: the friction
 * faces' and the bodies') another kept: before it, every process takes each
 * node's bits from the process that owns it. */
static int pool_contacts(mrn_sim *sim) {
  mrn_grid *g = &sim->grid;
  double *all = calloc(g->n + 1, sizeof *all);
  int rc = mrn_dist_agree(sim, all ? MRN_OK : mrn_error("parallel: out of memory for the contacts"));
  if (rc == MRN_OK) {
    for (size_t i = 0; i < g->n; i++) all[i] = mrn_grid_owns(g, (long)i) ? g->contact[i] : 0.0;
    mrn_comm_allreduce(all, (int)g->n, MRN_COMM_SUM);
    for (size_t i = 0; i < g->n; i++) g->contact[i] = (unsigned char)all[i];
  }
  free(all);
  return rc;
}

int mrn_dist_rebalance(mrn_sim *sim) {
  if (!sim->dist) return MRN_OK;
  int rc = pool_contacts(sim);
  if (rc == MRN_OK) rc = cut_by_count(sim, sim->dist, 0);
  if (rc == MRN_OK) sim->dist->rebalances++;
  rc = mrn_dist_agree(sim, rc == MRN_OK ? move_particles(sim) : rc);
  return rc == MRN_OK ? mrn_dist_walls_recut(sim) : rc;
}

/* a re-cut is due every rebalance_every steps, when the largest particle
 * count exceeds the mean by the imbalance factor */
static int rebalance_due(mrn_sim *sim) {
  const mrn_dist *d = sim->dist;
  if (sim->rebalance_every <= 0 || sim->step % sim->rebalance_every != 0) return 0;
  double v[2] = {(double)sim->particles.n, (double)sim->particles.n};
  mrn_comm_allreduce(v, 1, MRN_COMM_SUM);
  mrn_comm_allreduce(v + 1, 1, MRN_COMM_MAX);
  return v[1] > sim->rebalance_imbalance * v[0] / d->size;
}

int mrn_dist_migrate(mrn_sim *sim, int rc) {
  if (!sim->dist || (rc = mrn_dist_agree(sim, rc)) != MRN_OK) return rc;
  if (rebalance_due(sim)) return mrn_dist_rebalance(sim);
  return mrn_dist_agree(sim, move_particles(sim));
}

/* a record's id: the last field of mrn_particles_pack's layout */
static int64_t record_id(const unsigned char *r, size_t rec) {
  int64_t id;
  memcpy(&id, r + rec - sizeof id, sizeof id);
  return id;
}

static size_t gather_rec; /* record size for the comparison below (one sort at a time) */

static int by_id(const void *a, const void *b) {
  const int64_t x = record_id(*(const unsigned char *const *)a, gather_rec);
  const int64_t y = record_id(*(const unsigned char *const *)b, gather_rec);
  return (x > y) - (x < y);
}

/* on process 0: a particle set laid out as `like`, holding the `total`
 * records of `all` in the order of their ids */
static int assemble(mrn_particles *out, const mrn_particles *like, const unsigned char *all, size_t total,
                    size_t rec) {
  mrn_particles_init(out, like->dim);
  out->user_stride = like->user_stride;
  out->nuser = like->nuser;
  memcpy(out->user_fields, like->user_fields, sizeof out->user_fields);
  out->next_id = like->next_id;
  const unsigned char **order = malloc((total + 1) * sizeof *order);
  int rc = order && mrn_particles_set_state_stride(out, like->state_stride) == MRN_OK &&
                   mrn_particles_reserve(out, total) == MRN_OK
               ? MRN_OK
               : mrn_error("parallel: out of memory gathering %zu particles", total);
  for (size_t i = 0; rc == MRN_OK && i < total; i++) order[i] = all + i * rec;
  gather_rec = rec;
  if (rc == MRN_OK) qsort(order, total, sizeof *order, by_id);
  for (size_t i = 0; rc == MRN_OK && i < total; i++)
    if (mrn_particles_unpack(out, order[i]) < 0) rc = MRN_ERR;
  free(order);
  return rc;
}

/* the books kept per process (dist.h) */
static mrn_books books_get(const mrn_sim *sim) {
  return (mrn_books){sim->work_friction, sim->work_damping, sim->work_external, sim->energy_inflow,
                     sim->work_inflow, sim->inflow_mass, (double)sim->inflow_particles, sim->energy_outflow,
                     sim->outflow_mass, (double)sim->outflow_particles};
}

static void books_set(mrn_sim *sim, const mrn_books *b) {
  sim->work_friction = b->friction;
  sim->work_damping = b->damping;
  sim->work_external = b->external;
  sim->energy_inflow = b->inflow;
  sim->work_inflow = b->inflow_work;
  sim->inflow_mass = b->inflow_mass;
  sim->inflow_particles = (long)b->inflow_particles;
  sim->energy_outflow = b->outflow;
  sim->outflow_mass = b->outflow_mass;
  sim->outflow_particles = (long)b->outflow_particles;
}

enum { BOOKS = sizeof(mrn_books) / sizeof(double) };

void mrn_dist_books(const mrn_sim *sim, mrn_books *b) {
  *b = books_get(sim);
  mrn_dist_reduce(sim, (double *)b, BOOKS, MRN_COMM_SUM);
}

/* The nodal values a checkpoint keeps and a grid snapshot shows (mass, V,
 * force, the contact bits), each row from the process that owns it, on
 * process 0 in place of its own (kept in d->held_mass, ...) until
 * gather_grid_end. Collective: the processes agree on their buffers
 * before the sum. */
enum { GRID_VALUES = 8 }; /* per node: mass, V, force, contact */

static int gather_grid(mrn_sim *sim, mrn_dist *d) {
  mrn_grid *g = &sim->grid;
  const size_t n = g->n;
  double *all = calloc(GRID_VALUES * n, sizeof *all);
  unsigned char *contact = d->rank == 0 ? malloc(n) : NULL;
  int ok = all && (d->rank != 0 || contact);
  const int rc = mrn_dist_agree(sim, ok ? MRN_OK : mrn_error("parallel: out of memory gathering the grid"));
  if (rc != MRN_OK) {
    free(all);
    free(contact);
    return rc;
  }
  for (size_t i = 0; i < n; i++) {
    if (!mrn_grid_owns(g, (long)i)) continue;
    all[i] = g->mass[i];
    for (int k = 0; k < 3; k++) {
      all[n + 3 * i + k] = g->vel[3 * i + k];
      all[4 * n + 3 * i + k] = g->force[3 * i + k];
    }
    all[7 * n + i] = g->contact[i];
  }
  mrn_comm_reduce_sum(all, GRID_VALUES * n, 0);
  if (d->rank == 0) {
    for (size_t i = 0; i < n; i++) contact[i] = (unsigned char)all[7 * n + i];
    d->held_mass = g->mass;
    d->held_vel = g->vel;
    d->held_force = g->force;
    g->mass = all;
    g->vel = all + n;
    g->force = all + 4 * n;
    d->held_contact = g->contact;
    g->contact = contact;
    return MRN_OK;
  }
  free(all);
  return MRN_OK;
}

static void gather_grid_end(mrn_sim *sim, mrn_dist *d) {
  mrn_grid *g = &sim->grid;
  if (!d->held_contact) return;
  free(g->mass); /* the block gather_grid made, from its start */
  free(g->contact);
  g->mass = d->held_mass;
  g->vel = d->held_vel;
  g->force = d->held_force;
  g->contact = d->held_contact;
  d->held_contact = NULL;
}

int mrn_dist_gather_begin(const mrn_sim *csim) {
  /* the particles and books are exchanged for the whole set's, and given
   * back by mrn_dist_gather_end: a writer sees a consistent simulation */
  mrn_sim *sim = (mrn_sim *)csim;
  mrn_dist *d = sim->dist;
  if (!d) return MRN_OK;
  const mrn_particles *ps = &sim->particles;
  const size_t rec = mrn_particles_record_bytes(ps), P = (size_t)d->size;
  size_t *cnt = calloc(2 * P, sizeof *cnt), *displ = cnt + P, total = 0;
  unsigned char *mine = malloc(ps->n * rec + 1), *all = NULL;
  int rc = cnt && mine ? MRN_OK : mrn_error("parallel: out of memory gathering the particles");
  if (rc == MRN_OK) {
    for (size_t p = 0; p < ps->n; p++) mrn_particles_pack(ps, p, mine + p * rec);
    mrn_comm_allgather_size(ps->n * rec, cnt);
    for (size_t r = 0; r < P; r++) {
      displ[r] = total;
      total += cnt[r];
    }
    all = d->rank == 0 ? malloc(total + 1) : NULL;
    if (d->rank == 0 && !all) rc = mrn_error("parallel: out of memory gathering the particles");
    mrn_comm_gatherv(mine, ps->n * rec, all, cnt, displ, 0);
  }
  mrn_particles whole;
  if (rc == MRN_OK && d->rank == 0 && (rc = assemble(&whole, ps, all, total / rec, rec)) == MRN_OK) {
    d->held = malloc(sizeof *d->held);
    if (d->held) {
      *d->held = sim->particles;
      sim->particles = whole;
    } else {
      mrn_particles_free(&whole);
      rc = mrn_error("parallel: out of memory gathering the particles");
    }
  }
  /* process 0 alone may have failed to assemble: agreed before the grid's sum */
  rc = mrn_dist_agree(sim, rc);
  if (rc == MRN_OK) rc = gather_grid(sim, d);
  if ((rc = mrn_dist_agree(sim, rc)) == MRN_OK) rc = mrn_dist_walls_gather(sim);
  d->held_books = books_get(sim);
  mrn_books b = d->held_books;
  mrn_comm_allreduce((double *)&b, BOOKS, MRN_COMM_SUM);
  if (d->rank == 0) books_set(sim, &b);
  free(cnt);
  free(mine);
  free(all);
  return mrn_dist_agree(sim, rc);
}

void mrn_dist_gather_end(const mrn_sim *csim) {
  mrn_sim *sim = (mrn_sim *)csim;
  mrn_dist *d = sim->dist;
  if (!d) return;
  gather_grid_end(sim, d);
  mrn_dist_walls_gather_end(sim);
  books_set(sim, &d->held_books);
  if (!d->held) return;
  mrn_particles_free(&sim->particles);
  sim->particles = *d->held;
  free(d->held);
  d->held = NULL;
}

static int by_key(const void *a, const void *b) {
  const int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
  return (x > y) - (x < y);
}

int mrn_dist_allgather(const mrn_sim *sim, const void *mine, size_t bytes, unsigned char **all, size_t *total,
                       int rc) {
  *all = NULL, *total = 0;
  const size_t P = sim->dist ? (size_t)sim->dist->size : 1;
  /* bytes from each process and where they go; bytes to each and where
   * they come from: the same bytes to each, from the start */
  size_t *cnt = calloc(4 * P, sizeof *cnt);
  if (!cnt && rc == MRN_OK) rc = mrn_error("parallel: out of memory");
  if ((rc = mrn_dist_agree(sim, rc)) != MRN_OK) {
    free(cnt);
    return rc;
  }
  size_t *displ = cnt + P, *scnt = cnt + 2 * P, *sdispl = cnt + 3 * P, sum = 0;
  if (sim->dist) mrn_comm_allgather_size(bytes, cnt);
  else cnt[0] = bytes;
  for (size_t r = 0; r < P; r++) {
    displ[r] = sum;
    sum += cnt[r];
    scnt[r] = bytes;
  }
  unsigned char *buf = malloc(sum + 1);
  rc = mrn_dist_agree(sim, buf ? MRN_OK : mrn_error("parallel: out of memory gathering %zu bytes", sum));
  if (rc == MRN_OK && sim->dist) mrn_comm_alltoallv(mine, scnt, sdispl, buf, cnt, displ);
  else if (rc == MRN_OK && bytes) memcpy(buf, mine, bytes);
  free(cnt);
  if (rc != MRN_OK) {
    free(buf);
    return rc;
  }
  *all = buf;
  *total = sum;
  return MRN_OK;
}

int mrn_dist_key_places(const mrn_sim *sim, const int64_t *keys, size_t n, int64_t *place, int64_t *total, int rc) {
  if (!sim->dist) {
    for (size_t k = 0; k < n; k++) place[k] = (int64_t)k;
    *total = (int64_t)n;
    return rc;
  }
  unsigned char *bytes = NULL;
  size_t got = 0;
  rc = mrn_dist_allgather(sim, keys, n * sizeof *keys, &bytes, &got, rc);
  int64_t *all = (int64_t *)bytes;
  *total = (int64_t)(got / sizeof *keys);
  if (rc == MRN_OK && *total > 0) {
    qsort(all, (size_t)*total, sizeof *all, by_key);
    /* a key's place: the keys below it, found by bisection */
    for (size_t k = 0; k < n; k++) {
      size_t lo = 0, hi = (size_t)*total;
      while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (all[mid] < keys[k]) lo = mid + 1;
        else hi = mid;
      }
      place[k] = (int64_t)lo;
    }
  }
  free(all);
  return rc;
}

int mrn_dist_gather_grid_begin(const mrn_sim *sim) {
  return sim->dist ? gather_grid((mrn_sim *)sim, sim->dist) : MRN_OK;
}

void mrn_dist_gather_grid_end(const mrn_sim *sim) {
  if (sim->dist) gather_grid_end((mrn_sim *)sim, sim->dist);
}

int mrn_sim_set_rebalance(mrn_sim *sim, long every, double imbalance) {
  if (every < 0) return mrn_error("parallel: rebalance_every must be >= 0, got %ld", every);
  if (!(imbalance >= 1.0) || !isfinite(imbalance))
    return mrn_error("parallel: imbalance must be a finite number >= 1, got %s", mrn_num(imbalance).s);
  sim->rebalance_every = every;
  sim->rebalance_imbalance = imbalance;
  return MRN_OK;
}

void mrn_dist_max_over(void *ctx, double *values, int n) { mrn_dist_reduce(ctx, values, n, MRN_COMM_MAX); }

/* the records [0, total) of buf, each ending with its int64 id, put in the
 * order of their ids */
static int sort_records(unsigned char *buf, size_t total, size_t rec) {
  const unsigned char **order = malloc((total + 1) * sizeof *order);
  unsigned char *sorted = malloc(total * rec + 1);
  if (!order || !sorted) {
    free(order);
    free(sorted);
    return mrn_error("parallel: out of memory sorting %zu records", total);
  }
  for (size_t i = 0; i < total; i++) order[i] = buf + i * rec;
  gather_rec = rec;
  qsort(order, total, sizeof *order, by_id);
  for (size_t i = 0; i < total; i++) memcpy(sorted + i * rec, order[i], rec);
  memcpy(buf, sorted, total * rec);
  free(order);
  free(sorted);
  return MRN_OK;
}

int mrn_dist_gather_by_id(const mrn_sim *sim, const unsigned char *mine, size_t n, size_t rec, unsigned char **all,
                          size_t *total) {
  size_t bytes = 0;
  int rc = mrn_dist_allgather(sim, mine, n * rec, all, &bytes, MRN_OK);
  if (rc == MRN_OK) rc = sort_records(*all, bytes / rec, rec);
  if (rc != MRN_OK) {
    free(*all);
    *all = NULL;
    return rc;
  }
  *total = bytes / rec;
  return MRN_OK;
}
