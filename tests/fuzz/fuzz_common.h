/* moraine fuzzing: helpers shared by the harnesses (header-only, each harness
 * is one translation unit). */
#ifndef MRN_FUZZ_COMMON_H
#define MRN_FUZZ_COMMON_H

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the input, consumed from the front; reads past the end give zeros */
typedef struct fuzz_bytes {
  const uint8_t *p;
  size_t n;
} fuzz_bytes;

static inline unsigned fuzz_u8(fuzz_bytes *in) {
  if (!in->n) return 0;
  in->n--;
  return *in->p++;
}
static inline unsigned fuzz_u16(fuzz_bytes *in) { return fuzz_u8(in) << 8 | fuzz_u8(in); }
static inline size_t fuzz_left(const fuzz_bytes *in) { return in->n; }

/* a harness bug or an engine misbehaviour that is not a crash: abort so the
 * fuzzer keeps the input */
static inline void fuzz_die(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "fuzz: ");
  vfprintf(stderr, fmt, ap);
  fprintf(stderr, "\n");
  va_end(ap);
  abort();
}

/* a private directory under $TMPDIR (default /tmp) */
static inline void fuzz_make_workdir(char *buf, size_t len, const char *tag) {
  const char *tmp = getenv("TMPDIR");
  snprintf(buf, len, "%s/moraine-fuzz-%s-XXXXXX", tmp && tmp[0] ? tmp : "/tmp", tag);
  if (!mkdtemp(buf)) fuzz_die("cannot create %s", buf);
}

static inline void fuzz_write_file(const char *path, const uint8_t *data, size_t size) {
  FILE *f = fopen(path, "wb");
  if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0) fuzz_die("cannot write %s", path);
}

static inline void fuzz_copy_file(const char *from, const char *to) {
  FILE *f = fopen(from, "rb");
  if (!f) fuzz_die("cannot read %s", from);
  static uint8_t buf[1 << 20];
  size_t n = fread(buf, 1, sizeof buf, f);
  fclose(f);
  fuzz_write_file(to, buf, n);
}

#endif
