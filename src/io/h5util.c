#include "io/h5util.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"

/* ---- HDF5's own error printing ------------------------------------------ */

void mrn_h5_silence(mrn_h5_quiet *saved) {
  saved->func = NULL;
  saved->data = NULL;
  H5Eget_auto2(H5E_DEFAULT, &saved->func, &saved->data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

void mrn_h5_restore(const mrn_h5_quiet *saved) { H5Eset_auto2(H5E_DEFAULT, saved->func, saved->data); }

typedef struct detail_ctx {
  char *buf;
  size_t len;
} detail_ctx;

/* walking upward, the first entry is where HDF5 first noticed the problem */
static herr_t keep_first(unsigned n, const H5E_error2_t *e, void *user) {
  detail_ctx *c = user;
  if (n == 0 && e->desc) snprintf(c->buf, c->len, "%s", e->desc);
  return 0;
}

void mrn_h5_error_detail(char *buf, size_t len) {
  if (!len) return;
  buf[0] = '\0';
  detail_ctx c = {buf, len};
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_first, &c);
}

/* ---- writing -------------------------------------------------------------- */

/* Whether to go on; errno is cleared so that a failing HDF5 call leaves the
 * system's reason (the write(2) that hit a full disk) for the message. */
static int w_begin(mrn_h5w *w) {
  if (w->failed) return 0;
  errno = 0;
  return 1;
}

/* remember the first failure: "attribute 'cell' of /grid", "/particles/x" */
void mrn_h5w_fail(mrn_h5w *w, hid_t obj, const char *name, int is_attr) {
  if (w->failed) return;
  w->failed = 1;
  w->err = errno;
  char where[200] = "";
  if (obj >= 0) H5Iget_name(obj, where, sizeof where);
  if (is_attr)
    snprintf(w->what, sizeof w->what, "attribute '%s' of %s", name, where[0] ? where : "/");
  else
    snprintf(w->what, sizeof w->what, "%s%s%s", strcmp(where, "/") == 0 ? "" : where, "/", name);
}

int mrn_h5w_report(const mrn_h5w *w, const char *path) {
  if (w->err) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': %s (writing %s)", path, strerror(w->err), w->what);
  char detail[256];
  mrn_h5_error_detail(detail, sizeof detail);
  return mrn_error_code(MRN_ERR_IO, "cannot write '%s': HDF5 could not write %s%s%s%s", path, w->what,
                        detail[0] ? " (" : "", detail, detail[0] ? ")" : "");
}

hid_t mrn_h5w_group(mrn_h5w *w, hid_t parent, const char *name) {
  if (!w_begin(w)) return H5I_INVALID_HID;
  hid_t g = H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) mrn_h5w_fail(w, parent, name, 0);
  return g;
}

/* one attribute of `type` over `space`; the space is closed here */
static void w_attr(mrn_h5w *w, hid_t obj, const char *name, hid_t type, hid_t space, const void *data) {
  if (w->failed || space < 0) {
    if (space >= 0) H5Sclose(space);
    else mrn_h5w_fail(w, obj, name, 1);
    return;
  }
  errno = 0;
  hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  herr_t rc = a < 0 ? -1 : H5Awrite(a, type, data);
  if (a >= 0 && H5Aclose(a) < 0) rc = -1;
  H5Sclose(space);
  if (rc < 0) mrn_h5w_fail(w, obj, name, 1);
}

static hid_t list_space(int n) {
  hsize_t dims[1] = {(hsize_t)n};
  return H5Screate_simple(1, dims, NULL);
}

/* Fixed-length, NUL-terminated UTF-8. Variable-length strings would live in
 * HDF5's global heap, whose reader trusts the file and crashes on damaged
 * ones; a fixed-length string sits in the attribute itself. (h5py reads these
 * as bytes: .decode() gives the text.) */
void mrn_h5w_string(mrn_h5w *w, hid_t obj, const char *name, const char *value) {
  if (w->failed) return;
  hid_t t = H5Tcopy(H5T_C_S1);
  if (t < 0 || H5Tset_size(t, strlen(value) + 1) < 0 || H5Tset_strpad(t, H5T_STR_NULLTERM) < 0 ||
      H5Tset_cset(t, H5T_CSET_UTF8) < 0) {
    if (t >= 0) H5Tclose(t);
    mrn_h5w_fail(w, obj, name, 1);
    return;
  }
  w_attr(w, obj, name, t, H5Screate(H5S_SCALAR), value);
  H5Tclose(t);
}

void mrn_h5w_double(mrn_h5w *w, hid_t obj, const char *name, double value) {
  w_attr(w, obj, name, H5T_NATIVE_DOUBLE, H5Screate(H5S_SCALAR), &value);
}

void mrn_h5w_doubles(mrn_h5w *w, hid_t obj, const char *name, const double *values, int n) {
  w_attr(w, obj, name, H5T_NATIVE_DOUBLE, list_space(n), values);
}

void mrn_h5w_int32(mrn_h5w *w, hid_t obj, const char *name, int value) {
  w_attr(w, obj, name, H5T_NATIVE_INT, H5Screate(H5S_SCALAR), &value);
}

void mrn_h5w_int32s(mrn_h5w *w, hid_t obj, const char *name, const int *values, int n) {
  w_attr(w, obj, name, H5T_NATIVE_INT, list_space(n), values);
}

void mrn_h5w_int64(mrn_h5w *w, hid_t obj, const char *name, int64_t value) {
  w_attr(w, obj, name, H5T_NATIVE_INT64, H5Screate(H5S_SCALAR), &value);
}

void mrn_h5w_dataset(mrn_h5w *w, hid_t group, const char *name, hid_t type, const void *data, size_t rows,
                     int cols, const char *units, const char *description) {
  if (!w_begin(w)) return;
  hsize_t dims[2] = {(hsize_t)rows, cols < 0 ? 0 : (hsize_t)cols};
  hid_t space = H5Screate_simple(cols < 0 ? 1 : 2, dims, NULL);
  hid_t d = space < 0 ? -1 : H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (space >= 0) H5Sclose(space);
  /* an empty dataset (no particles, no history variables) has nothing to write */
  size_t count = cols < 0 ? rows : rows * (size_t)cols;
  herr_t rc = d < 0 ? -1 : 0;
  if (rc == 0 && count > 0) rc = H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  if (rc < 0) {
    mrn_h5w_fail(w, group, name, 0);
  } else {
    mrn_h5w_string(w, d, "units", units);
    mrn_h5w_string(w, d, "description", description);
  }
  if (d >= 0 && H5Dclose(d) < 0) mrn_h5w_fail(w, group, name, 0);
}

/* ---- reading: failures ---------------------------------------------------- */

int mrn_h5r_fail(mrn_h5r *r, const char *fmt, ...) {
  if (r->failed) return MRN_ERR_IO;
  r->failed = 1;
  char msg[1600];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return mrn_error_code(MRN_ERR_IO, "'%s': %s", r->path, msg);
}

/* ---- reading: the file ---------------------------------------------------- */

int mrn_h5r_open(mrn_h5r *r, const char *path) {
  memset(r, 0, sizeof *r);
  r->file = H5I_INVALID_HID;
  r->path = path ? path : "";
  struct stat st;
  if (!path || !*path) return mrn_h5r_fail(r, "no file name given");
  if (stat(path, &st) != 0) return mrn_h5r_fail(r, "cannot open: %s", strerror(errno));
  if (S_ISDIR(st.st_mode)) return mrn_h5r_fail(r, "is a directory, not a checkpoint file");
  if (access(path, R_OK) != 0) return mrn_h5r_fail(r, "cannot open: %s", strerror(errno));
  if (st.st_size == 0) return mrn_h5r_fail(r, "empty file, not a moraine checkpoint");
  htri_t is_hdf5 = H5Fis_hdf5(path);
  if (is_hdf5 == 0) return mrn_h5r_fail(r, "not an HDF5 file, so not a moraine checkpoint");
  if (is_hdf5 < 0) return mrn_h5r_fail(r, "cannot read the file");
  /* a strong close degree makes H5Fclose release every object still open,
   * so an early return from a half-read file leaks nothing */
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl >= 0) H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
  r->file = H5Fopen(path, H5F_ACC_RDONLY, fapl >= 0 ? fapl : H5P_DEFAULT);
  char detail[256];
  mrn_h5_error_detail(detail, sizeof detail);
  if (fapl >= 0) H5Pclose(fapl);
  if (r->file < 0) {
    /* the signature was there, so the file was meant to be HDF5: it is cut
     * short or damaged (HDF5's innermost reason helps telling which) */
    return mrn_h5r_fail(r, "truncated or corrupted HDF5 file%s%s%s", detail[0] ? " (" : "", detail,
                        detail[0] ? ")" : "");
  }
  if (H5Fget_filesize(r->file, &r->file_size) < 0) r->file_size = (hsize_t)st.st_size;
  return MRN_OK;
}

void mrn_h5r_close(mrn_h5r *r) {
  if (r->file >= 0) H5Fclose(r->file);
  r->file = H5I_INVALID_HID;
}

/* ---- reading: objects ----------------------------------------------------- */

/* one step of a path: 1 present as a hard link, 0 absent */
static int link_present(mrn_h5r *r, const char *prefix) {
  htri_t e = H5Lexists(r->file, prefix, H5P_DEFAULT);
  if (e < 0) return mrn_h5r_fail(r, "cannot read %s (truncated or corrupted file)", prefix), 0;
  if (e == 0) return 0;
  H5L_info_t info;
  if (H5Lget_info(r->file, prefix, &info, H5P_DEFAULT) < 0)
    return mrn_h5r_fail(r, "cannot read %s (truncated or corrupted file)", prefix), 0;
  /* a soft or external link would make the loader read what another file holds */
  if (info.type != H5L_TYPE_HARD)
    return mrn_h5r_fail(r, "%s is a soft or external link; a checkpoint holds its data itself", prefix), 0;
  return 1;
}

int mrn_h5r_exists(mrn_h5r *r, const char *path) {
  if (r->failed) return 0;
  char buf[512];
  if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) return mrn_h5r_fail(r, "path too long"), 0;
  /* H5Lexists fails rather than answering 0 when a parent is missing: walk down */
  for (char *p = buf + 1; *p; p++) {
    if (*p != '/') continue;
    *p = '\0';
    int present = link_present(r, buf);
    *p = '/';
    if (!present) return 0;
  }
  return strcmp(buf, "/") == 0 ? 1 : link_present(r, buf);
}

int mrn_h5r_group(mrn_h5r *r, const char *path) {
  if (r->failed) return MRN_ERR_IO;
  if (!mrn_h5r_exists(r, path)) return mrn_h5r_fail(r, "missing group %s", path);
  hid_t o = H5Oopen(r->file, path, H5P_DEFAULT);
  if (o < 0) return mrn_h5r_fail(r, "cannot read %s (truncated or corrupted file)", path);
  H5I_type_t t = H5Iget_type(o);
  H5Oclose(o);
  if (t != H5I_GROUP) return mrn_h5r_fail(r, "%s is not a group", path);
  return MRN_OK;
}

int mrn_h5r_has_attr(mrn_h5r *r, const char *obj, const char *name) {
  if (r->failed) return 0;
  htri_t e = H5Aexists_by_name(r->file, obj, name, H5P_DEFAULT);
  if (e < 0) return mrn_h5r_fail(r, "cannot read the attributes of %s (truncated or corrupted file)", obj), 0;
  return e > 0;
}

long mrn_h5r_group_size(mrn_h5r *r, const char *path) {
  if (r->failed) return -1;
  H5G_info_t info;
  if (H5Gget_info_by_name(r->file, path, &info, H5P_DEFAULT) < 0)
    return mrn_h5r_fail(r, "cannot read %s (truncated or corrupted file)", path), -1;
  return (long)info.nlinks;
}

typedef struct each_attr_ctx {
  int (*fn)(void *user, const char *name);
  void *user;
} each_attr_ctx;

static herr_t each_attr_cb(hid_t loc, const char *name, const H5A_info_t *info, void *data) {
  each_attr_ctx *c = data;
  return c->fn(c->user, name) ? 1 : 0;
}

int mrn_h5r_each_attr(mrn_h5r *r, const char *obj, int (*fn)(void *user, const char *name), void *user) {
  if (r->failed) return MRN_ERR_IO;
  each_attr_ctx c = {fn, user};
  hsize_t idx = 0;
  if (H5Aiterate_by_name(r->file, obj, H5_INDEX_NAME, H5_ITER_INC, &idx, each_attr_cb, &c, H5P_DEFAULT) < 0)
    return mrn_h5r_fail(r, "cannot read the attributes of %s (truncated or corrupted file)", obj);
  return r->failed ? MRN_ERR_IO : MRN_OK;
}

/* ---- reading: types and shapes -------------------------------------------- */

/* "64-bit float", "32-bit integer", "string", ... for messages */
static const char *type_text(hid_t t, char *buf, size_t len) {
  size_t bits = 8 * H5Tget_size(t);
  switch (H5Tget_class(t)) {
  case H5T_INTEGER: snprintf(buf, len, "%zu-bit integer", bits); break;
  case H5T_FLOAT: snprintf(buf, len, "%zu-bit float", bits); break;
  case H5T_STRING: snprintf(buf, len, "string"); break;
  case H5T_COMPOUND: snprintf(buf, len, "compound"); break;
  case H5T_ENUM: snprintf(buf, len, "enumeration"); break;
  case H5T_ARRAY: snprintf(buf, len, "array"); break;
  case H5T_VLEN: snprintf(buf, len, "variable-length sequence"); break;
  default: snprintf(buf, len, "unusual type"); break;
  }
  return buf;
}

typedef enum { WANT_FLOAT64, WANT_INTEGER, WANT_INT32, WANT_INT64, WANT_STRING } want_type;

static const char *want_text(want_type w) {
  switch (w) {
  case WANT_FLOAT64: return "64-bit float";
  case WANT_INTEGER: return "integer";
  case WANT_INT32: return "integer of at most 32 bits";
  case WANT_INT64: return "integer of at most 64 bits";
  default: return "string";
  }
}

static const char *article(const char *word) { return strchr("aeiou", word[0]) ? "an" : "a"; }

static int type_matches(hid_t t, want_type want) {
  H5T_class_t c = H5Tget_class(t);
  size_t size = H5Tget_size(t);
  switch (want) {
  case WANT_FLOAT64: return c == H5T_FLOAT && size == 8; /* anything narrower has lost digits */
  case WANT_INTEGER:
  case WANT_INT64: return c == H5T_INTEGER && size <= 8;
  case WANT_INT32: return c == H5T_INTEGER && size <= 4;
  default: return c == H5T_STRING;
  }
}

/* "10 x 6", "10", "a scalar" */
static void shape_text(hid_t space, char *buf, size_t len) {
  H5S_class_t c = H5Sget_simple_extent_type(space);
  if (c == H5S_SCALAR) {
    snprintf(buf, len, "a scalar");
    return;
  }
  if (c != H5S_SIMPLE) {
    snprintf(buf, len, "no data (null dataspace)");
    return;
  }
  hsize_t dims[H5S_MAX_RANK];
  int rank = H5Sget_simple_extent_dims(space, dims, NULL);
  size_t used = 0;
  buf[0] = '\0';
  for (int i = 0; i < rank && used < len; i++)
    used += (size_t)snprintf(buf + used, len - used, "%s%llu", i ? " x " : "", (unsigned long long)dims[i]);
}

/* ---- reading: attributes -------------------------------------------------- */

/* "attribute 'cell' of /grid" is built into every message below */
static hid_t open_attr(mrn_h5r *r, const char *obj, const char *name, want_type want) {
  if (r->failed) return H5I_INVALID_HID;
  htri_t e = H5Aexists_by_name(r->file, obj, name, H5P_DEFAULT);
  if (e < 0) return mrn_h5r_fail(r, "cannot read the attributes of %s (truncated or corrupted file)", obj), -1;
  if (e == 0) return mrn_h5r_fail(r, "%s has no attribute '%s'", obj, name), -1;
  hid_t a = H5Aopen_by_name(r->file, obj, name, H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0) return mrn_h5r_fail(r, "cannot read attribute '%s' of %s (truncated or corrupted file)", name, obj), -1;
  hid_t t = H5Aget_type(a);
  int ok = t >= 0 && type_matches(t, want);
  if (!ok) {
    char text[64] = "unreadable type";
    if (t >= 0) type_text(t, text, sizeof text);
    mrn_h5r_fail(r, "attribute '%s' of %s is %s %s, expected %s %s", name, obj, article(text), text,
                 article(want_text(want)), want_text(want));
  }
  if (t >= 0) H5Tclose(t);
  if (!ok) {
    H5Aclose(a);
    return H5I_INVALID_HID;
  }
  return a;
}

/* number of values: a scalar counts as one, a list as its length */
static long long attr_count(mrn_h5r *r, hid_t a, const char *obj, const char *name) {
  hid_t s = H5Aget_space(a);
  if (s < 0) return mrn_h5r_fail(r, "cannot read attribute '%s' of %s", name, obj), -1;
  H5S_class_t c = H5Sget_simple_extent_type(s);
  int rank = H5Sget_simple_extent_ndims(s);
  long long n = (long long)H5Sget_simple_extent_npoints(s);
  char shape[64];
  shape_text(s, shape, sizeof shape);
  H5Sclose(s);
  if (c == H5S_SCALAR) return 1;
  if (c == H5S_SIMPLE && rank == 1) return n;
  return mrn_h5r_fail(r, "attribute '%s' of %s has shape %s, expected a value or a list", name, obj, shape), -1;
}

/* open an attribute of `want` holding exactly n values */
static hid_t open_values(mrn_h5r *r, const char *obj, const char *name, want_type want, int n) {
  hid_t a = open_attr(r, obj, name, want);
  if (a < 0) return a;
  long long count = attr_count(r, a, obj, name);
  if (count >= 0 && count != n) {
    if (n == 1)
      mrn_h5r_fail(r, "attribute '%s' of %s has %lld values, expected one", name, obj, count);
    else
      mrn_h5r_fail(r, "attribute '%s' of %s has %lld values, expected %d", name, obj, count, n);
  }
  if (r->failed) {
    H5Aclose(a);
    return H5I_INVALID_HID;
  }
  return a;
}

static int read_values(mrn_h5r *r, const char *obj, const char *name, want_type want, hid_t memtype, void *out,
                       int n) {
  hid_t a = open_values(r, obj, name, want, n);
  if (a < 0) return MRN_ERR_IO;
  if (H5Aread(a, memtype, out) < 0)
    mrn_h5r_fail(r, "cannot read attribute '%s' of %s (truncated or corrupted file)", name, obj);
  H5Aclose(a);
  return r->failed ? MRN_ERR_IO : MRN_OK;
}

int mrn_h5r_double(mrn_h5r *r, const char *obj, const char *name, double *out) {
  return read_values(r, obj, name, WANT_FLOAT64, H5T_NATIVE_DOUBLE, out, 1);
}

int mrn_h5r_doubles(mrn_h5r *r, const char *obj, const char *name, double *out, int n) {
  return read_values(r, obj, name, WANT_FLOAT64, H5T_NATIVE_DOUBLE, out, n);
}

int mrn_h5r_int(mrn_h5r *r, const char *obj, const char *name, int64_t *out) {
  return read_values(r, obj, name, WANT_INTEGER, H5T_NATIVE_INT64, out, 1);
}

int mrn_h5r_ints(mrn_h5r *r, const char *obj, const char *name, int64_t *out, int n) {
  return read_values(r, obj, name, WANT_INTEGER, H5T_NATIVE_INT64, out, n);
}

static int read_vlen_string(mrn_h5r *r, hid_t a, hid_t ftype, char **out) {
  hid_t mt = H5Tcopy(H5T_C_S1);
  int ok = mt >= 0 && H5Tset_size(mt, H5T_VARIABLE) >= 0 && H5Tset_cset(mt, H5Tget_cset(ftype)) >= 0 &&
           H5Aread(a, mt, out) >= 0;
  if (mt >= 0) H5Tclose(mt);
  return ok;
}

/* copy a string read from the file into buf, refusing one that does not fit */
static int take_string(mrn_h5r *r, const char *obj, const char *name, const char *s, size_t slen, char *buf,
                       size_t cap) {
  if (memchr(s, '\0', slen)) slen = strlen(s);
  if (slen >= cap)
    return mrn_h5r_fail(r, "attribute '%s' of %s is %zu characters long, at most %zu expected", name, obj, slen,
                        cap - 1);
  memcpy(buf, s, slen);
  buf[slen] = '\0';
  return MRN_OK;
}

int mrn_h5r_string(mrn_h5r *r, const char *obj, const char *name, char *buf, size_t cap) {
  buf[0] = '\0';
  hid_t a = open_values(r, obj, name, WANT_STRING, 1);
  if (a < 0) return MRN_ERR_IO;
  hid_t ft = H5Aget_type(a);
  if (ft >= 0 && H5Tis_variable_str(ft) > 0) {
    char *s = NULL;
    if (!read_vlen_string(r, a, ft, &s))
      mrn_h5r_fail(r, "cannot read attribute '%s' of %s (truncated or corrupted file)", name, obj);
    else
      take_string(r, obj, name, s ? s : "", s ? strlen(s) : 0, buf, cap);
    if (s) H5free_memory(s);
  } else if (ft >= 0) {
    /* fixed length: read in the stored type itself (HDF5 converts between
     * character sets only by refusing), then cut at the first NUL */
    size_t size = H5Tget_size(ft);
    char *tmp = size <= 65536 ? malloc(size + 1) : NULL;
    if (!tmp)
      mrn_h5r_fail(r, "attribute '%s' of %s is a string of %zu bytes, at most %zu expected", name, obj, size, cap - 1);
    else if (H5Aread(a, ft, tmp) < 0)
      mrn_h5r_fail(r, "cannot read attribute '%s' of %s (truncated or corrupted file)", name, obj);
    else
      take_string(r, obj, name, tmp, size, buf, cap);
    free(tmp);
  }
  if (ft >= 0) H5Tclose(ft);
  H5Aclose(a);
  return r->failed ? MRN_ERR_IO : MRN_OK;
}

int mrn_h5r_choice(mrn_h5r *r, const char *obj, const char *name, const char *const *names, int *out) {
  char value[128];
  if (mrn_h5r_string(r, obj, name, value, sizeof value)) return MRN_ERR_IO;
  for (int i = 0; names[i]; i++)
    if (strcmp(names[i], value) == 0) {
      *out = i;
      return MRN_OK;
    }
  char list[512] = "";
  size_t used = 0;
  for (int i = 0; names[i] && used < sizeof list; i++)
    used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", names[i]);
  return mrn_h5r_fail(r, "attribute '%s' of %s is '%s', expected one of: %s", name, obj, value, list);
}

/* ---- reading: datasets ---------------------------------------------------- */

static size_t elem_size(mrn_h5_elem e) { return e == MRN_H5_INT32 ? 4 : 8; }

static hid_t elem_memtype(mrn_h5_elem e) {
  switch (e) {
  case MRN_H5_INT32: return H5T_NATIVE_INT32;
  case MRN_H5_INT64: return H5T_NATIVE_INT64;
  default: return H5T_NATIVE_DOUBLE;
  }
}

static want_type elem_want(mrn_h5_elem e) {
  switch (e) {
  case MRN_H5_INT32: return WANT_INT32;
  case MRN_H5_INT64: return WANT_INT64;
  default: return WANT_FLOAT64;
  }
}

static int check_dataset_type(mrn_h5r *r, hid_t d, const char *path, mrn_h5_elem elem) {
  hid_t t = H5Dget_type(d);
  if (t < 0) return mrn_h5r_fail(r, "cannot read %s (truncated or corrupted file)", path);
  int ok = type_matches(t, elem_want(elem));
  char text[64];
  type_text(t, text, sizeof text);
  H5Tclose(t);
  if (!ok) return mrn_h5r_fail(r, "%s holds %s values, expected %s values", path, text, want_text(elem_want(elem)));
  return MRN_OK;
}

static int check_dataset_shape(mrn_h5r *r, hid_t d, const char *path, int64_t rows, int cols) {
  hid_t s = H5Dget_space(d);
  if (s < 0) return mrn_h5r_fail(r, "cannot read %s (truncated or corrupted file)", path);
  hsize_t dims[H5S_MAX_RANK] = {0};
  int rank = H5Sget_simple_extent_type(s) == H5S_SIMPLE ? H5Sget_simple_extent_dims(s, dims, NULL) : -1;
  int want_rank = cols < 0 ? 1 : 2;
  int ok = rank == want_rank && dims[0] == (hsize_t)rows && (cols < 0 || dims[1] == (hsize_t)cols);
  char got[128], want[64];
  shape_text(s, got, sizeof got);
  H5Sclose(s);
  if (ok) return MRN_OK;
  if (cols >= 0)
    snprintf(want, sizeof want, "%lld x %d", (long long)rows, cols);
  else
    snprintf(want, sizeof want, "%lld", (long long)rows);
  return mrn_h5r_fail(r, "%s has shape %s, expected %s", path, got, want);
}

/* A dataset that claims more data than the file could hold is refused
 * before any memory is set aside for it. Compressed data can shrink, but
 * never by more than a few thousand times. */
static int check_dataset_storage(mrn_h5r *r, hid_t d, const char *path, size_t bytes) {
  hid_t dcpl = H5Dget_create_plist(d);
  int nfilters = dcpl >= 0 ? H5Pget_nfilters(dcpl) : 0;
  if (dcpl >= 0) H5Pclose(dcpl);
  size_t limit = nfilters > 0 ? (size_t)r->file_size * 4096 : (size_t)r->file_size;
  if (bytes > limit)
    return mrn_h5r_fail(r, "%s claims %zu bytes of data but the file has %llu bytes (truncated or corrupted file)",
                        path, bytes, (unsigned long long)r->file_size);
  return MRN_OK;
}

void *mrn_h5r_dataset(mrn_h5r *r, const char *path, mrn_h5_elem elem, int64_t rows, int cols) {
  if (r->failed) return NULL;
  if (!mrn_h5r_exists(r, path)) return mrn_h5r_fail(r, "missing dataset %s", path), NULL;
  size_t width = cols < 0 ? 1 : (size_t)cols;
  if (rows < 0 || (width && (uint64_t)rows > SIZE_MAX / elem_size(elem) / width))
    return mrn_h5r_fail(r, "%s: impossible size %lld x %d", path, (long long)rows, cols), NULL;
  size_t bytes = (size_t)rows * (size_t)width * elem_size(elem);
  hid_t d = H5Oopen(r->file, path, H5P_DEFAULT);
  if (d < 0) return mrn_h5r_fail(r, "cannot read %s (truncated or corrupted file)", path), NULL;
  if (H5Iget_type(d) != H5I_DATASET) {
    H5Oclose(d);
    return mrn_h5r_fail(r, "%s is not a dataset", path), NULL;
  }
  void *buf = NULL;
  if (check_dataset_type(r, d, path, elem) || check_dataset_shape(r, d, path, rows, cols) ||
      check_dataset_storage(r, d, path, bytes))
    goto done;
  buf = malloc(bytes ? bytes : 1);
  if (!buf) {
    mrn_h5r_fail(r, "out of memory reading %s (%zu bytes)", path, bytes);
    goto done;
  }
  if (bytes && H5Dread(d, elem_memtype(elem), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) {
    mrn_h5r_fail(r, "cannot read %s (truncated or corrupted file)", path);
    free(buf);
    buf = NULL;
  }
done:
  H5Oclose(d);
  return buf;
}
