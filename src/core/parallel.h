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

#define MRN_OMP_MIN_ITEMS 4096
#define MRN_OMP_MIN_NODES 65536

#endif
