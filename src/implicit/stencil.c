/* moraine: implicit-integrator stencils (see stencil.h), from the 2D and 3D
 * instances of transfer/stencil.h. */
#include "implicit/stencil.h"

#include "transfer/stencils.h"

/* copy a stencil, dropping nodes where both the weight and its gradient vanish */
#define COPY_STENCIL(SUFFIX, D)                                                                  \
  {                                                                                              \
    stencil_##SUFFIX s;                                                                          \
    stencil_build_##SUFFIX(g, opt, x, vol0, &s);                                                 \
    out->count = 0;                                                                              \
    for (int k = 0; k < s.count; k++) {                                                          \
      int zero = s.N[k] == 0.0;                                                                  \
      for (int d = 0; d < D; d++) zero &= s.dN[k][d] == 0.0;                                     \
      if (zero) continue;                                                                        \
      int c = out->count++;                                                                      \
      out->node[c] = s.node[k];                                                                  \
      out->N[c] = s.N[k];                                                                        \
      for (int d = 0; d < 3; d++) out->dN[c][d] = d < D ? s.dN[k][d] : 0.0;                      \
    }                                                                                            \
  }

void mrn_implicit_stencil_2d(const mrn_grid *g, const mrn_kernel_options *opt, const double x[3], double vol0,
                             mrn_implicit_stencil *out) COPY_STENCIL(2d, 2)

void mrn_implicit_stencil_3d(const mrn_grid *g, const mrn_kernel_options *opt, const double x[3], double vol0,
                             mrn_implicit_stencil *out) COPY_STENCIL(3d, 3)
