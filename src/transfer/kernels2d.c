/* moraine: transfer kernels specialised for 2D plane strain */
#define DIM 2
#define KNAME(name) name##_2d
#include "transfer/kernels_impl.h"
