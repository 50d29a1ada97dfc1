/* moraine: small HDF5 helpers for the checkpoint files.
 *
 * Writing and reading each go through a context that remembers its first
 * failure. The checkpoint code can then list what it writes or reads in
 * straight lines and look at the outcome once per section; every helper does
 * nothing once the context has failed (the same idea as the VTK writer).
 *
 * The reader is meant for files nobody vouches for: every attribute and
 * dataset is checked for presence, type class, rank and shape before a value
 * is read, and every message names the file and the object, in moraine's
 * words rather than HDF5's error stack. */
#ifndef MRN_IO_H5UTIL_H
#define MRN_IO_H5UTIL_H

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>

/* ---- HDF5's own error printing ------------------------------------------ */

/* HDF5 prints its whole error stack to stderr by default; these turn that off
 * around one moraine call and put back whatever handler was installed. */
typedef struct mrn_h5_quiet {
  H5E_auto2_t func;
  void *data;
} mrn_h5_quiet;

void mrn_h5_silence(mrn_h5_quiet *saved);
void mrn_h5_restore(const mrn_h5_quiet *saved);

/* the innermost (most specific) description on HDF5's error stack, or "" */
void mrn_h5_error_detail(char *buf, size_t len);

/* ---- writing -------------------------------------------------------------- */

typedef struct mrn_h5w {
  hid_t file;
  int failed;
  int err;        /* errno at the first failure (ENOSPC, EDQUOT, ...), 0 if none */
  char what[256]; /* the object that could not be written */
} mrn_h5w;

/* Remember the first failure, naming obj/name ("attribute 'cell' of
 * /grid", "/particles/x"), with errno at that moment. */
void mrn_h5w_fail(mrn_h5w *w, hid_t obj, const char *name, int is_attr);
/* the first failure as moraine's message for `path`: the system's reason
 * when there is one (a full disk), else HDF5's innermost; MRN_ERR_IO */
int mrn_h5w_report(const mrn_h5w *w, const char *path);

/* a new group (close it with H5Gclose); H5I_INVALID_HID once failed */
hid_t mrn_h5w_group(mrn_h5w *w, hid_t parent, const char *name);
/* attributes on a group or dataset */
void mrn_h5w_string(mrn_h5w *w, hid_t obj, const char *name, const char *value);
void mrn_h5w_double(mrn_h5w *w, hid_t obj, const char *name, double value);
void mrn_h5w_doubles(mrn_h5w *w, hid_t obj, const char *name, const double *values, int n);
void mrn_h5w_int32(mrn_h5w *w, hid_t obj, const char *name, int value);
void mrn_h5w_int32s(mrn_h5w *w, hid_t obj, const char *name, const int *values, int n);
void mrn_h5w_int64(mrn_h5w *w, hid_t obj, const char *name, int64_t value);
/* `cols` of a rank-1 dataset (one value per row) */
#define MRN_H5_RANK1 (-1)

/* A dataset of `rows` x `cols` values of the native type `type` (cols ==
 * MRN_H5_RANK1: `rows` values), stored in that same type so nothing is
 * converted, with `units` and `description` attributes. */
void mrn_h5w_dataset(mrn_h5w *w, hid_t group, const char *name, hid_t type, const void *data, size_t rows,
                     int cols, const char *units, const char *description);

/* ---- reading -------------------------------------------------------------- */

typedef struct mrn_h5r {
  hid_t file;
  const char *path; /* the file name, for messages */
  hsize_t file_size;
  int failed;
} mrn_h5r;

/* what a dataset holds; the file type must have this class and size */
typedef enum { MRN_H5_FLOAT64, MRN_H5_INT32, MRN_H5_INT64 } mrn_h5_elem;

/* Record the first failure as "'<file>': <message>" (MRN_ERR_IO); later
 * failures keep the first message. Returns MRN_ERR_IO. */
int mrn_h5r_fail(mrn_h5r *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Open a file read-only, telling a missing or unreadable file, a file that is
 * not HDF5 and a truncated or corrupted one apart. 0 or MRN_ERR_IO. */
int mrn_h5r_open(mrn_h5r *r, const char *path);
void mrn_h5r_close(mrn_h5r *r);

/* 1 when `path` ("/a/b") exists and every step of it is a plain (hard) link,
 * 0 when it does not exist; a soft or external link is refused (failure). */
int mrn_h5r_exists(mrn_h5r *r, const char *path);
/* fail unless `path` is a group */
int mrn_h5r_group(mrn_h5r *r, const char *path);
/* 1 when the object `obj` carries attribute `name` */
int mrn_h5r_has_attr(mrn_h5r *r, const char *obj, const char *name);
/* the number of links (members) of a group; -1 once failed */
long mrn_h5r_group_size(mrn_h5r *r, const char *path);
/* call fn for every attribute name of `obj` until it returns non-zero */
int mrn_h5r_each_attr(mrn_h5r *r, const char *obj, int (*fn)(void *user, const char *name), void *user);

/* Attributes of the object at path `obj`. Numbers: one value (a scalar or a
 * one-element array), or exactly n values. Doubles must be stored as 64-bit
 * floats so nothing is rounded; integers may have any integer type. */
int mrn_h5r_double(mrn_h5r *r, const char *obj, const char *name, double *out);
int mrn_h5r_doubles(mrn_h5r *r, const char *obj, const char *name, double *out, int n);
int mrn_h5r_int(mrn_h5r *r, const char *obj, const char *name, int64_t *out);
int mrn_h5r_ints(mrn_h5r *r, const char *obj, const char *name, int64_t *out, int n);
/* a fixed- or variable-length string of at most cap - 1 bytes */
int mrn_h5r_string(mrn_h5r *r, const char *obj, const char *name, char *buf, size_t cap);
/* a string that must be one of the NULL-terminated `names`; *out is its index */
int mrn_h5r_choice(mrn_h5r *r, const char *obj, const char *name, const char *const *names, int *out);

/* The dataset at `path` as a malloc'd array of rows x cols elements (cols ==
 * MRN_H5_RANK1: rows elements), after checking its presence, type, rank and shape and that the
 * file can hold that much data. NULL once failed. */
void *mrn_h5r_dataset(mrn_h5r *r, const char *path, mrn_h5_elem elem, int64_t rows, int cols);

#endif
