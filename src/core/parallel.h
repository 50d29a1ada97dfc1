/* moraine: threading policy.
 * Loops over fewer items than this run on one thread: starting a parallel
 * region costs more than it saves on small problems (and a busy-waiting
 * thread team can starve other processes on a small machine). */
#ifndef MRN_CORE_PARALLEL_H
#define MRN_CORE_PARALLEL_H

#define MRN_OMP_MIN_ITEMS 4096

#endif
