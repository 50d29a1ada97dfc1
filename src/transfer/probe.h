/* moraine: values of nodal grid fields at any point of the domain.
 *
 * A probe interpolates a nodal array with the transfer's own shape
 * functions, face treatment and periodic axes: f(x) = sum_i N_i(x) f_i, the
 * interpolation G2P uses for the velocity (000, Eq. 11). The nodal arrays are
 * those of the last completed step (see grid/grid.h for what each holds). */
#ifndef MRN_TRANSFER_PROBE_H
#define MRN_TRANSFER_PROBE_H

#include "transfer/context.h"

/* `ncomp` values (1 for a scalar array of one value per node, 3 for a vector
 * array of 3 per node) of `nodal` at point x into out. Returns 0, or -1 when
 * x lies outside the grid's domain (out untouched). For uGIMP the kernel of
 * a particle half a cell wide is used (the probe has no size of its own). */
int mrn_probe_grid(const mrn_transfer *tr, const double *nodal, int ncomp, const double x[3], double *out);

/* The gradient of a nodal vector array (3 values per node) of grid g at
 * point x, L[3 a + b] = sum_i nodal_i,a dN_i/dx_b (000, Eqs. 44-45: the
 * velocity gradient of the stress update), row-major 3 x 3, zero beyond the
 * dimension, with the kernel k (mrn_sim_kernel_options). vol0 is the initial
 * volume of the particle at x (the uGIMP kernel's width). Returns 0, or -1
 * when x lies outside the grid (L zeroed). Only reads g. */
int mrn_probe_grid_gradient(const mrn_grid *g, const mrn_kernel_options *k, const double *nodal, const double x[3],
                            double vol0, double L[9]);

#endif
