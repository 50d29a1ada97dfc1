#include "transfer/blocks.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "core/parallel.h"
#include "particles/sort.h"
#include "transfer/context.h"
#include "transfer/profile.h"

/* Cells per block along an axis, as a power of 2 (at least 3 cells along
 * every axis for the colouring to hold). Blocks are long along x, the axis
 * along which both the nodes and (in seeding or sorted order) the particles
 * lie next to each other in memory: 32 x 4 cells in 2D, 16 x 4 x 4 in 3D.
 * A block long along x keeps a P2G's stencils on few cache lines of the
 * nodal arrays; small enough that even the smallest bench problems have many
 * blocks of each colour for the threads to share (doc/performance.md). */
static int block_shift(int dim, int axis) {
  if (dim == 2) return axis == 0 ? 5 : 2;
  return axis == 0 ? 4 : 2;
}

mrn_blocks *mrn_blocks_new(const mrn_grid *g) {
  mrn_blocks *b = calloc(1, sizeof *b);
  if (!b) {
    mrn_error("grid: out of memory");
    return NULL;
  }
  b->nblocks = 1;
  for (int d = 0; d < 3; d++) {
    b->ncell[d] = d < g->dim ? g->nnode[d] - 1 : 1;
    b->shift[d] = d < g->dim ? block_shift(g->dim, d) : 0;
    b->size[d] = 1 << b->shift[d];
    b->nb[d] = d < g->dim ? (b->ncell[d] + b->size[d] - 1) / b->size[d] : 1;
    b->nblocks *= (size_t)b->nb[d];
  }
  b->colours = 1 << g->dim;
  b->start = malloc((b->nblocks + 1) * sizeof *b->start);
  b->list = malloc(b->nblocks * sizeof *b->list);
  b->movers = malloc(MRN_BLOCK_MOVERS_MAX * sizeof *b->movers);
  b->moved_out = malloc(2 * b->nblocks * sizeof *b->moved_out);
  b->moved_in = b->moved_out ? b->moved_out + b->nblocks : NULL;
  if (!b->start || !b->list || !b->movers || !b->moved_out) {
    mrn_blocks_free(b);
    mrn_error("grid: out of memory");
    return NULL;
  }
  return b;
}

void mrn_blocks_free(mrn_blocks *b) {
  if (!b) return;
  free(b->order);
  free(b->start);
  free(b->hist);
  free(b->movers);
  free(b->found);
  free(b->moved_out);
  free(b->list);
  free(b);
}

size_t mrn_blocks_bytes(const mrn_blocks *b) {
  if (!b) return 0;
  return sizeof *b + b->cap * sizeof(uint32_t) + (b->nblocks + 1) * sizeof(size_t) +
         (size_t)b->hist_threads * b->nblocks * sizeof(uint32_t) + b->nblocks * sizeof(uint32_t) +
         MRN_BLOCK_MOVERS_MAX * sizeof(struct mrn_block_mover) + (size_t)b->hist_threads * sizeof(size_t) +
         2 * b->nblocks * sizeof(uint32_t);
}

void mrn_blocks_reuse(mrn_blocks *b) {
  if (b) b->reuse = 1;
}

static int grow_particles(mrn_blocks *b, size_t n, int threads) {
  if (n > b->cap) {
    size_t cap = n + n / 8;
    uint32_t *o = realloc(b->order, cap * sizeof *o);
    if (!o) return 0;
    b->order = o;
    b->cap = cap;
  }
  if (threads > b->hist_threads) {
    uint32_t *h = realloc(b->hist, (size_t)threads * b->nblocks * sizeof *h);
    if (!h) return 0;
    b->hist = h;
    size_t *f = realloc(b->found, (size_t)threads * sizeof *f);
    if (!f) return 0;
    b->found = f;
    b->hist_threads = threads;
  }
  return 1;
}

/* What the block of a particle depends on, copied out of the grid and the
 * blocks so that the binning loops keep it in registers (the counts they
 * store are uint32_t, which may alias the int fields of mrn_blocks). */
typedef struct block_map {
  double origin[3], inv_cell, pad;
  double top[3]; /* last padded cell along each axis */
  int shift[3];
  uint32_t nb[3];
} block_map;

static block_map block_map_of(const mrn_blocks *b, const mrn_grid *g) {
  block_map m = {.inv_cell = g->inv_cell, .pad = g->pad};
  for (int d = 0; d < 3; d++) {
    m.origin[d] = g->origin[d];
    m.top[d] = b->ncell[d] - 1.0;
    m.shift[d] = b->shift[d];
    m.nb[d] = (uint32_t)b->nb[d];
  }
  return m;
}

/* the block of the padded cell holding x (clamped to the grid) */
static inline __attribute__((always_inline)) uint32_t block_of(const block_map *m, const int dim, const double *x) {
  uint32_t key = 0, mul = 1;
  for (int d = 0; d < dim; d++) {
    double xi = floor((x[d] - m->origin[d]) * m->inv_cell) + m->pad;
    xi = xi > 0.0 ? xi : 0.0; /* clamped in floating point: max, min, one conversion (NaN -> 0) */
    xi = xi < m->top[d] ? xi : m->top[d];
    key += mul * ((uint32_t)xi >> m->shift[d]);
    mul *= m->nb[d];
  }
  return key;
}

/* The blocks of particles [lo, lo + n), n <= BIN_CHUNK, into key: one loop
 * without branches or calls, which the compiler vectorises. */
enum { BIN_CHUNK = 256 };
static inline __attribute__((always_inline)) void block_keys(const block_map *m, const int dim, const double *x,
                                                             size_t lo, size_t n, uint32_t *restrict key) {
  for (size_t i = 0; i < n; i++) key[i] = block_of(m, dim, x + 3 * (lo + i));
}

/* Stable counting sort of the particles by block, in parallel, with the
 * same result for any number of threads: the part of one thread of the
 * team. The second pass works the block of each particle out again rather
 * than keeping it from the first (4 bytes per particle less; the particles
 * have not moved in between, so it is the same block). Neighbouring
 * particles mostly share a block, so both passes keep the count (the next
 * slot) of the current run of one block in a register and store it when the
 * block changes. `dim` is a constant in each instance (bin_2d, bin_3d: the
 * parallel regions sit there, as GCC outlines a region before it inlines). */
static inline __attribute__((always_inline)) void bin_thread(mrn_blocks *b, const mrn_particles *ps,
                                                             const block_map map, const int dim) {
  int t = 0, nt = 1;
#ifdef _OPENMP
  t = omp_get_thread_num();
  nt = omp_get_num_threads();
#endif
  const size_t n = ps->n, nb = b->nblocks;
  const double *x = ps->x;
  uint32_t *order = b->order;
  const size_t lo = n * (size_t)t / (size_t)nt, hi = n * (size_t)(t + 1) / (size_t)nt;
  uint32_t *h = b->hist + (size_t)t * nb;
  uint32_t key[BIN_CHUNK];
  memset(h, 0, nb * sizeof *h);
  uint32_t run_key = 0, run = 0;
  for (size_t c = lo; c < hi; c += BIN_CHUNK) {
    const size_t len = hi - c < BIN_CHUNK ? hi - c : BIN_CHUNK;
    block_keys(&map, dim, x, c, len, key);
    for (size_t i = 0; i < len; i++) {
      if (key[i] != run_key) {
        h[run_key] += run;
        run_key = key[i];
        run = 0;
      }
      run++;
    }
  }
  h[run_key] += run;
#pragma omp barrier
#pragma omp single
  {
    size_t total = 0;
    for (size_t k = 0; k < nb; k++) {
      b->start[k] = total;
      for (int s = 0; s < nt; s++) {
        uint32_t c = b->hist[(size_t)s * nb + k];
        b->hist[(size_t)s * nb + k] = (uint32_t)total;
        total += c;
      }
    }
    b->start[nb] = total;
  }
  /* the first particle's block starts the first run; every change of block
   * starts another */
  uint32_t at_key = lo < hi ? block_of(&map, dim, x + 3 * lo) : 0, at = h[at_key];
  size_t runs = lo < hi;
  for (size_t c = lo; c < hi; c += BIN_CHUNK) {
    const size_t len = hi - c < BIN_CHUNK ? hi - c : BIN_CHUNK;
    block_keys(&map, dim, x, c, len, key);
    for (size_t i = 0; i < len; i++) {
      if (key[i] != at_key) {
        h[at_key] = at;
        at_key = key[i];
        at = h[at_key];
        runs++;
      }
      order[at++] = (uint32_t)(c + i);
    }
  }
  h[at_key] = at;
#pragma omp atomic
  b->runs += runs;
}

static void bin_2d(mrn_blocks *b, const block_map map, const mrn_particles *ps, int threads) {
#pragma omp parallel num_threads(threads) if (threads > 1)
  bin_thread(b, ps, map, 2);
}

static void bin_3d(mrn_blocks *b, const block_map map, const mrn_particles *ps, int threads) {
#pragma omp parallel num_threads(threads) if (threads > 1)
  bin_thread(b, ps, map, 3);
}

/* ---- incremental rebinning ------------------------------------------------
 *
 * From one step to the next few particles change block (a particle crosses a
 * block's side about once in size / (v dt) steps). The binning is a stable
 * sort of the particle indices by block, so it is the previous one with the
 * particles that changed block (the movers) taken out of their old block's
 * run and put into their new block's at their index; with no mover, it is
 * the previous one. rebin finds the movers in one parallel pass over `order`
 * (the block of each particle worked out once, against the block of its
 * slot) and then patches `order` in place. The result is the same `order`
 * and `start` as binning from scratch, so P2G is bitwise the same. It needs
 * the previous binning to be of as many particles (every index 0 .. n-1 in
 * it once, in increasing index within each block): any change of the
 * particles since then (moved, added, removed, reordered) only makes more
 * movers. With more than MRN_BLOCK_MOVERS_MAX, the caller bins from scratch,
 * and rebin is not tried again for REBIN_WAIT binnings. */
enum { REBIN_WAIT = 16 };

/* the block whose slots [start[k], start[k + 1]) hold `slot` (the last k with
 * start[k] <= slot: empty blocks before it are skipped) */
static size_t block_of_slot(const mrn_blocks *b, size_t slot) {
  size_t lo = 0, hi = b->nblocks; /* start[lo] <= slot < start[hi] */
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (b->start[mid] <= slot) lo = mid;
    else hi = mid;
  }
  return lo;
}

/* The movers among the slots of one thread of the team, into its share of
 * b->movers (in slot order); b->found[t] their count, or SIZE_MAX when they
 * did not fit. The blocks of a chunk of slots are formed in a loop of their
 * own (block_of on the gathered positions), then compared. */
static inline __attribute__((always_inline)) void find_movers(mrn_blocks *b, const mrn_particles *ps,
                                                              const block_map map, const int dim, int threads) {
  int t = 0, nt = 1;
#ifdef _OPENMP
  t = omp_get_thread_num();
  nt = omp_get_num_threads();
#endif
  const size_t n = ps->n, room = MRN_BLOCK_MOVERS_MAX / (size_t)threads;
  const size_t lo = n * (size_t)t / (size_t)nt, hi = n * (size_t)(t + 1) / (size_t)nt;
  const double *x = ps->x;
  const uint32_t *order = b->order;
  mrn_block_mover *mine = b->movers + room * (size_t)t;
  size_t found = 0;
  uint32_t key[BIN_CHUNK];
  size_t k = lo < hi ? block_of_slot(b, lo) : 0, next = b->start[k + 1];
  for (size_t c = lo; c < hi && found != SIZE_MAX; c += BIN_CHUNK) {
    const size_t len = hi - c < BIN_CHUNK ? hi - c : BIN_CHUNK;
    for (size_t i = 0; i < len; i++) key[i] = block_of(&map, dim, x + 3 * (size_t)order[c + i]);
    for (size_t i = 0; i < len; i++) {
      const size_t slot = c + i;
      while (slot >= next) next = b->start[++k + 1];
      if (key[i] == k) continue;
      if (found == room) {
        found = SIZE_MAX;
        break;
      }
      mine[found++] = (mrn_block_mover){(uint32_t)slot, order[slot], (uint32_t)k, key[i]};
    }
  }
  b->found[t] = found;
  if (t == 0) b->found_threads = nt; /* the team may be smaller than asked */
}

static void find_movers_2d(mrn_blocks *b, const block_map map, const mrn_particles *ps, int threads) {
#pragma omp parallel num_threads(threads) if (threads > 1)
  find_movers(b, ps, map, 2, threads);
}

static void find_movers_3d(mrn_blocks *b, const block_map map, const mrn_particles *ps, int threads) {
#pragma omp parallel num_threads(threads) if (threads > 1)
  find_movers(b, ps, map, 3, threads);
}

/* movers by new block, then index: the order they take in their new blocks */
static int mover_cmp(const void *pa, const void *pb) {
  const mrn_block_mover *a = pa, *b = pb;
  if (a->to != b->to) return a->to < b->to ? -1 : 1;
  return (a->p > b->p) - (a->p < b->p);
}

/* runs of consecutive particle indices within the blocks of `order` */
static size_t count_runs(const mrn_blocks *b, size_t n) {
  const uint32_t *o = b->order;
  size_t breaks = 0;
  for (size_t s = 1; s < n; s++) breaks += o[s] != o[s - 1] + 1;
  size_t runs = n > 0 ? 1 + breaks : 0;
  /* a block's first slot starts a run even when its index follows the last of the block before */
  for (size_t k = 1; k < b->nblocks; k++) {
    const size_t s = b->start[k];
    if (s > 0 && s < b->start[k + 1] && o[s] == o[s - 1] + 1) runs++;
  }
  return runs;
}

/* Patch order and start for the movers m[0 .. total), in slot order. */
static void apply_movers(mrn_blocks *b, mrn_block_mover *m, size_t total, size_t n) {
  uint32_t *order = b->order, *out = b->moved_out, *in = b->moved_in;
  const size_t nb = b->nblocks;
  memset(out, 0, 2 * nb * sizeof *out);
  for (size_t j = 0; j < total; j++) {
    out[m[j].from]++;
    in[m[j].to]++;
  }
  /* the movers out: the rest slides down over their slots, in order */
  size_t w = m[0].slot;
  for (size_t j = 0; j < total; j++) {
    const size_t from = (size_t)m[j].slot + 1, to = j + 1 < total ? m[j + 1].slot : n;
    memmove(order + w, order + from, (to - from) * sizeof *order);
    w += to - from;
  }
  /* the movers in, block by block from the last: block k's remaining
   * particles sit at [cs, ce) (its old slots less the movers out of the
   * blocks before it and of itself) and go to [start_new(k), start_new(k+1)),
   * merged by index with its movers in. The write position never falls
   * behind the read position (the difference is the movers in still to
   * place), so nothing is overwritten before it is read; once every mover is
   * placed the blocks below are where they were. */
  qsort(m, total, sizeof *m, mover_cmp);
  size_t out_below = total, new_end = n; /* movers out of the blocks before k; start_new(k + 1) */
  long j = (long)total - 1;
  size_t k = nb;
  while (k > 0 && j >= 0) {
    k--;
    out_below -= out[k];
    const size_t stay = b->start[k + 1] - b->start[k] - out[k];
    const size_t cs = b->start[k] - out_below;
    size_t r = cs + stay, wp = new_end;
    while (j >= 0 && m[j].to == k) {
      const uint32_t p = m[j].p;
      while (r > cs && order[r - 1] > p) order[--wp] = order[--r];
      order[--wp] = p;
      j--;
    }
    while (r > cs && wp != r) order[--wp] = order[--r];
    b->start[k + 1] = new_end;
    new_end -= stay + in[k];
  }
  /* below block k no mover came in: those blocks start lower by the movers
   * out of the blocks before them, and their particles are already there */
  size_t below = 0;
  for (size_t i = 0; i < k; i++) {
    below += out[i];
    b->start[i + 1] -= below;
  }
}

/* 1 when the binning was brought up to date by patching, 0 when the caller
 * must bin from scratch */
static int rebin(mrn_blocks *b, const mrn_grid *g, const mrn_particles *ps, int threads) {
  if (b->np != ps->n || !ps->n || b->rebin_wait > 0) {
    if (b->rebin_wait > 0) b->rebin_wait--;
    return 0;
  }
  const block_map map = block_map_of(b, g);
  if (g->dim == 2) find_movers_2d(b, map, ps, threads);
  else find_movers_3d(b, map, ps, threads);
  const size_t room = MRN_BLOCK_MOVERS_MAX / (size_t)threads;
  size_t total = 0;
  for (int t = 0; t < b->found_threads; t++) {
    if (b->found[t] == SIZE_MAX) {
      b->rebin_wait = REBIN_WAIT;
      return 0;
    }
    /* the threads' shares one after the other, in slot order */
    memmove(b->movers + total, b->movers + room * (size_t)t, b->found[t] * sizeof *b->movers);
    total += b->found[t];
  }
  if (!total) return 1;
  apply_movers(b, b->movers, total, ps->n);
  b->runs = count_runs(b, ps->n);
  return 1;
}

static void bin(mrn_blocks *b, const mrn_grid *g, const mrn_particles *ps, int threads) {
  if (rebin(b, g, ps, threads)) return;
  const block_map map = block_map_of(b, g);
  b->runs = 0;
  if (g->dim == 2) bin_2d(b, map, ps, threads);
  else bin_3d(b, map, ps, threads);
  b->np = ps->n;
}

/* non-empty blocks by colour, and the node spans they reach (the grid's
 * next active spans) */
static void colour_and_spans(mrn_blocks *b, mrn_grid *g) {
  size_t count[8] = {0};
  const int SX = b->size[0], SY = b->size[1], SZ = b->size[2];
  mrn_grid_active *active = g->active;
  mrn_grid_active_begin(g);
  for (int pass = 0; pass < 2; pass++) {
    size_t at[8];
    if (pass == 1) {
      size_t run = 0;
      for (int c = 0; c < b->colours; c++) {
        b->colour_first[c] = at[c] = run;
        run += count[c];
      }
      b->colour_first[b->colours] = run;
    }
    for (int bz = 0; bz < b->nb[2]; bz++)
      for (int by = 0; by < b->nb[1]; by++)
        for (int bx = 0; bx < b->nb[0]; bx++) {
          size_t k = (size_t)bx + (size_t)b->nb[0] * ((size_t)by + (size_t)b->nb[1] * (size_t)bz);
          if (b->start[k + 1] == b->start[k]) continue;
          int c = (bx & 1) | (by & 1) << 1 | (bz & 1) << 2;
          if (pass == 0) {
            count[c]++;
            continue;
          }
          b->list[at[c]++] = (uint32_t)k;
          /* a particle in cell i touches nodes i-1 .. i+2 */
          int x0 = bx * SX - 1, x1 = bx * SX + SX + 2;
          if (x0 < 0) x0 = 0;
          if (x1 > g->nnode[0]) x1 = g->nnode[0];
          int y0 = by * SY - 1, y1 = by * SY + SY + 2, z0 = 0, z1 = 1;
          if (y0 < 0) y0 = 0;
          if (y1 > g->nnode[1]) y1 = g->nnode[1];
          if (g->dim == 3) {
            z0 = bz * SZ - 1, z1 = bz * SZ + SZ + 2;
            if (z0 < 0) z0 = 0;
            if (z1 > g->nnode[2]) z1 = g->nnode[2];
          }
          for (int z = z0; z < z1; z++)
            for (int y = y0; y < y1; y++) {
              mrn_grid_active_reach(active, (size_t)y + (size_t)g->nnode[1] * (size_t)z, x0, x1);
            }
        }
  }
}

static int threads_for(size_t n) {
#ifdef _OPENMP
  return n > MRN_OMP_MIN_ITEMS ? omp_get_max_threads() : 1;
#else
  (void)n;
  return 1;
#endif
}

/* reorder the particles by block (the binning just made), and the binning
 * with them: one run per non-empty block */
static void sort_particles(mrn_blocks *b, mrn_transfer *tr) {
  const mrn_particles *ps = tr->particles;
  double t0 = mrn_phase_begin();
  if (mrn_particles_permute(tr->particles, b->order) == MRN_OK) {
    for (size_t i = 0; i < ps->n; i++) b->order[i] = (uint32_t)i;
    b->runs = 0;
    for (size_t k = 0; k < b->nblocks; k++) b->runs += b->start[k + 1] > b->start[k];
    tr->sort_now = 0;
  }
  mrn_phase_end(MRN_PHASE_SORT, t0);
}

mrn_blocks *mrn_blocks_prepare(mrn_transfer *tr, unsigned clear) {
  mrn_grid *g = tr->grid;
  mrn_blocks *b = tr->blocks;
  const mrn_particles *ps = tr->particles;
  const int reuse = b->reuse;
  b->reuse = 0;
  if (reuse && b->np == ps->n) {
    mrn_grid_active_switch(g, clear); /* the spans stay: this clears the arrays named in `clear` on them */
    return b;
  }
  int threads = threads_for(ps->n);
  int dense = 0;
  for (int d = 0; d < g->dim; d++) dense |= mrn_boundary_periodic(tr->boundary, d);
  b->dense = dense;
  if (ps->n > UINT32_MAX || !grow_particles(b, ps->n, threads)) {
    /* no room to bin: everything active, the caller scatters in index order */
    b->np = 0; /* no binning to reuse */
    mrn_grid_active_all(g);
    mrn_grid_active_switch(g, clear);
    return NULL;
  }
  bin(b, g, ps, threads);
  if (tr->sort_now) sort_particles(b, tr);
  colour_and_spans(b, g);
  if (dense) mrn_grid_active_all(g);
  mrn_grid_active_switch(g, clear);
  return b;
}

void mrn_blocks_forget(mrn_blocks *b) {
  b->np = 0;
  b->reuse = 0;
}
