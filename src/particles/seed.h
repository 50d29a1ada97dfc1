/* moraine: seeding particles from a region on the grid's cells.
 *
 * Every cell that overlaps the region's bounding box (clipped to the grid when
 * the region is unbounded) is divided into n^dim candidate points, either at
 * the Gauss-Legendre points of order n (000 §5.1.2) or regularly spaced at
 * the centres of n^dim equal sub-cells. A candidate inside the region becomes
 * a particle whose volume is its share of the cell: h^dim / n^dim for regular
 * spacing, h^dim times the product of the Gauss-Legendre weights / 2^dim
 * otherwise (so the particles integrate the cell exactly). */
#ifndef MRN_PARTICLES_SEED_H
#define MRN_PARTICLES_SEED_H

#include "grid/grid.h"
#include "particles/region.h"

typedef enum { MRN_SEED_GAUSS = 0, MRN_SEED_REGULAR } mrn_seed_placement;

#define MRN_SEED_MAX_PER_AXIS 8
/* more candidate points than this in one seeding are refused rather than
 * tested for many minutes (their particles would need hundreds of GB) */
#define MRN_SEED_MAX_CANDIDATES 1e9

/* called for each seeded point with its volume; return 0 to go on, non-zero
 * to stop seeding (that value is returned by mrn_seed) */
typedef int (*mrn_seed_callback)(void *user, const double x[3], double volume);

/* Returns 0 on success; MRN_ERR with a message when per_axis is outside
 * 1..MRN_SEED_MAX_PER_AXIS, when a point inside the region lies outside the
 * grid ("region extends outside the grid ..."), or when a predicate fails.
 * *count receives the number of particles seeded. */
int mrn_seed(const mrn_grid *g, const mrn_region *r, int per_axis, mrn_seed_placement placement,
             mrn_seed_callback cb, void *user, long *count);

/* The candidate points mrn_seed would test: those of the grid cells the
 * region's bounding box overlaps (0 when none), an upper bound of the
 * particles it seeds. MRN_ERR for bad arguments or a bounding box far beyond
 * the grid (message set). */
int mrn_seed_candidates(const mrn_grid *g, const mrn_region *r, int per_axis, double *candidates);

/* Gauss-Legendre abscissae on [-1, 1] and weights for order n (1..8) */
void mrn_gauss_legendre(int n, double *points, double *weights);

#endif
