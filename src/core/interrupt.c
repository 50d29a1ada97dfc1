#include "core/interrupt.h"

#include <signal.h>
#include <string.h>
#include <unistd.h>

#include "core/log.h"

static volatile sig_atomic_t received = 0;
static void (*volatile notify)(int sig);

static void on_signal(int sig) {
  if (received) {
    static const char msg[] = "\nmoraine: second signal, exiting at once\n";
    (void)!write(2, msg, sizeof msg - 1);
    int log = mrn_log_fd(); /* the run log ends with it too */
    if (log >= 0) (void)!write(log, msg + 1, sizeof msg - 2);
    _exit(MRN_EXIT_INTERRUPTED);
  }
  received = sig;
  void (*fn)(int) = notify;
  if (fn) fn(sig);
}

void mrn_interrupt_install(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  /* past a file-size limit (ulimit -f) write() then fails with EFBIG and the
   * run stops with a message naming the file, instead of being killed */
  signal(SIGXFSZ, SIG_IGN);
}

int mrn_interrupt_pending(void) { return (int)received; }

void mrn_interrupt_clear(void) { received = 0; }

void mrn_interrupt_notify(void (*fn)(int sig)) { notify = fn; }
