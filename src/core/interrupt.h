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
/* fn(sig) is called inside the signal handler at the first signal, after
 * the flag is set, so that code which does not read the flag can be stopped
 * (the Lua layer arms a hook there); fn must be async-signal-safe. NULL: none. */
void mrn_interrupt_notify(void (*fn)(int sig));

#endif
