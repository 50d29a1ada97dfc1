/* moraine: what a large allocation would take, against the machine's memory.
 *
 * Arrays sized from a deck (a grid of a cell size typed a hundred times too
 * small, a billion particles) are refused with the figures before they are
 * allocated, rather than swapping or being killed by the kernel half-way. */
#ifndef MRN_CORE_MEMORY_H
#define MRN_CORE_MEMORY_H

/* bytes of physical memory of this machine; 0 when unknown */
double mrn_memory_total(void);
/* MRN_OK when `need` bytes fit in the machine's memory (or it is unknown);
 * otherwise MRN_ERR with "<what> need X GB, more than this machine's Y GB
 * of memory<hint>" */
int mrn_memory_check(const char *what, double need, const char *hint);

#endif
