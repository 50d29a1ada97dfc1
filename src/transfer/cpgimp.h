/* moraine: cpGIMP, contiguous-particle GIMP (Bardenhagen & Kober 2004;
 * Wallstedt & Guilkey 2008; doc/numerics.md, "cpGIMP").
 *
 * GIMP's weights are the grid's hat functions N_i averaged over the
 * particle's characteristic function. uGIMP (shape/shape.h) takes a box of
 * fixed half-width, the particle's initial one, so that particles drifting
 * apart under a stretch leave gaps between their boxes. cpGIMP keeps the box
 * aligned with the axes but sizes it from the particle's domain A = F U0
 * (particles/domain.h): its half-width along axis d is the diagonal entry
 *   l_d = A_dd = (F U0)_dd = F_dd l0_d      (U0 = diag(l0): r I until split)
 * so that boxes tiling a body keep tiling it under stretches along the axes.
 * With r = x_p - x_i along d in cells, N the hat function and Phi its
 * antiderivative, the 1D weight and its derivative are
 *   S(r)  = (1 / 2l) int_{r-l}^{r+l} N(s) ds = (Phi(r + l) - Phi(r - l)) / 2l
 *   S'(r) = (N(r + l) - N(r - l)) / 2l
 * and the particle's weights the tensor product over the axes, gradients
 * likewise. For l <= 1/2 they are uGIMP's closed form, evaluated by it
 * (mrn_shape_gimp_1d): with F = I cpGIMP gives uGIMP's bits. A box reaches
 * 2 + ceil(2 l) nodes per axis.
 *
 * The box follows stretches along the axes only. Under shear or rotation
 * the domain is no longer a box aligned with the axes, F_dd no longer its
 * extent (a quarter turn gives F_dd = 0), and the boxes overlap or leave
 * gaps; CPDI (transfer/cpdi.h) follows those. A box with l_d <= 0, not
 * finite, or wider than a reference stencil holds (MRN_REF_STENCIL_MAX
 * nodes) is refused when the step freezes the domains.
 *
 * Like CPDI, cpGIMP runs through the reference stencil with the domains the
 * step froze (the kernels of transfer/cpdi.h), with the `extended` face
 * treatment only; periodic axes wrap; a node beyond the grid's ghost layers
 * is taken back onto the last of them. */
#ifndef MRN_TRANSFER_CPGIMP_H
#define MRN_TRANSFER_CPGIMP_H

#include <stddef.h>

#include "transfer/reference.h"

/* nodes per axis that a box of half-width l cells (0 < l, finite) reaches */
int mrn_cpgimp_nodes(double l);

/* the 1D weights w and derivatives dw (per unit of xi) of a box of
 * half-width l cells centred at grid coordinate xi, for the
 * mrn_cpgimp_nodes(l) nodes from the node returned */
int mrn_cpgimp_1d(double xi, double l, double *w, double *dw);

/* the half-widths in cells of domain A's box (9 values, particles/domain.h)
 * into l; returns the nodes of its stencil, or 0 when a half-width is not
 * positive and finite or the stencil holds more than MRN_REF_STENCIL_MAX */
int mrn_cpgimp_box(const double A[9], int dim, double inv_cell, double l[3]);

/* particle p's cpGIMP stencil, nodes with x fastest; NaN weights on one node
 * for a box mrn_cpgimp_box refuses */
void mrn_cpgimp_stencil(const mrn_transfer *t, size_t p, mrn_ref_stencil *s);

/* the domains A = F U0 of every particle into A (9 per particle), as the
 * step freezes them for all its transfers (mrn_transfer.domain); returns
 * -1 and the widest half-width in cells in *extent, or the index of the
 * first particle whose box mrn_cpgimp_box refuses */
long mrn_cpgimp_domains(const mrn_particles *ps, int dim, double inv_cell, double *A, double *extent);

#endif
