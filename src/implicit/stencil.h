/* moraine: the grid stencil of a material point for the implicit integrator:
 * the same kernels (shape function, treatment of the faces, uGIMP size) as
 * the explicit transfers (transfer/stencil.h), in a dimension-free form. */
#ifndef MRN_IMPLICIT_STENCIL_H
#define MRN_IMPLICIT_STENCIL_H

#include <stddef.h>

#include "grid/grid.h"
#include "shape/shape.h"

#define MRN_IMPLICIT_STENCIL_MAX 64

typedef struct mrn_implicit_stencil {
  int count;
  size_t node[MRN_IMPLICIT_STENCIL_MAX];
  double N[MRN_IMPLICIT_STENCIL_MAX];
  double dN[MRN_IMPLICIT_STENCIL_MAX][3]; /* d N / d x (1/m), z = 0 in 2D */
} mrn_implicit_stencil;

void mrn_implicit_stencil_2d(const mrn_grid *g, const mrn_kernel_options *opt, const double x[3], double vol0,
                             mrn_implicit_stencil *s);
void mrn_implicit_stencil_3d(const mrn_grid *g, const mrn_kernel_options *opt, const double x[3], double vol0,
                             mrn_implicit_stencil *s);

#endif
