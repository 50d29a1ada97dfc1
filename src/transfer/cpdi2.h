/* moraine: CPDI2 in 2D, second-order convected particle domain
 * interpolation (Sadeghirad, Brannon & Guilkey 2013, IJNME; doc/numerics.md,
 * "CPDI2").
 *
 * A particle's domain is a general quadrilateral whose four corners are
 * tracked as points of their own, numbered counter-clockwise
 * (xi_c, eta_c) = (-1,-1), (1,-1), (1,1), (-1,1) as the paper does. Its map
 * from the square [-1,1]^2 is bilinear, x = sum_c M_c(xi, eta) x_c with
 * M_c = (1 + xi_c xi)(1 + eta_c eta) / 4, and with
 *   a = sum_c xi_c x_c / 4,  b = sum_c eta_c x_c / 4,  e = sum_c xi_c eta_c x_c / 4
 * its Jacobian is dx/dxi = a + eta e, dx/deta = b + xi e, so
 *   det J = J0 + J1 xi + J2 eta,  J0 = a x b, J1 = a x e, J2 = e x b
 * (x the 2D cross product). As CPDI1 (transfer/cpdi.h), CPDI2 replaces the
 * linear hat function N_i inside the domain by its interpolation from the
 * corners, sum_c N_i(x_c) M_c, and averages it over the domain:
 *   S_ip      = (1/V_p) sum_c N_i(x_c) w_c,   w_c = int M_c dx = J0 + (J1 xi_c + J2 eta_c) / 3
 *   grad S_ip = (1/V_p) sum_c N_i(x_c) g_c,   g_c = int grad M_c dx
 *             = (y_{c+1} - y_{c-1}, x_{c-1} - x_{c+1}) / 2
 *   V_p = sum_c w_c = 4 J0, the quadrilateral's area.
 * w_c: int M_c det J over the square, where int M_c = 1 and
 * int M_c xi = xi_c / 3. g_c: by the divergence theorem, M_c is 1 at x_c,
 * 0 at the other corners and linear along the edges, so each of the two
 * edges at c gives half its outward normal times its length. For a
 * parallelogram J1 = J2 = 0 and these are CPDI1's weights and gradients.
 *
 * The corners are kept as their offsets from the particle's centre in the
 * registered particle field MRN_CPDI2_FIELD (carried through checkpoints,
 * sorting and migration): a particle whose offsets are all zero (never
 * stepped with CPDI2, e.g. just added) starts from CPDI1's parallelogram
 * x_p + A xi_c, A = F U0 (particles/domain.h). Each step the corners move
 * with the grid's updated velocity V~ interpolated by the hat functions at
 * the corners where the step began (the paper's update), and the
 * quadrilateral is then placed with its centroid on the particle's new
 * position, however the strategy moved it: so sum_i S_ip (x_i - x_p) = 0,
 * which the affine transfers' momentum balance needs. */
#ifndef MRN_TRANSFER_CPDI2_H
#define MRN_TRANSFER_CPDI2_H

#include <stddef.h>

#include "particles/particles.h"
#include "transfer/context.h"

/* the registered field of the corners' offsets from the particle's centre
 * (m; x, y of each corner, counter-clockwise from (-1,-1); all zero: unset) */
#define MRN_CPDI2_FIELD "cpdi2_corners"

/* the reference corners (xi_c, eta_c), counter-clockwise */
extern const double mrn_cpdi2_xi[4][2];

/* the quadrilateral q (4 corners, x and y): w_c and g_c (cpdi2.h) into w
 * and g; returns its area V_p = 4 J0 */
double mrn_cpdi2_integrals(const double q[4][2], double w[4], double g[4][2]);

/* particle p's corner offsets: stored, or the parallelogram A xi_c when
 * unset or when the field is missing */
void mrn_cpdi2_offsets(const mrn_particles *ps, size_t p, double off[4][2]);

/* At the start of a step: the field registered if missing and every unset
 * particle's corners set; then the corners' positions frozen into
 * corners (8 per particle) for every transfer of the step. Returns MRN_OK
 * and the largest reach of a corner from its centre along an axis, in
 * cells, into *reach; MRN_ERR (message set) when the field cannot be had. */
int mrn_cpdi2_begin(mrn_particles *ps, double inv_cell, double *corners, double *reach);

/* At the end of a step: each frozen corner moved by dt V~ (t->grid->vel_new
 * by the hat functions at the corner) and the new offsets, about the moved
 * quadrilateral's centroid, into the field */
void mrn_cpdi2_move_corners(const mrn_transfer *t, const double *corners, double dt);

#endif
