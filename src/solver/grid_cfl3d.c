/* moraine: grid-averaged CFL nodal averages, 3D */
#define DIM 3
#define KNAME(name) name##_3d
#include "solver/grid_cfl_impl.h"
