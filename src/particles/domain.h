/* moraine: a particle's domain, tracked from its deformation gradient.
 *
 * In the reference configuration a particle's domain is spanned by the
 * columns of U0 about its centre: the half-axes of an ellipsoid for particle
 * splitting (solver/split.h), the half-edge vectors of a parallelogram
 * (parallelepiped in 3D) for CPDI (transfer/cpdi.h). A particle never split
 * has U0 = r I with r = vol0^(1/dim) / 2, half its seeding spacing; a split
 * halves U0 along the split axis and keeps it in the registered field
 * MRN_DOMAIN_FIELD. Now the domain is the image under F: A = F U0. */
#ifndef MRN_PARTICLES_DOMAIN_H
#define MRN_PARTICLES_DOMAIN_H

#include <math.h>
#include <stddef.h>

#include "particles/particles.h"

/* the registered field holding U0 (m, 3 x 3 row-major; all zero: never
 * split, r I) */
#define MRN_DOMAIN_FIELD "split_domain"

/* where U0 sits in a particle's record of ps->user (9 components), or -1 */
int mrn_particle_domain_offset(const mrn_particles *ps);

/* half the seeding spacing of a particle of initial volume vol0: the
 * half-width r of its domain until it is split, and uGIMP's half-width */
static inline double mrn_particle_half_side(double vol0, int dim) {
  return 0.5 * (dim == 2 ? sqrt(vol0) : cbrt(vol0));
}

/* particle i's domain A: the one `frozen` holds (9 per particle, as a step
 * froze them), or, when frozen is NULL, F U0 formed now */
void mrn_particle_domain_now(const mrn_particles *ps, int dim, size_t i, const double *frozen, double A[9]);

/* particle i's U0 and its image A = F U0 (3 x 3 row-major; in 2D the
 * in-plane block, the rest zero); `offset` from mrn_particle_domain_offset,
 * `r` the half-width of a particle never split */
void mrn_particle_domain(const mrn_particles *ps, int dim, size_t i, int offset, double r, double U0[9], double A[9]);

#endif
