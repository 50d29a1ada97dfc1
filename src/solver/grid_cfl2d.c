/* moraine: grid-averaged CFL nodal averages, 2D */
#define DIM 2
#define KNAME(name) name##_2d
#include "solver/grid_cfl_impl.h"
