/* moraine: the XPIC(m) smoothed grid velocity (000, Eqs. 39-41; Hammerquist
 * and Nairn 2017).
 *
 * With A = G P_m (particle -> grid -> particle) and S = P_m G (grid ->
 * particle -> grid), (I - A)^m V^P = V^P - G V* where
 *   V* = sum_{k=1..m} C(m, k) (-1)^(k+1) S^(k-1) V^G,   V^G = P_m V^P.
 * XPIC(m) then sets V^P_new = G V* + G a dt (000, Eq. 40) and moves the
 * particles with 000 Eq. 41; m = 1 gives V* = V^G, the PIC velocity. */
#ifndef MRN_TRANSFER_XPIC_H
#define MRN_TRANSFER_XPIC_H

#include "transfer/context.h"

/* fill grid.vel_star from grid.vel (already P_m V^P with boundary conditions);
 * `particle_scratch` holds 3 values per particle. */
void mrn_xpic_smooth(mrn_transfer *tr, double *particle_scratch);

#endif
