/* moraine: pieces shared by the rate-form elastic-plastic models
 * (mohr_coulomb, drucker_prager, von_mises): elastic constants and the
 * energy split of one update. */
#ifndef MRN_MATERIAL_ELASTOPLASTIC_H
#define MRN_MATERIAL_ELASTOPLASTIC_H

#include <math.h>

#include "core/tensor.h"
#include "material/material.h"

static inline void mrn_lame(double E, double nu, double *lambda, double *shear, double *bulk) {
  *lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  *shear = E / (2 * (1 + nu));
  *bulk = E / (3 * (1 - 2 * nu));
}

/* de = C^-1 : ds (000, Eq. 63) */
static inline void mrn_hooke_compliance(double E, double nu, const double ds[6], double de[6]) {
  double tr = ds[0] + ds[1] + ds[2];
  for (int k = 0; k < 3; k++) de[k] = ((1 + nu) * ds[k] - nu * tr) / E;
  for (int k = 3; k < 6; k++) de[k] = (1 + nu) * ds[k] / E;
}

/* Energies of one update from `old` (the rotated start-of-step stress) to
 * `now` under the strain increment deps (000, Eqs. 63-65), with the stress
 * averaged over the step (000 §5.1.4):
 *   deps_el = C^-1 : (now - old),   de_elastic = mid : deps_el,
 *   dw_plastic = -mid : (deps - deps_el)  (<= 0 while dissipating).
 * Because C^-1 is linear, mid : deps_el is exactly the change of the
 * complementary energy sigma : C^-1 : sigma / 2, so the elastic energy sums
 * without drift, and de_elastic - dw_plastic = mid : deps is the stress
 * work. The price: for an increment much larger than the elastic range, the
 * start-of-step stress can do negative work on a dilatant plastic strain and
 * dw_plastic come out positive, although the return itself dissipates
 * (sigma_new : deps_p >= 0). An elastic step reports no plastic work at all
 * rather than the round-off of deps - C^-1 : C : deps. The plastic strain
 * increment is returned in deps_p when not NULL. */
static inline void mrn_energy_split(double E, double nu, const double old[6], const double now[6],
                                    const double deps[6], int plastic, mrn_material_point *pt, double deps_p[6]) {
  double ds[6], de_el[6], mid[6], dp[6];
  for (int k = 0; k < 6; k++) {
    ds[k] = now[k] - old[k];
    mid[k] = 0.5 * (old[k] + now[k]);
  }
  if (plastic) {
    mrn_hooke_compliance(E, nu, ds, de_el);
    for (int k = 0; k < 6; k++) dp[k] = deps[k] - de_el[k];
  } else {
    for (int k = 0; k < 6; k++) {
      de_el[k] = deps[k];
      dp[k] = 0.0;
    }
  }
  pt->de_elastic = sym_ddot(mid, de_el);
  pt->dw_plastic = plastic ? -sym_ddot(mid, dp) : 0.0;
  if (deps_p)
    for (int k = 0; k < 6; k++) deps_p[k] = dp[k];
}

/* equivalent plastic strain increment sqrt(2/3 dev(de):dev(de)) */
static inline double mrn_equivalent_strain(const double de[6]) {
  double d[6];
  sym_dev(de, d);
  return sqrt(2.0 / 3.0 * sym_ddot(d, d));
}

#endif
