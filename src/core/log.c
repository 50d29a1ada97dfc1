#include "core/log.h"

#include <stdarg.h>
#include <stdio.h>

static int quiet_mode = 0;

void mrn_log_set_quiet(int quiet) { quiet_mode = quiet; }
int mrn_log_quiet(void) { return quiet_mode; }

void mrn_info(const char *fmt, ...) {
  if (quiet_mode) return;
  va_list ap;
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
}

void mrn_warn(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("moraine: warning: ", stderr);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
}
