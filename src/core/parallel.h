/* moraine: threading policy.
 * Loops over fewer items than this run on one thread: starting a parallel
 * region costs more than it saves on small problems (and a busy-waiting
 * thread team can starve other processes on a small machine).
 *
 * Grid loops do a few flops per node, so they go parallel only above
 * MRN_OMP_MIN_NODES active nodes: below that a parallel region would save
 * tens of microseconds per step and add a synchronisation point, which on a
 * loaded machine (the other core busy with another process) can cost a whole
 * scheduler time slice.
 *
 * Every parallel loop in the step gives the same result for any number of
 * threads: particles and nodes are updated independently, P2G scatters in a
 * fixed order (transfer/blocks.h) and sums over nodes or particles are
 * formed in fixed pieces added up in a fixed order. */
#ifndef MRN_CORE_PARALLEL_H
#define MRN_CORE_PARALLEL_H

#include <stddef.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define MRN_OMP_MIN_ITEMS 4096
#define MRN_OMP_MIN_NODES 65536

/* Particle ownership. The transfer kernels share the particles out among
 * the threads of a team in one way: in chunks of MRN_PARTICLE_CHUNK
 * consecutive indices, thread t of T takes chunks [N t / T, N (t + 1) / T)
 * of the N chunks (mrn_team_chunks; the step's other particle loops, OpenMP
 * static ones, split the indices into the same shares to within a chunk).
 * P2G, which goes block by block, gives each block to the thread that owns
 * the block's first particle (mrn_chunk_owner). So from P2G to G2P and the
 * material update a particle's cache lines stay on one core: a block
 * handed out first come, first served would often be read in P2G by one core
 * and written in G2P by another, which must first take each line back from
 * the first core's cache. Which thread does what never changes a result. */
enum { MRN_PARTICLE_CHUNK = 256 };

/* chunks of MRN_PARTICLE_CHUNK needed for n particles */
static inline size_t mrn_particle_chunks(size_t n) { return (n + MRN_PARTICLE_CHUNK - 1) / MRN_PARTICLE_CHUNK; }

/* this thread's number and its team's size (0 and 1 outside a parallel region) */
static inline void mrn_team(int *t, int *threads) {
#ifdef _OPENMP
  *t = omp_get_thread_num();
  *threads = omp_get_num_threads();
#else
  *t = 0;
  *threads = 1;
#endif
}

/* the chunks [*c0, *c1) of nchunks that the calling thread owns */
static inline void mrn_team_chunks(size_t nchunks, size_t *c0, size_t *c1) {
  int t, threads;
  mrn_team(&t, &threads);
  *c0 = nchunks * (size_t)t / (size_t)threads;
  *c1 = nchunks * (size_t)(t + 1) / (size_t)threads;
}

/* the thread of a team of `threads` that owns chunk c of nchunks: the t
 * with N t / T <= c < N (t + 1) / T, i.e. ceil((c + 1) T / N) - 1 */
static inline int mrn_chunk_owner(size_t c, size_t nchunks, int threads) {
  return (int)(((c + 1) * (size_t)threads - 1) / nchunks);
}

#endif
