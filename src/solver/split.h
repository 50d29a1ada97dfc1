/* moraine: particle splitting (000 §5.3, after FEMLIP; doc/numerics.md,
 * "Particle splitting").
 *
 * Each particle carries a domain: in the reference configuration the
 * ellipsoid of half-axes the columns of U0 (a sphere of radius r, half the
 * seeding spacing vol0^(1/dim), until the particle is first split), and now
 * its image under F, the half-axes F U0. A particle whose largest half-axis
 * sigma exceeds `split_stretch` times r_ref, the half-width of the particle
 * it descends from, is split across that axis n into two particles at
 * x +- sigma n / 2, each with half the mass, volume, elastic energy and
 * plastic work, the same velocity, affine matrix, stress, F, strain,
 * history variables and registered fields, and the half of the domain it
 * lies in (U0 halved along the axis). Mass, momentum, angular momentum
 * (the affine part too) and E_k + E_g + E_el are the parent's to round-off.
 *
 * U0 and the split count of each particle are two registered particle
 * fields (particles/particles.h), added when splitting is switched on: they
 * are checkpointed, imported and output like any other. */
#ifndef MRN_SOLVER_SPLIT_H
#define MRN_SOLVER_SPLIT_H

#include <stddef.h>

#include "particles/domain.h"

struct mrn_sim;

/* the registered fields: U0 (m, 3 x 3 row-major; all zero: never split, the
 * sphere of radius vol0^(1/dim) / 2) and the splits in the ancestry */
#define MRN_SPLIT_DOMAIN_FIELD MRN_DOMAIN_FIELD /* particles/domain.h */
#define MRN_SPLIT_LEVEL_FIELD "split_level"

/* Split particles whose domain stretched beyond `stretch` (> 1), at most
 * `max_level` times in a particle's ancestry, at the end of every explicit
 * step; stretch 0 switches splitting off. Registers the two fields when
 * missing. 0 or MRN_ERR (message set). */
int mrn_sim_set_split(struct mrn_sim *sim, double stretch, int max_level);

/* Split every particle that is due, now (the step calls it). The particles
 * split keep their index and id (the first child, at +sigma n / 2); the
 * second children are appended in the order of their parents' ids and take
 * the ids from next_id on in that order, the same on any number of
 * processes. Returns the number of particles split (over every process of
 * a distributed run, where it is collective), or -1 (message set: out of
 * memory). */
long mrn_sim_split(struct mrn_sim *sim);

/* The stretch of particle i's domain: its largest half-axis over r_ref */
double mrn_split_stretch(const struct mrn_sim *sim, size_t i);

#endif
