/* moraine: the stencil code of transfer/stencil.h compiled for 2D (names
 * ending in _2d) and for 3D (_3d) in one translation unit, for code outside
 * the transfer kernels that needs both (grid probes, kernel tests). */
#ifndef MRN_TRANSFER_STENCILS_H
#define MRN_TRANSFER_STENCILS_H

#define DIM 2
#define KNAME(name) name##_2d
#include "transfer/stencil.h"
#undef DIM
#undef KNAME
#define DIM 3
#define KNAME(name) name##_3d
#include "transfer/stencil.h"
#undef DIM
#undef KNAME

#endif
