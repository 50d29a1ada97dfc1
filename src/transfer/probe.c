/* moraine: grid probes (see probe.h). */
#include "transfer/probe.h"

#include "transfer/stencils.h"

#define PROBE_BODY(SUFFIX)                                                             \
  {                                                                                    \
    stencil_##SUFFIX s;                                                                \
    stencil_build_##SUFFIX(tr->grid, &tr->kernel, x, vol0, &s);                        \
    for (int k = 0; k < ncomp; k++) out[k] = 0.0;                                      \
    for (int c = 0; c < s.count; c++)                                                  \
      for (int k = 0; k < ncomp; k++) out[k] += s.N[c] * nodal[ncomp * s.node[c] + k]; \
  }

int mrn_probe_grid(const mrn_transfer *tr, const double *nodal, int ncomp, const double x[3], double *out) {
  if (!mrn_grid_contains(tr->grid, x)) return -1;
  /* uGIMP: half a cell wide (lp = 1/4 cell), as 4 particles per cell in 2D, 8 in 3D */
  const double half = 0.5 * tr->grid->cell;
  const double vol0 = tr->dim == 3 ? half * half * half : half * half;
  if (tr->dim == 3) PROBE_BODY(3d) else PROBE_BODY(2d)
  return 0;
}

#define GRADIENT_BODY(SUFFIX, DIMS)                                                       \
  {                                                                                      \
    stencil_##SUFFIX s;                                                                  \
    stencil_build_##SUFFIX(g, k, x, vol0, &s);                                           \
    for (int c = 0; c < s.count; c++)                                                    \
      for (int a = 0; a < DIMS; a++)                                                     \
        for (int b = 0; b < DIMS; b++) L[3 * a + b] += nodal[3 * s.node[c] + a] * s.dN[c][b]; \
  }

int mrn_probe_grid_gradient(const mrn_grid *g, const mrn_kernel_options *k, const double *nodal, const double x[3],
                            double vol0, double L[9]) {
  for (int c = 0; c < 9; c++) L[c] = 0.0;
  if (!mrn_grid_contains(g, x)) return -1;
  if (g->dim == 3) GRADIENT_BODY(3d, 3) else GRADIENT_BODY(2d, 2)
  return 0;
}
