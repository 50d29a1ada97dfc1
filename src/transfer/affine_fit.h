/* moraine: APIC's affine matrix for the multilinear kernel.
 *
 * APIC's C = B D^-1 (000, Eqs. 25-27) is the affine velocity field that fits
 * the updated grid velocities V~ around the particle best in the least
 * squares sense, with the kernel values N_i as weights. For the quadratic and
 * cubic B-splines D is the constant h^2/4 I resp. h^2/3 I (Jiang et al.
 * 2015). For the multilinear kernel D = diag(t_d (1 - t_d) h^2), t_d the
 * particle's place in its cell, and B D^-1 = sum_i V~_i (x) grad N_i: the
 * inertia of the particle's affine mode vanishes as the particle nears a
 * grid line (0/0 on it), and the fit rests on a node the material has only
 * just reached, whose tiny mass turns a finite force into an unbounded V~.
 * The affine mode of a particle that has just entered a cell then oscillates
 * with a frequency that grows without bound, which no time step resolves
 * (doc/numerics.md, "APIC with linear shape functions").
 *
 * Here, for that kernel, C is the fit over the 3^d nodes of the quadratic
 * B-spline around the particle, each weighted by its quadratic B-spline
 * value times its mass (nodes at or below the mass floor left out), with a
 * free mean:
 *   C = sum W (V~_i - V_w) (x) (b_i - b_w)  [sum W (b_i - b_w) (x) (b_i - b_w)]^-1,
 *   W_i = N^q_i m_i,  b_i = x_i - x_p,  V_w, b_w the W-weighted means.
 * It reproduces any affine V~ exactly (a least-squares fit with a free mean),
 * a node's pull on C is in proportion to its mass, and where the nodes
 * weigh alike (inside the material) it is the quadratic B-spline's
 * B D^-1 of the same V~. An axis along which the weighted nodes do not
 * spread (a lone particle on a grid line) gets no gradient. */
#ifndef MRN_TRANSFER_AFFINE_FIT_H
#define MRN_TRANSFER_AFFINE_FIT_H

#include "grid/grid.h"
#include "shape/shape.h"

/* C (dim x dim, row-major d v_a / d x_b) of the particle at x from the
 * grid's mass and vel_new */
void mrn_affine_fit(const mrn_grid *g, const mrn_kernel_options *k, int dim, double mass_floor, const double *x,
                    double *C);

#endif
