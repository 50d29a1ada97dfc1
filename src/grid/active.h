/* moraine: the active part of the grid.
 *
 * Each row of nodes (the x-line of nodes at one j, k) keeps a span [lo, hi)
 * of x indices outside which every nodal array (mass, momentum, force,
 * velocities; not vel_star and work) is zero. Whoever scatters into the grid
 * says, before it does, which spans it may reach (mrn_grid_active_begin,
 * _reach or _all, then _switch): what the old spans covered beyond the new
 * ones is cleared then, in every array, so the zero outside the spans holds
 * without clearing the whole grid. The grid loops of a step visit only the
 * spans, as linear node ranges (mrn_grid_active_ranges), so an empty part of
 * the grid costs next to nothing. */
#ifndef MRN_GRID_ACTIVE_H
#define MRN_GRID_ACTIVE_H

#include <stddef.h>

struct mrn_grid;

/* nodal arrays a scatter accumulates into (cleared on the new spans) */
enum { MRN_CLEAR_MASS_MOM = 1u, MRN_CLEAR_FORCE = 2u };

typedef struct mrn_grid_active {
  size_t nrows;          /* rows j + nnode[1] k */
  int *lo, *hi;          /* span [lo, hi) of each row */
  int *new_lo, *new_hi;  /* the spans the next mrn_grid_active_switch sets */
  /* the spans as linear node ranges, non-empty rows only */
  size_t nranges;
  long *range_lo, *range_hi;
  double *range_sum;     /* one value per range, for deterministic reductions */
  long nodes;            /* nodes in the ranges */
} mrn_grid_active;

/* allocated with the grid (mrn_grid_init), every row fully active; NULL on
 * failure (message set) */
mrn_grid_active *mrn_grid_active_new(const struct mrn_grid *g);
void mrn_grid_active_free(mrn_grid_active *a);
/* bytes held, for memory reports */
size_t mrn_grid_active_bytes(const struct mrn_grid *g);

/* the next spans: none (then widened by mrn_grid_active_reach), or every
 * row whole */
void mrn_grid_active_begin(struct mrn_grid *g);
void mrn_grid_active_all(struct mrn_grid *g);
/* the next span of `row` covers x indices [x0, x1) */
static inline void mrn_grid_active_reach(mrn_grid_active *a, size_t row, int x0, int x1) {
  if (x0 < a->new_lo[row]) a->new_lo[row] = x0;
  if (x1 > a->new_hi[row]) a->new_hi[row] = x1;
}
/* Replace the spans by the next ones: what the old spans covered beyond the
 * new ones is cleared in every array, the new spans in the arrays named in
 * `clear`. Called again without a new begin, it keeps the spans and clears
 * the arrays named on them. */
void mrn_grid_active_switch(struct mrn_grid *g, unsigned clear);

/* Widen the span of `row` to cover [x0, x1) as well (an empty interval
 * changes nothing), for nodes that are zero and about to be added to (a
 * distributed run's halo sum, solver/dist.h); then refresh the ranges. A
 * switch without a new begin keeps the widened span. */
void mrn_grid_active_widen(struct mrn_grid *g, size_t row, int x0, int x1);
void mrn_grid_active_refresh(struct mrn_grid *g);

/* Node index ranges [lo[k], hi[k]) outside which every nodal array is zero;
 * `sum` has room for one double per range. */
typedef struct mrn_node_ranges {
  long count;
  const long *lo, *hi;
  double *sum;
  long nodes; /* total nodes in the ranges */
} mrn_node_ranges;

mrn_node_ranges mrn_grid_active_ranges(const struct mrn_grid *g);

#endif
