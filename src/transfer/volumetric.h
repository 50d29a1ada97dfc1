/* moraine: the volumetric part of the particles' velocity gradients averaged
 * over the nodes: the F-bar of scheme{volumetric = "fbar"}, against the
 * volumetric locking of nearly isochoric (plastic) flow.
 *
 * With div_p = tr L_p and V_p the particle's volume, the divergence is
 * projected to the nodes volume-weighted and interpolated back,
 *   div_i = sum_p N_ip V_p div_p / sum_p N_ip V_p,
 *   div~_p = sum_i N_ip div_i / sum_i N_ip chi_i
 * (chi_i = 1 at the nodes the projection reached, 0 elsewhere), and only
 * the volumetric part of L_p is replaced:
 *   L~_p = L_p + (div~_p - div_p) / d I_d
 * (d the dimension, I_d the identity of the plane in 2D): the deviatoric
 * part stays the particle's own, a uniform divergence is kept exactly.
 * doc/numerics.md, "Volumetric averaging (F-bar)". */
#ifndef MRN_TRANSFER_VOLUMETRIC_H
#define MRN_TRANSFER_VOLUMETRIC_H

#include "transfer/context.h"

/* L~ in place of L (9 values per particle, row-major, as the gradient sink
 * hands them) for every particle of tr, at their current positions; uses
 * grid.work and `particle_scratch` (3 values per particle). The nodal sums
 * go through tr->sum_nodal. */
void mrn_volumetric_average(mrn_transfer *tr, double *L, double *particle_scratch);

#endif
