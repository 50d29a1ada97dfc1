/* moraine: particle <-> grid transfer kernels, specialised for 2D and 3D.
 *
 * The same source (kernels_impl.h) is compiled twice, with DIM = 2 and 3;
 * the wrappers below pick the right one. */
#ifndef MRN_TRANSFER_KERNELS_H
#define MRN_TRANSFER_KERNELS_H

#include <stddef.h>

#include "core/parallel.h"
#include "transfer/context.h"
#include "transfer/profile.h"

/* particles per chunk of velocity gradients handed on together: the chunks
 * by which the particles are shared out among threads (core/parallel.h) */
enum { MRN_GRADIENT_CHUNK = MRN_PARTICLE_CHUNK };

/* the mean run of consecutive particle indices within a block (of the last
 * binning) from which mrn_update_force is used */
enum { MRN_FUSED_MIN_RUN = 16 };

/* Where the velocity gradients go. They are not stored per particle: the
 * kernels form them for a chunk of consecutive particles [lo, hi) (at most
 * MRN_GRADIENT_CHUNK) in a buffer, L holding 9 values per particle
 * (row-major d v_a / d x_b, zero beyond the dimension), and hand the buffer
 * to `chunk` at once, on the thread that formed it (several chunks run at
 * the same time on several threads). `chunk` returns the lowest index of
 * [lo, hi) it rejects, or -1; the kernel returns the lowest over all chunks,
 * the same for any thread count. When the phases are timed (profile.h), the
 * time spent in `chunk` is booked to `phase` instead of G2P. */
typedef struct mrn_gradient_sink {
  long (*chunk)(void *ctx, size_t lo, size_t hi, const double *L);
  void *ctx;
  mrn_phase phase;
} mrn_gradient_sink;

/* Work on particles [lo, hi) (at most MRN_GRADIENT_CHUNK) that G2P, and the
 * gradient sink if any, have just finished, while their values are still in
 * the cache (the end-of-step wrap, wall clamp and state check of the
 * explicit step). Runs on the thread that did the chunk; returns the lowest
 * index of [lo, hi) it rejects, or -1. */
typedef struct mrn_particle_pass {
  long (*chunk)(void *ctx, size_t lo, size_t hi);
  void *ctx;
} mrn_particle_pass;

/* P2G: nodal mass and momentum (000, Eqs. 6, 16), with the affine (000,
 * Eqs. 23-24) or Taylor (000, Eqs. 19-20) term of the scheme, when
 * `momentum` is set; internal force -sum V sigma . grad N (002, Fig. 1 step 3)
 * when `force` is set. The grid arrays touched are cleared first (only where
 * particles can reach: see transfer/blocks.h; every nodal array stays zero
 * outside the grid's active spans, grid/active.h). Bitwise the same result
 * for any thread count. With tr->sort_now set, the particles are reordered
 * by block first (and sort_now cleared). */
void mrn_p2g_2d(mrn_transfer *tr, int momentum, int force);
void mrn_p2g_3d(mrn_transfer *tr, int momentum, int force);

/* velocity gradient L_p = sum_i v_i (x) grad N_i (000, Eqs. 44-45) from the
 * nodal velocity array `gvel`, handed to `sink`; returns what the sink
 * rejected first (see mrn_gradient_sink) */
long mrn_gradient_2d(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink);
long mrn_gradient_3d(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink);

/* USF's material update and internal force in one pass over the particles,
 * for the kernels with a fast stencil (linear, uGIMP, plain quadratic and
 * cubic B-splines; no MLS gradient, no periodic axis) and particles that lie in long
 * runs of consecutive indices within the blocks of the last binning
 * (mrn_update_force_fused says whether the options and the order allow it): the same as mrn_gradient from gvel with
 * `sink`, then mrn_p2g with force only (keeping the binning of the last
 * P2G: the particles must not have moved since), but each particle's
 * stencil serves both. Particles go block by block as in P2G, in runs of
 * consecutive indices handed to the sink together; the result is bitwise
 * that of the two passes, for any thread count. Returns what the sink
 * rejected first, or -1 (the forces are scattered in any case). */
int mrn_update_force_fused_2d(const mrn_transfer *tr);
int mrn_update_force_fused_3d(const mrn_transfer *tr);
long mrn_update_force_2d(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink);
long mrn_update_force_3d(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink);

/* G2P: new particle velocities by the scheme (000, Eqs. 31, 33, 37, 40), the
 * affine/Taylor matrices (000, Eqs. 22, 25-27) and the position increments
 * (000, Eqs. 32, 36, 38, 41). When `dx` is NULL positions are moved at once,
 * otherwise the increments are stored there (3 per particle). */
void mrn_g2p_2d(mrn_transfer *tr, double dt, double *dx);
void mrn_g2p_3d(mrn_transfer *tr, double dt, double *dx);
/* mrn_g2p, and with a sink mrn_gradient from the updated grid velocity
 * (grid.vel_new) in the same pass over the particles (the same stencil
 * serves both): a chunk's gradients go to the sink after its particles have
 * moved, then the chunk goes to `after` (either may be NULL). Returns what
 * the sink rejected first; *after_bad is what `after` rejected first, or -1. */
long mrn_g2p_then_2d(mrn_transfer *tr, double dt, double *dx, const mrn_gradient_sink *sink,
                     const mrn_particle_pass *after, long *after_bad);
long mrn_g2p_then_3d(mrn_transfer *tr, double dt, double *dx, const mrn_gradient_sink *sink,
                     const mrn_particle_pass *after, long *after_bad);

/* G = interpolation of a nodal field to the particles (000, Eq. 11), 3 per particle */
void mrn_grid_to_particles_2d(mrn_transfer *tr, const double *gvel, double *pvel);
void mrn_grid_to_particles_3d(mrn_transfer *tr, const double *gvel, double *pvel);
/* P_m = mass-weighted projection of particle velocities to the nodes (000, Eq. 17);
 * uses the nodal masses already in the grid */
void mrn_particles_to_grid_2d(mrn_transfer *tr, const double *pvel, double *gvel);
void mrn_particles_to_grid_3d(mrn_transfer *tr, const double *pvel, double *gvel);

#define MRN_DISPATCH(name, tr, ...) ((tr)->dim == 2 ? name##_2d(tr, __VA_ARGS__) : name##_3d(tr, __VA_ARGS__))

static inline void mrn_p2g(mrn_transfer *tr, int momentum, int force) { MRN_DISPATCH(mrn_p2g, tr, momentum, force); }
static inline long mrn_gradient(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink) {
  return MRN_DISPATCH(mrn_gradient, tr, gvel, sink);
}
static inline int mrn_update_force_fused(const mrn_transfer *tr) {
  return tr->dim == 2 ? mrn_update_force_fused_2d(tr) : mrn_update_force_fused_3d(tr);
}
static inline long mrn_update_force(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink) {
  return MRN_DISPATCH(mrn_update_force, tr, gvel, sink);
}
static inline void mrn_g2p(mrn_transfer *tr, double dt, double *dx) { MRN_DISPATCH(mrn_g2p, tr, dt, dx); }
static inline long mrn_g2p_then(mrn_transfer *tr, double dt, double *dx, const mrn_gradient_sink *sink,
                                const mrn_particle_pass *after, long *after_bad) {
  return MRN_DISPATCH(mrn_g2p_then, tr, dt, dx, sink, after, after_bad);
}
static inline void mrn_grid_to_particles(mrn_transfer *tr, const double *gvel, double *pvel) {
  MRN_DISPATCH(mrn_grid_to_particles, tr, gvel, pvel);
}
static inline void mrn_particles_to_grid(mrn_transfer *tr, const double *pvel, double *gvel) {
  MRN_DISPATCH(mrn_particles_to_grid, tr, pvel, gvel);
}

/* Initialise the Taylor grad v (and APIC C, to the same value) of particles
 * given initial velocities by repeating 000 Eqs. 19-22 until grad v
 * converges (000 §3.2, last paragraph). Returns the iterations used. */
int mrn_transfer_init_affine(mrn_transfer *tr);

#endif
