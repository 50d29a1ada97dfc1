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
