/* moraine: error reporting for the C engine.
 *
 * Engine functions that can fail return a non-zero status and leave a
 * human-readable message here; the caller (the Lua layer, main.c or a C
 * program using the engine directly) reads it with mrn_error_message().
 * The message is per thread so OpenMP workers cannot clobber each other. */
#ifndef MRN_CORE_ERROR_H
#define MRN_CORE_ERROR_H

#include <stddef.h>

enum {
  MRN_OK = 0,
  MRN_ERR = 1,       /* generic failure, message set */
  MRN_ERR_IO = 2,    /* a file could not be written or read */
  MRN_ERR_STATE = 3, /* the simulation state became invalid (NaN, particle left grid) */
  MRN_ERR_HOOK = 4,  /* a user callback asked to stop with an error */
  MRN_ERR_INTERRUPTED = 5 /* SIGINT or SIGTERM arrived; the run stopped after a whole step */
};

/* printf-style; always returns MRN_ERR so callers can `return mrn_error(...)` */
int mrn_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* same as mrn_error but returns the given code */
int mrn_error_code(int code, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
const char *mrn_error_message(void);
void mrn_error_clear(void);

/* A double as messages print it: like %g (or %.<digits>g), except that NaN is
 * always spelt "NaN" (glibc prints "nan" or "-nan" by the sign bit); the
 * infinities are "inf" and "-inf". For values that may not be finite:
 *   mrn_error("dt = %s", mrn_num(dt).s)
 * The text lives until the end of the full expression that made it. */
typedef struct mrn_num_text {
  char s[32];
} mrn_num_text;
mrn_num_text mrn_num(double v);
mrn_num_text mrn_num_digits(double v, int digits);

#endif
