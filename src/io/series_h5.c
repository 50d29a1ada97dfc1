#include "io/series_h5.h"

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/h5util.h"

#define SERIES_FORMAT "moraine-series"
#define SERIES_VERSION 1

/* Rows per chunk. A flush rewrites the last chunk of every dataset, so small
 * chunks keep each append cheap; 512 rows (4 KiB) still make a long series
 * only a few thousand chunks. */
#define CHUNK_ROWS 512

/* A column lives in memory until the next append (or the close) creates its
 * dataset: the file then changes only inside mrn_series_append(), and one
 * flush there takes every change to disk at once. */
typedef struct column {
  char *name, *units, *description;
  hid_t ds;       /* H5I_INVALID_HID until the dataset exists */
  int attrs_new;  /* units/description changed after the dataset was made */
  double pending; /* the value for the next row (NaN: none given) */
} column;

struct mrn_series {
  char *path;
  hid_t file, time_ds, step_ds;
  column *cols;
  int ncol, cap;
  long rows;
  int broken; /* an append failed part-way: no more writes */
};

/* ---- failures --------------------------------------------------------------- */

/* Remember what failed and errno at that moment (the write(2) that hit a full
 * disk); HDF5 calls are made with errno cleared first, see begin(). */
static void note_fail(mrn_h5w *w, const char *fmt, const char *name) {
  if (w->failed) return;
  w->failed = 1;
  w->err = errno;
  snprintf(w->what, sizeof w->what, fmt, name);
}

static int begin(mrn_h5w *w) {
  if (w->failed) return 0;
  errno = 0;
  return 1;
}

/* the moraine message for a failed write, in the checkpoint writer's words */
static int report(const mrn_h5w *w, const char *path) {
  if (w->err) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': %s (writing %s)", path, strerror(w->err), w->what);
  char detail[256];
  mrn_h5_error_detail(detail, sizeof detail);
  return mrn_error_code(MRN_ERR_IO, "cannot write '%s': HDF5 could not write %s%s%s%s", path, w->what,
                        detail[0] ? " (" : "", detail, detail[0] ? ")" : "");
}

/* ---- file and dataset properties -------------------------------------------- */

/* The HDF5 1.8 file format, as the checkpoints use: checksummed metadata, and
 * readable by every HDF5 since 1.8. File locking is off: HDF5 would otherwise
 * hold an exclusive lock while the run has the file open, and every reader
 * (h5py, h5dump) would be refused until the run ends. */
static hid_t file_access(void) {
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0) return fapl;
  H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18);
#if H5_VERSION_GE(1, 10, 7) && !(H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 12 && H5_VERS_RELEASE == 0)
  H5Pset_file_locking(fapl, 0, 1);
#endif
  return fapl;
}

/* A 1D dataset of `rows` entries that can grow without limit. Entries never
 * written read as the fill value, which for the columns is NaN: that is what
 * pads a column added late. */
static hid_t make_dataset(mrn_h5w *w, hid_t file, const char *name, hid_t type, hsize_t rows, const char *units,
                          const char *description) {
  if (!begin(w)) return H5I_INVALID_HID;
  hsize_t maxdims = H5S_UNLIMITED, chunk = CHUNK_ROWS;
  hid_t space = H5Screate_simple(1, &rows, &maxdims);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  hid_t ds = H5I_INVALID_HID;
  if (space >= 0 && dcpl >= 0 && H5Pset_chunk(dcpl, 1, &chunk) >= 0) {
    const double nan = NAN;
    if (H5Tget_class(type) != H5T_FLOAT || H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, &nan) >= 0)
      ds = H5Dcreate2(file, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  }
  if (space >= 0) H5Sclose(space);
  if (dcpl >= 0) H5Pclose(dcpl);
  if (ds < 0) {
    note_fail(w, "dataset /%s", name);
    return H5I_INVALID_HID;
  }
  mrn_h5w_string(w, ds, "units", units ? units : "");
  mrn_h5w_string(w, ds, "description", description ? description : "");
  return ds;
}

/* ---- creating the file ------------------------------------------------------- */

/* the empty series: root attributes, /time and /step */
static void write_skeleton(mrn_h5w *w, const char *temp_path) {
  hid_t fapl = file_access();
  hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
  /* datasets listed in the order added (h5dump --sort_by=creation_order) */
  if (fcpl >= 0) H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
  errno = 0;
  w->file = H5Fcreate(temp_path, H5F_ACC_TRUNC, fcpl >= 0 ? fcpl : H5P_DEFAULT, fapl >= 0 ? fapl : H5P_DEFAULT);
  if (fcpl >= 0) H5Pclose(fcpl);
  if (fapl >= 0) H5Pclose(fapl);
  if (w->file < 0) {
    note_fail(w, "%s", "the file");
    return;
  }
  mrn_h5w_string(w, w->file, "format", SERIES_FORMAT);
  mrn_h5w_int32(w, w->file, "version", SERIES_VERSION);
  mrn_h5w_string(w, w->file, "moraine_version", MORAINE_VERSION " (" MORAINE_GIT_COMMIT ")");
  mrn_h5w_string(w, w->file, "description",
                 "time series: one entry per row in every dataset; NaN where a column had no value");
  hid_t t = make_dataset(w, w->file, "time", H5T_IEEE_F64LE, 0, "s", "model time of the row");
  hid_t st = make_dataset(w, w->file, "step", H5T_STD_I64LE, 0, "", "step number of the row");
  if (t >= 0) H5Dclose(t);
  if (st >= 0) H5Dclose(st);
  errno = 0;
  if (H5Fclose(w->file) < 0) note_fail(w, "%s", "the file (closing it)");
  w->file = H5I_INVALID_HID;
}

/* HDF5 writes the temporary file by name; mrn_atomic_file reserved that name
 * and on commit fsyncs and renames it, so the series appears whole or not at all */
static int create_file(const char *path) {
  mrn_atomic_file tmp;
  int rc = mrn_atomic_open(&tmp, path);
  if (rc != MRN_OK) return rc;
  mrn_h5w w = {.file = H5I_INVALID_HID};
  write_skeleton(&w, tmp.temp_path);
  if (w.failed) {
    rc = report(&w, path);
    mrn_atomic_abort(&tmp);
    return rc;
  }
  return mrn_atomic_commit(&tmp);
}

static int open_file(mrn_series *s) {
  hid_t fapl = file_access();
  errno = 0;
  s->file = H5Fopen(s->path, H5F_ACC_RDWR, fapl >= 0 ? fapl : H5P_DEFAULT);
  if (fapl >= 0) H5Pclose(fapl);
  if (s->file >= 0) s->time_ds = H5Dopen2(s->file, "time", H5P_DEFAULT);
  if (s->time_ds >= 0) s->step_ds = H5Dopen2(s->file, "step", H5P_DEFAULT);
  if (s->step_ds >= 0) return MRN_OK;
  mrn_h5w w = {.file = s->file};
  note_fail(&w, "%s", "the file (opening it)");
  return report(&w, s->path);
}

static void release(mrn_series *s) {
  for (int i = 0; i < s->ncol; i++) {
    free(s->cols[i].name);
    free(s->cols[i].units);
    free(s->cols[i].description);
  }
  free(s->cols);
  free(s->path);
  free(s);
}

int mrn_series_create(mrn_series **out, const char *path) {
  *out = NULL;
  if (!path || !*path) return mrn_error_code(MRN_ERR_IO, "cannot write a series file without a path");
  mrn_series *s = calloc(1, sizeof *s);
  if (!s || !(s->path = strdup(path))) {
    free(s);
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", path);
  }
  s->file = s->time_ds = s->step_ds = H5I_INVALID_HID;
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  int rc = create_file(path);
  if (rc == MRN_OK) rc = open_file(s);
  mrn_h5_restore(&quiet);
  if (rc != MRN_OK) {
    mrn_series_close(s); /* the file, if made, stays: it is a valid empty series */
    return rc;
  }
  *out = s;
  return MRN_OK;
}

/* ---- columns ------------------------------------------------------------------ */

int mrn_series_find(const mrn_series *s, const char *name) {
  for (int i = 0; s && name && i < s->ncol; i++)
    if (strcmp(s->cols[i].name, name) == 0) return i;
  return -1;
}

/* one dataset per column in the root group: a '/' would make groups, and
 * time/step are taken */
static int check_name(const mrn_series *s, const char *name) {
  if (!name || !*name) return mrn_error("series '%s': a column needs a name", s->path);
  if (strchr(name, '/') || strcmp(name, ".") == 0)
    return mrn_error("series '%s': column name '%s' may not contain '/' or be '.'", s->path, name);
  if (strcmp(name, "time") == 0 || strcmp(name, "step") == 0)
    return mrn_error("series '%s': column name '%s' is taken by the series itself", s->path, name);
  return MRN_OK;
}

static int grow_columns(mrn_series *s) {
  if (s->ncol < s->cap) return 0;
  int cap = s->cap ? 2 * s->cap : 32;
  column *cols = realloc(s->cols, (size_t)cap * sizeof *cols);
  if (!cols) return -1;
  s->cols = cols;
  s->cap = cap;
  return 0;
}

/* replace *slot with a copy of text when text says something; 0 or -1 (memory) */
static int take_text(char **slot, const char *text, int *changed) {
  if (!text || !*text || (*slot && strcmp(*slot, text) == 0)) return 0;
  char *copy = strdup(text);
  if (!copy) return -1;
  free(*slot);
  *slot = copy;
  *changed = 1;
  return 0;
}

int mrn_series_add_column(mrn_series *s, const char *name, const char *units, const char *description) {
  if (check_name(s, name) != MRN_OK) return MRN_ERR;
  int idx = mrn_series_find(s, name);
  if (idx < 0) {
    char *copy = strdup(name);
    if (!copy || grow_columns(s) != 0) {
      free(copy);
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", s->path);
    }
    idx = s->ncol++;
    s->cols[idx] = (column){copy, NULL, NULL, H5I_INVALID_HID, 0, NAN};
  }
  column *c = &s->cols[idx];
  int changed = 0;
  if (take_text(&c->units, units, &changed) != 0 || take_text(&c->description, description, &changed) != 0)
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", s->path);
  if (changed && c->ds >= 0) c->attrs_new = 1;
  return MRN_OK;
}

int mrn_series_set(mrn_series *s, const char *name, double value) {
  int idx = mrn_series_find(s, name);
  if (idx < 0) {
    int rc = mrn_series_add_column(s, name, "", "");
    if (rc != MRN_OK) return rc;
    idx = s->ncol - 1;
  }
  s->cols[idx].pending = value;
  return MRN_OK;
}

int mrn_series_set_at(mrn_series *s, int column, double value) {
  if (column < 0 || column >= s->ncol)
    return mrn_error("series '%s': no column %d (it has %d)", s->path, column, s->ncol);
  s->cols[column].pending = value;
  return MRN_OK;
}

/* ---- rows ---------------------------------------------------------------------- */

/* replace an attribute's text (HDF5 attributes cannot change size in place) */
static void rewrite_attr(mrn_h5w *w, hid_t ds, const char *attr, const char *text) {
  if (!text || !begin(w)) return;
  if (H5Aexists(ds, attr) > 0 && H5Adelete(ds, attr) < 0) {
    note_fail(w, "attribute '%s'", attr);
    return;
  }
  mrn_h5w_string(w, ds, attr, text);
}

/* the datasets of columns named since the last append (NaN for the rows
 * already written: the fill value), and units or descriptions given late */
static void sync_columns(mrn_series *s, mrn_h5w *w) {
  for (int i = 0; i < s->ncol && !w->failed; i++) {
    column *c = &s->cols[i];
    if (c->ds < 0) {
      c->ds = make_dataset(w, s->file, c->name, H5T_IEEE_F64LE, (hsize_t)s->rows, c->units, c->description);
    } else if (c->attrs_new) {
      rewrite_attr(w, c->ds, "units", c->units);
      rewrite_attr(w, c->ds, "description", c->description);
      c->attrs_new = 0;
    }
  }
}

/* grow `ds` to row + 1 entries and write `value` (of memory type `type`) at `row` */
static void write_entry(mrn_h5w *w, hid_t ds, const char *name, hid_t type, const void *value, hsize_t row) {
  if (!begin(w)) return;
  hsize_t size = row + 1, one = 1;
  hid_t fs = H5I_INVALID_HID, ms = H5I_INVALID_HID;
  int ok = H5Dset_extent(ds, &size) >= 0 && (fs = H5Dget_space(ds)) >= 0 &&
           H5Sselect_hyperslab(fs, H5S_SELECT_SET, &row, NULL, &one, NULL) >= 0 &&
           (ms = H5Screate_simple(1, &one, NULL)) >= 0 && H5Dwrite(ds, type, ms, fs, H5P_DEFAULT, value) >= 0;
  if (fs >= 0) H5Sclose(fs);
  if (ms >= 0) H5Sclose(ms);
  if (!ok) note_fail(w, "dataset /%s", name);
}

static int append(mrn_series *s, long step, double time) {
  if (s->broken) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': an earlier write failed", s->path);
  mrn_h5w w = {.file = s->file};
  const hsize_t row = (hsize_t)s->rows;
  const int64_t step64 = step;
  sync_columns(s, &w);
  write_entry(&w, s->time_ds, "time", H5T_NATIVE_DOUBLE, &time, row);
  write_entry(&w, s->step_ds, "step", H5T_NATIVE_INT64, &step64, row);
  for (int i = 0; i < s->ncol; i++)
    write_entry(&w, s->cols[i].ds, s->cols[i].name, H5T_NATIVE_DOUBLE, &s->cols[i].pending, row);
  /* the row reaches the file whole before the call returns: what makes the
   * file readable while the run goes on, and after it is killed */
  if (begin(&w) && H5Fflush(s->file, H5F_SCOPE_LOCAL) < 0) note_fail(&w, "%s", "the file (flushing it)");
  if (w.failed) {
    s->broken = 1;
    return report(&w, s->path);
  }
  s->rows++;
  for (int i = 0; i < s->ncol; i++) s->cols[i].pending = NAN;
  return MRN_OK;
}

int mrn_series_append(mrn_series *s, long step, double time) {
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  int rc = append(s, step, time);
  mrn_h5_restore(&quiet);
  return rc;
}

/* ---- queries and closing ---------------------------------------------------------- */

long mrn_series_rows(const mrn_series *s) { return s ? s->rows : 0; }
int mrn_series_column_count(const mrn_series *s) { return s ? s->ncol : 0; }
const char *mrn_series_column_name(const mrn_series *s, int column) {
  return s && column >= 0 && column < s->ncol ? s->cols[column].name : NULL;
}

int mrn_series_close(mrn_series *s) {
  if (!s) return MRN_OK;
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  int rc = MRN_OK;
  mrn_h5w w = {.file = s->file};
  /* columns named but never given a row still appear, empty */
  if (s->file >= 0 && !s->broken) sync_columns(s, &w);
  for (int i = 0; i < s->ncol; i++)
    if (s->cols[i].ds >= 0) H5Dclose(s->cols[i].ds);
  if (s->time_ds >= 0) H5Dclose(s->time_ds);
  if (s->step_ds >= 0) H5Dclose(s->step_ds);
  if (s->file >= 0) {
    errno = 0;
    if (H5Fclose(s->file) < 0) note_fail(&w, "%s", "the file (closing it)");
  }
  if (w.failed) rc = report(&w, s->path);
  mrn_h5_restore(&quiet);
  release(s);
  return rc;
}
