/* moraine: the nodes a particle talks to, with weights and gradients.
 *
 * Included by the dimension-specialised kernel files with DIM defined to 2
 * or 3, so every loop bound below is a compile-time constant. */
#ifndef DIM
#error "stencil.h needs DIM"
#endif

#include "grid/grid.h"
#include "shape/shape.h"

#define STENCIL_MAX (MRN_SHAPE_MAX_SUPPORT * MRN_SHAPE_MAX_SUPPORT * (DIM == 3 ? MRN_SHAPE_MAX_SUPPORT : 1))

typedef struct KNAME(stencil) {
  int count;
  size_t node[STENCIL_MAX];
  double N[STENCIL_MAX];
  double dN[STENCIL_MAX][DIM]; /* d N / d x (1/m) */
  double offset[STENCIL_MAX][DIM]; /* x_i - x_p, the branch vector (000, Eq. 21) */
} KNAME(stencil);

/* fill the stencil of a particle at x (which must lie inside the domain) */
static inline void KNAME(stencil_build)(const mrn_grid *g, mrn_shape_kind shape, const double *x,
                                        KNAME(stencil) *s) {
  double w[DIM][MRN_SHAPE_MAX_SUPPORT], dw[DIM][MRN_SHAPE_MAX_SUPPORT];
  int base[DIM];
  const int sup = mrn_shape_support(shape);
  for (int d = 0; d < DIM; d++) {
    double xi = (x[d] - g->origin[d]) * g->inv_cell;
    base[d] = mrn_shape_weights_1d(shape, xi, w[d], dw[d]);
  }
  int c = 0;
#if DIM == 3
  for (int k = 0; k < sup; k++)
#endif
    for (int j = 0; j < sup; j++)
      for (int i = 0; i < sup; i++) {
#if DIM == 3
        const int idx[3] = {i, j, k};
#else
        const int idx[2] = {i, j};
#endif
        double N = 1.0;
        for (int d = 0; d < DIM; d++) N *= w[d][idx[d]];
        for (int d = 0; d < DIM; d++) {
          double g_d = dw[d][idx[d]] * g->inv_cell;
          for (int e = 0; e < DIM; e++)
            if (e != d) g_d *= w[e][idx[e]];
          s->dN[c][d] = g_d;
          s->offset[c][d] = g->origin[d] + (base[d] + idx[d]) * g->cell - x[d];
        }
        s->N[c] = N;
#if DIM == 3
        s->node[c] = mrn_grid_index(g, base[0] + i, base[1] + j, base[2] + k);
#else
        s->node[c] = mrn_grid_index(g, base[0] + i, base[1] + j, 0);
#endif
        c++;
      }
  s->count = c;
}
