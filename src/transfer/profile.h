/* moraine: optional timers for the phases of a step.
 *
 * The benchmark harness (bench/) points mrn_profile_seconds at an array of
 * MRN_PHASE_COUNT accumulators; the step and the transfer kernels then add
 * the wall time of each phase to it. When the pointer is NULL (the default)
 * a hook is one load and one branch per phase and step, nothing per particle.
 * The hooks are called outside parallel regions only, except for the time
 * spent in a gradient sink (transfer/kernels.h), summed per thread. */
#ifndef MRN_TRANSFER_PROFILE_H
#define MRN_TRANSFER_PROFILE_H

#include <time.h>

typedef enum {
  MRN_PHASE_P2G = 0, /* particle-to-grid transfers, binning by block included */
  MRN_PHASE_GRID,    /* nodal velocities, forces, boundary conditions */
  MRN_PHASE_G2P,     /* grid-to-particle transfers and velocity gradients */
  MRN_PHASE_STRESS,  /* kinematics and constitutive update of the particles */
  MRN_PHASE_SORT,    /* reordering the particles by cell */
  MRN_PHASE_COUNT
} mrn_phase;

extern double *mrn_profile_seconds;

static inline double mrn_profile_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* threads of a parallel loop run with if(parallel) */
int mrn_profile_threads(int parallel);

static inline double mrn_phase_begin(void) { return mrn_profile_seconds ? mrn_profile_now() : 0.0; }

static inline void mrn_phase_end(mrn_phase phase, double start) {
  if (mrn_profile_seconds) mrn_profile_seconds[phase] += mrn_profile_now() - start;
}

/* End of a phase whose parallel loop ran another phase inside it: `inner`
 * gets the time its threads spent there (inner_thread_seconds, summed over
 * the threads) divided by the threads that ran the loop, `outer` the rest of
 * the wall time since `start`. */
static inline void mrn_phase_end_split(mrn_phase outer, mrn_phase inner, double start, double inner_thread_seconds,
                                       int parallel) {
  if (!mrn_profile_seconds) return;
  const double wall = mrn_profile_now() - start, in = inner_thread_seconds / mrn_profile_threads(parallel);
  mrn_profile_seconds[inner] += in;
  mrn_profile_seconds[outer] += wall - in;
}

#endif
