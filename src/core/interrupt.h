/* moraine: stopping cleanly on SIGINT / SIGTERM.
 *
 * The first signal only sets a flag: the run finishes the step it is in,
 * writes a checkpoint and its pending outputs, and moraine exits with status
 * MRN_EXIT_INTERRUPTED. A second signal exits at once. */
#ifndef MRN_CORE_INTERRUPT_H
#define MRN_CORE_INTERRUPT_H

#define MRN_EXIT_INTERRUPTED 130

void mrn_interrupt_install(void);
/* the signal number received (0 when none) */
int mrn_interrupt_pending(void);
void mrn_interrupt_clear(void);

#endif
