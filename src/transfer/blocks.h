/* moraine: particles binned by blocks of cells.
 *
 * P2G scatters every particle's contributions into the nodes around it. To
 * do that on several threads without races and without per-thread grids,
 * the padded cell range is cut into blocks of size[d] cells along axis d
 * (32 x 4 in 2D, 16 x 4 x 4 in 3D); a particle in cell c only touches the
 * nodes c-1 .. c+2 along each axis (support of at most 4 nodes), so two
 * blocks whose indices differ by 2 along an axis never touch the same node
 * once every size[d] >= 3. Blocks are coloured by
 * the parity of their indices (4 colours in 2D, 8 in 3D); the blocks of one
 * colour are processed in parallel, the colours one after the other, and
 * the particles of a block in increasing index. Every node therefore adds
 * its contributions in the same order whatever the number of threads: the
 * result is bitwise identical for 1, 2 or more threads.
 *
 * The same binning tells which node rows can receive anything: P2G sets the
 * grid's active spans (grid/active.h) from the non-empty blocks, so that it
 * clears only those and the grid loops of the step visit only them.
 *
 * When the transfer context asks for it (mrn_transfer.sort_now, set by the
 * simulation's sort policy), the particles themselves are reordered by block
 * at the next binning, so that the particles of a block are contiguous in
 * memory. This changes particle indices (ids are kept). */
#ifndef MRN_TRANSFER_BLOCKS_H
#define MRN_TRANSFER_BLOCKS_H

#include <stddef.h>
#include <stdint.h>

#include "core/parallel.h"
#include "grid/active.h"

struct mrn_grid;
struct mrn_transfer;

/* A particle found out of the block it was binned in: at slot `slot` of
 * `order`, particle `p`, from block `from` to block `to`. */
typedef struct mrn_block_mover {
  uint32_t slot, p, from, to;
} mrn_block_mover;
/* At most this many movers per step are moved by patching the order;
 * beyond, the particles are binned from scratch (a few thousand particles
 * leave their block per step even in a fast flow of a million). */
enum { MRN_BLOCK_MOVERS_MAX = 4096 };

typedef struct mrn_blocks {
  int size[3];     /* cells per block along each axis, 1 << shift (>= 3 for the colouring) */
  int shift[3];
  int ncell[3];    /* padded cells per axis (nodes - 1; 1 along unused axes) */
  int nb[3];       /* blocks per axis (1 along unused axes) */
  size_t nblocks;
  int colours;     /* 2^dim */
  int dense;       /* periodic axes: every row is fully active, one thread scatters */

  /* particles grouped by block: order[start[b] .. start[b + 1]) */
  size_t np, cap;
  uint32_t *order;
  size_t *start;   /* nblocks + 1 */
  uint32_t *hist;  /* per-thread block counts, hist_threads * nblocks */
  int hist_threads;
  size_t runs;     /* runs of consecutive particle indices in `order` (within a block) */
  /* incremental rebinning (blocks.c, rebin): the particles found out of
   * their block, each thread's share of them, and per-block counts */
  struct mrn_block_mover *movers; /* MRN_BLOCK_MOVERS_MAX */
  size_t *found;                  /* hist_threads: movers found by each thread, or SIZE_MAX */
  int found_threads;              /* threads of the last search */
  uint32_t *moved_out, *moved_in; /* nblocks each */
  int rebin_wait;                 /* full binnings left before the next rebin is tried */
  uint32_t *list;  /* non-empty blocks, by colour */
  size_t colour_first[9];

  int reuse;       /* the next mrn_blocks_prepare keeps the binning (mrn_blocks_reuse) */
} mrn_blocks;

/* the blocks of grid g (the grid's shape only: one grid may be shared by
 * several binnings); NULL on failure (message set) */
mrn_blocks *mrn_blocks_new(const struct mrn_grid *g);
void mrn_blocks_free(mrn_blocks *b);
/* bytes held, for memory reports */
size_t mrn_blocks_bytes(const mrn_blocks *b);

/* The particles have not moved, nor been added, removed or reordered, since
 * the last P2G: the next one keeps its binning and spans and only clears the
 * arrays it accumulates into (USF's second P2G, for one). */
void mrn_blocks_reuse(mrn_blocks *b);
/* the particles changed wholesale (moved between processes): the next
 * binning starts from scratch */
void mrn_blocks_forget(mrn_blocks *b);

/* Bin the particles of the transfer by block, reorder them when tr->sort_now
 * (then clear it), set the grid's new active spans and switch to them
 * (mrn_grid_active_switch: the arrays named in `clear`, grid/active.h, are
 * cleared on them). Returns the binning, or NULL when memory ran out: then
 * every row is active, and the caller must scatter the particles in index
 * order on one thread. */
mrn_blocks *mrn_blocks_prepare(struct mrn_transfer *tr, unsigned clear);

/* The thread of a team of `threads` that scatters block blk (non-empty):
 * the owner of the block's first particle among nchunks =
 * mrn_particle_chunks(b->np) chunks (core/parallel.h), so that the thread
 * which then moves and updates a particle (G2P) is the one that read it. */
static inline int mrn_block_owner(const mrn_blocks *b, uint32_t blk, size_t nchunks, int threads) {
  return mrn_chunk_owner(b->order[b->start[blk]] / MRN_PARTICLE_CHUNK, nchunks, threads);
}

#endif
