/* moraine: reordering the particles.
 *
 * Every per-particle array moves together: each field of
 * MRN_PARTICLE_FIELDS, the material index, the id and the material history
 * variables. Ids are kept, so a particle can still be followed by its id. */
#ifndef MRN_PARTICLES_SORT_H
#define MRN_PARTICLES_SORT_H

#include <stdint.h>

#include "particles/particles.h"

/* New index i takes the particle that had index order[i]; `order` is a
 * permutation of 0 .. n-1. Needs n doubles of scratch, allocated here.
 * Returns 0, or an error code (message set, nothing moved) when memory ran out. */
int mrn_particles_permute(mrn_particles *p, const uint32_t *order);

#endif
