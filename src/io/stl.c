#include "io/stl.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

/* the whole file into memory; *size its length */
static char *slurp(const char *path, size_t *size) {
  FILE *f = fopen(path, "rb");
  if (!f) return mrn_error_code(MRN_ERR_IO, "'%s': cannot open: %s", path, strerror(errno)), NULL;
  char *buf = NULL;
  long len = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
  if (len >= 0 && fseek(f, 0, SEEK_SET) == 0 && (buf = malloc((size_t)len + 1)) && fread(buf, 1, (size_t)len, f) == (size_t)len) {
    buf[len] = '\0';
    *size = (size_t)len;
  } else {
    mrn_error_code(MRN_ERR_IO, "'%s': cannot read: %s", path, len < 0 || !buf ? "not a regular file, or too large" : strerror(errno));
    free(buf), buf = NULL;
  }
  fclose(f);
  return buf;
}

/* ---- binary ------------------------------------------------------------------------ */

static double float_le(const unsigned char *p) {
  const uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
  float f;
  memcpy(&f, &u, sizeof f);
  return f;
}

static int read_binary(const char *path, const unsigned char *buf, size_t size, double **tri, size_t *n) {
  if (size < 84)
    return mrn_error_code(MRN_ERR_IO, "'%s': not an STL file: %zu bytes, shorter than a binary STL's 84-byte header "
                          "and not ASCII (which starts with 'solid')", path, size);
  const uint32_t count = (uint32_t)buf[80] | (uint32_t)buf[81] << 8 | (uint32_t)buf[82] << 16 | (uint32_t)buf[83] << 24;
  const uint64_t want = 84 + 50 * (uint64_t)count;
  if (size != want)
    return mrn_error_code(MRN_ERR_IO, "'%s': truncated or corrupted binary STL: its header counts %lu triangles, "
                          "%llu bytes, the file has %zu", path, (unsigned long)count, (unsigned long long)want, size);
  if (count == 0) return mrn_error_code(MRN_ERR_IO, "'%s': the file holds no triangles", path);
  if (count > MRN_STL_MAX_TRIANGLES)
    return mrn_error_code(MRN_ERR_IO, "'%s': %lu triangles, more than %d", path, (unsigned long)count, MRN_STL_MAX_TRIANGLES);
  double *t = malloc(9 * (size_t)count * sizeof *t);
  if (!t) return mrn_error("out of memory for '%s'", path);
  for (size_t i = 0; i < count; i++)
    for (int k = 0; k < 9; k++) t[9 * i + k] = float_le(buf + 84 + 50 * i + 12 + 4 * k);
  *tri = t, *n = count;
  return MRN_OK;
}

/* ---- ASCII ------------------------------------------------------------------------- */

typedef struct scan {
  const char *p, *end, *path;
  int line;
  char tok[64]; /* the last token, cut to fit */
  double *tri;
  size_t n, cap;
} scan;

/* the next token into s->tok; 0 at the end of the file */
static int next(scan *s) {
  while (s->p < s->end && strchr(" \t\r\n\f\v", *s->p)) s->line += *s->p++ == '\n';
  if (s->p >= s->end) return s->tok[0] = '\0', 0;
  size_t len = 0;
  while (s->p < s->end && !strchr(" \t\r\n\f\v", *s->p)) {
    if (len + 1 < sizeof s->tok) s->tok[len++] = *s->p;
    s->p++;
  }
  s->tok[len] = '\0';
  return 1;
}

static void skip_line(scan *s) {
  while (s->p < s->end && *s->p != '\n') s->p++;
}

static int unexpected(const scan *s, const char *want) {
  if (!s->tok[0])
    return mrn_error_code(MRN_ERR_IO, "'%s': line %d: the file ends where %s was expected (truncated?)", s->path,
                          s->line, want);
  return mrn_error_code(MRN_ERR_IO, "'%s': line %d: expected %s, got '%s'", s->path, s->line, want, s->tok);
}

static int expect(scan *s, const char *word) {
  char want[32];
  snprintf(want, sizeof want, "'%s'", word);
  return next(s) && strcmp(s->tok, word) == 0 ? MRN_OK : unexpected(s, want);
}

static int numbers(scan *s, int count, double *out) {
  for (int k = 0; k < count; k++) {
    char *stop;
    if (!next(s)) return unexpected(s, "a number");
    out[k] = strtod(s->tok, &stop);
    if (*stop || stop == s->tok || !isfinite(out[k])) return unexpected(s, "a finite number");
  }
  return MRN_OK;
}

/* one `facet ... endfacet`, its keyword read */
static int facet(scan *s) {
  double normal[3], v[9];
  int rc = expect(s, "normal");
  if (!rc) rc = numbers(s, 3, normal);
  if (!rc) rc = expect(s, "outer");
  if (!rc) rc = expect(s, "loop");
  for (int k = 0; k < 3 && !rc; k++) {
    rc = expect(s, "vertex");
    if (!rc) rc = numbers(s, 3, v + 3 * k);
  }
  if (!rc) rc = expect(s, "endloop");
  if (!rc) rc = expect(s, "endfacet");
  if (rc) return rc;
  if (s->n == MRN_STL_MAX_TRIANGLES)
    return mrn_error_code(MRN_ERR_IO, "'%s': more than %d triangles", s->path, MRN_STL_MAX_TRIANGLES);
  if (s->n == s->cap) {
    s->cap = s->cap ? 2 * s->cap : 64;
    double *grown = realloc(s->tri, 9 * s->cap * sizeof *grown);
    if (!grown) return mrn_error("out of memory for '%s'", s->path);
    s->tri = grown;
  }
  memcpy(s->tri + 9 * s->n++, v, sizeof v);
  return MRN_OK;
}

static int read_ascii(const char *path, const char *buf, size_t size, double **tri, size_t *n) {
  scan s = {.p = buf, .end = buf + size, .path = path, .line = 1};
  int rc = expect(&s, "solid");
  skip_line(&s);
  while (!rc) {
    if (!next(&s)) {
      rc = unexpected(&s, "'endsolid'");
    } else if (strcmp(s.tok, "facet") == 0) {
      rc = facet(&s);
    } else if (strcmp(s.tok, "endsolid") == 0) {
      skip_line(&s);
      if (!next(&s)) break;
      if (strcmp(s.tok, "solid") == 0) skip_line(&s);
      else rc = unexpected(&s, "'solid' or the end of the file");
    } else {
      rc = unexpected(&s, "'facet' or 'endsolid'");
    }
  }
  if (!rc && !s.n) rc = mrn_error_code(MRN_ERR_IO, "'%s': the file holds no triangles", path);
  if (rc) return free(s.tri), rc;
  *tri = s.tri, *n = s.n;
  return MRN_OK;
}

int mrn_stl_read(const char *path, double **tri, size_t *n) {
  size_t size = 0;
  char *buf = slurp(path, &size);
  if (!buf) return MRN_ERR_IO;
  const char *p = buf;
  while (p < buf + size && *p && strchr(" \t\r\n", *p)) p++;
  const int ascii = strncmp(p, "solid", 5) == 0 && !memchr(buf, '\0', size);
  int rc = ascii ? read_ascii(path, buf, size, tri, n) : read_binary(path, (const unsigned char *)buf, size, tri, n);
  free(buf);
  return rc;
}
