#include "core/error.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

static _Thread_local char error_buffer[2048];

static void set_message(const char *fmt, va_list ap) {
  vsnprintf(error_buffer, sizeof error_buffer, fmt, ap);
}

int mrn_error(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  set_message(fmt, ap);
  va_end(ap);
  return MRN_ERR;
}

int mrn_error_code(int code, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  set_message(fmt, ap);
  va_end(ap);
  return code;
}

const char *mrn_error_message(void) { return error_buffer; }

void mrn_error_clear(void) { error_buffer[0] = '\0'; }

mrn_num_text mrn_num_digits(double v, int digits) {
  mrn_num_text t;
  if (isnan(v)) snprintf(t.s, sizeof t.s, "NaN");
  else snprintf(t.s, sizeof t.s, "%.*g", digits, v);
  return t;
}

mrn_num_text mrn_num(double v) { return mrn_num_digits(v, 6); }
