/* moraine: CPDI, convected particle domain interpolation (Sadeghirad,
 * Brannon & Burghardt 2011; doc/numerics.md, "CPDI").
 *
 * A particle's domain is the parallelogram (parallelepiped in 3D) spanned
 * about its centre x_p by the half-edge vectors r_k, the columns of
 * A = F U0 (particles/domain.h: U0 = r I, r half the seeding spacing, until
 * the particle is split). The grid basis N_i is the linear hat function.
 * CPDI replaces N_i inside the domain by its multilinear interpolation from
 * the domain's 2^d corners x_c = x_p + sum_k xi_ck r_k (xi_ck = +-1) and
 * averages that over the domain; in closed form
 *   S_ip      = (1 / 2^d) sum_c N_i(x_c)
 *   grad S_ip = (1 / 2^d) sum_c N_i(x_c) J^-T xi_c,     J = [r_1 .. r_d] = A.
 * The second follows from the divergence theorem on the reference square:
 * int_Omega grad M_c dx = det J J^-T int grad_xi M_c dxi = det J J^-T xi_c for
 * the multilinear corner function M_c, divided by V_p = 2^d det J. In 2D,
 * corners numbered (-1,-1), (1,-1), (1,1), (-1,1) as the paper does, this is
 * its grad S_ip = [(N_1 - N_3) (r1y - r2y, r2x - r1x)
 *                + (N_2 - N_4) (r1y + r2y, -r1x - r2x)] / V_p.
 * The weights keep the partition of unity and linear reproduction for any
 * domain, and their gradients sum to zero.
 *
 * The support grows with the domain, so CPDI has no fast stencil and no
 * block colouring: its kernels below run through the reference stencil
 * (transfer/reference.h), P2G in index order on one thread, the gathers in
 * parallel chunks; the fast kernels hand every call over to them
 * (kernels_impl.h). Only the `extended` face treatment, without the MLS
 * gradient (the step refuses the rest); periodic axes wrap. A corner beyond
 * the grid's ghost layers is taken back onto the last ghost node. CPDI2
 * (transfer/cpdi2.h) runs through the same kernels, its stencil formed
 * from the tracked quadrilateral. */
#ifndef MRN_TRANSFER_CPDI_H
#define MRN_TRANSFER_CPDI_H

#include <stddef.h>

#include "transfer/kernels.h"
#include "transfer/reference.h"

/* particle p's CPDI (or CPDI2, transfer/cpdi2.h) stencil: 2^d corners x
 * 2^d nodes, a node reached from several corners listed once per corner */
void mrn_cpdi_stencil(const mrn_transfer *t, size_t p, mrn_ref_stencil *s);

/* the velocity gvel interpolated at the point xc by the hat functions, as
 * at a corner (beyond the ghost layers taken back onto the last of them) */
void mrn_cpdi_point_velocity(const mrn_transfer *t, const double xc[3], const double *gvel, double v[3]);

/* the largest |grad S_ip| (1/m) over the nodes of particle p's stencil,
 * the corners' parts of a node summed. The hat function's gradient is at
 * most about 1/h; a thin domain spanning several cells takes corner values
 * that no linear field gives, and its averaged gradient grows with its
 * aspect ratio (J^-T, or CPDI2's edge normals over the area): the stable
 * step falls with it (solver/timestep.h) */
double mrn_cpdi_gradient_bound(const mrn_transfer *t, size_t p);

/* the domains A = F U0 (9 per particle) of every particle into A, as the
 * step freezes them for all its transfers (mrn_transfer.domain); returns
 * the largest reach of a domain from its centre along an axis, in cells */
double mrn_cpdi_domains(const mrn_particles *ps, int dim, double inv_cell, double *A);

/* the kernels of kernels.h for CPDI, with their contracts; they build each
 * particle's stencil with mrn_ref_stencil_build, so they serve every shape
 * with a tracked domain (mrn_shape_tracks_domain: cpGIMP too) */
void mrn_cpdi_p2g(mrn_transfer *tr, int momentum, int force);
long mrn_cpdi_g2p_then(mrn_transfer *tr, double dt, double *dx, const mrn_gradient_sink *sink,
                       const mrn_particle_pass *after, long *after_bad);
long mrn_cpdi_gradient(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink);
void mrn_cpdi_grid_to_particles(mrn_transfer *tr, const double *gvel, double *pvel);
void mrn_cpdi_particles_to_grid(mrn_transfer *tr, const double *pvel, double *gvel);

#endif
