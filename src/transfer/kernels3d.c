/* moraine: transfer kernels specialised for 3D */
#define DIM 3
#define KNAME(name) name##_3d
#include "transfer/kernels_impl.h"
