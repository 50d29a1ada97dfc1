#include "io/series_h5.h"

#include <errno.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/h5image.h"
#include "io/h5util.h"

#define SERIES_FORMAT "moraine-series"
#define SERIES_VERSION 1

/* Rows per chunk of the datasets in the file (4 KiB of doubles). */
#define CHUNK_ROWS 512

/* A publication (the whole file written under a temporary name and renamed
 * into place) is made at an append only when the time since the last one is
 * at least this many times what the last one cost: the rewrites then take at
 * most 1/(1 + PUBLISH_RATIO) of the run's wall time, however long the series. */
#define PUBLISH_RATIO 20.0

/* Every value lives in memory; the file on disk is a copy, rewritten whole. */
typedef struct column {
  char *name, *units, *description;
  double *values; /* `rows` entries (NaN where the column had no value) */
  double pending; /* the value for the next row (NaN: none given) */
} column;

struct mrn_series {
  char *path;
  column *cols;
  int ncol, cap;
  long rows, row_cap;
  double *time;
  int64_t *step;
  int dirty;                   /* appended or declared since the last publication */
  double last_end, last_cost;  /* wall clock at the end of the last publication, and its cost (s) */
  int broken;                  /* a publication failed: no more writes */
  char *run_name, *deck_path, *deck; /* root attributes, or NULL */
};

static double wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* ---- failures --------------------------------------------------------------- */

/* Remember what failed and errno at that moment (the file is built in
 * memory, so ENOMEM if anything); HDF5 calls are made with errno cleared
 * first, see begin(). */
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

/* ---- datasets ----------------------------------------------------------------- */

/* A 1D dataset of `rows` entries holding `data`, chunked with an unlimited
 * maximum size (a reader may extend or append to a copy) and NaN as the fill
 * value of the float columns. */
static hid_t write_dataset(mrn_h5w *w, hid_t file, const char *name, hid_t type, hid_t mem_type, hsize_t rows,
                           const void *data, const char *units, const char *description) {
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
  int ok = ds >= 0 && (rows == 0 || H5Dwrite(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0);
  if (space >= 0) H5Sclose(space);
  if (dcpl >= 0) H5Pclose(dcpl);
  if (!ok) note_fail(w, "dataset /%s", name);
  if (ds >= 0) {
    mrn_h5w_string(w, ds, "units", units ? units : "");
    mrn_h5w_string(w, ds, "description", description ? description : "");
  }
  return ds;
}

/* Every dataset is indexed by the row: /time becomes the dimension scale of
 * that axis (HDF5's H5DS, the form netCDF-4 gives a coordinate variable), so
 * xarray and netCDF readers see one dimension `time` with its values instead
 * of an anonymous axis per dataset. The dataset is closed here. */
static void attach_time(mrn_h5w *w, hid_t time, hid_t ds, const char *name) {
  if (ds < 0) return;
  if (!w->failed && time >= 0 && H5DSattach_scale(ds, time, 0) < 0) note_fail(w, "dimension scale of /%s", name);
  H5Dclose(ds);
}

/* ---- publishing the file ------------------------------------------------------ */

/* the whole series into a new file in memory (io/h5image.h); its bytes, or NULL */
static void *build_image(mrn_h5w *w, const mrn_series *s, size_t *size) {
  hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
  /* datasets listed in the order added (h5dump --sort_by=creation_order) */
  if (fcpl >= 0) H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
  mrn_h5_image img;
  errno = 0;
  w->file = mrn_h5_image_create(&img, s->path, fcpl >= 0 ? fcpl : H5P_DEFAULT);
  if (fcpl >= 0) H5Pclose(fcpl);
  if (w->file < 0) {
    note_fail(w, "%s", "the file");
    return NULL;
  }
  mrn_h5w_string(w, w->file, "format", SERIES_FORMAT);
  mrn_h5w_int32(w, w->file, "version", SERIES_VERSION);
  mrn_h5w_string(w, w->file, "moraine_version", MORAINE_VERSION " (" MORAINE_GIT_COMMIT ")");
  mrn_h5w_string(w, w->file, "description",
                 "time series: one entry per row in every dataset; NaN where a column had no value");
  if (s->run_name) mrn_h5w_string(w, w->file, "run_name", s->run_name);
  if (s->deck_path) mrn_h5w_string(w, w->file, "deck_path", s->deck_path);
  if (s->deck) mrn_h5w_string(w, w->file, "deck", s->deck);
  const hsize_t rows = (hsize_t)s->rows;
  hid_t time = write_dataset(w, w->file, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, rows, s->time, "s",
                             "model time of the row");
  if (time >= 0 && !w->failed && H5DSset_scale(time, "time") < 0) note_fail(w, "%s", "dimension scale /time");
  attach_time(w, time, write_dataset(w, w->file, "step", H5T_STD_I64LE, H5T_NATIVE_INT64, rows, s->step, "",
                                     "step number of the row"), "step");
  for (int i = 0; i < s->ncol; i++)
    attach_time(w, time, write_dataset(w, w->file, s->cols[i].name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, rows,
                                       s->cols[i].values, s->cols[i].units, s->cols[i].description), s->cols[i].name);
  if (time >= 0) H5Dclose(time);
  void *bytes;
  errno = 0;
  if (mrn_h5_image_close(&img, w->file, &bytes, size) != 0) note_fail(w, "%s", "the file (closing it)");
  w->file = H5I_INVALID_HID;
  if (w->failed) {
    free(bytes);
    return NULL;
  }
  return bytes;
}

/* The file on disk is always a whole series, the previous publication or
 * this one: the new one is built in memory and written through
 * mrn_atomic_write_file, renamed into place only when complete. */
static int publish(mrn_series *s) {
  if (s->broken) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': an earlier write failed", s->path);
  const double t0 = wall_seconds();
  mrn_h5w w = {.file = H5I_INVALID_HID};
  size_t size;
  void *bytes = build_image(&w, s, &size);
  int rc = bytes ? mrn_atomic_write_file(s->path, bytes, size) : mrn_h5w_report(&w, s->path);
  free(bytes);
  if (rc != MRN_OK) {
    s->broken = 1;
    return rc;
  }
  s->dirty = 0;
  s->last_end = wall_seconds();
  s->last_cost = s->last_end - t0;
  return MRN_OK;
}

static int publish_quietly(mrn_series *s) {
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  int rc = publish(s);
  mrn_h5_restore(&quiet);
  return rc;
}

static void release(mrn_series *s) {
  for (int i = 0; i < s->ncol; i++) {
    free(s->cols[i].name);
    free(s->cols[i].units);
    free(s->cols[i].description);
    free(s->cols[i].values);
  }
  free(s->cols);
  free(s->time);
  free(s->step);
  free(s->path);
  free(s->run_name);
  free(s->deck_path);
  free(s->deck);
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
  int rc = publish_quietly(s); /* the empty series, so the file exists from the start */
  if (rc != MRN_OK) {
    release(s);
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

/* room for `rows` rows in every array; new entries of the columns are NaN */
static int grow_rows(mrn_series *s, long rows) {
  if (rows <= s->row_cap) return 0;
  long cap = s->row_cap ? 2 * s->row_cap : 256;
  while (cap < rows) cap *= 2;
  double *time = realloc(s->time, (size_t)cap * sizeof *time);
  if (time) s->time = time;
  int64_t *step = realloc(s->step, (size_t)cap * sizeof *step);
  if (step) s->step = step;
  if (!time || !step) return -1;
  for (int i = 0; i < s->ncol; i++) {
    double *v = realloc(s->cols[i].values, (size_t)cap * sizeof *v);
    if (!v) return -1;
    for (long r = s->row_cap; r < cap; r++) v[r] = NAN;
    s->cols[i].values = v;
  }
  s->row_cap = cap;
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
    double *values = malloc((size_t)(s->row_cap ? s->row_cap : 1) * sizeof *values);
    if (!copy || !values || grow_columns(s) != 0) {
      free(copy);
      free(values);
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", s->path);
    }
    for (long r = 0; r < s->row_cap; r++) values[r] = NAN; /* the rows before it existed */
    idx = s->ncol++;
    s->cols[idx] = (column){copy, NULL, NULL, values, NAN};
    s->dirty = 1;
  }
  column *c = &s->cols[idx];
  if (take_text(&c->units, units, &s->dirty) != 0 || take_text(&c->description, description, &s->dirty) != 0)
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", s->path);
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

int mrn_series_append(mrn_series *s, long step, double time) {
  if (s->broken) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': an earlier write failed", s->path);
  if (grow_rows(s, s->rows + 1) != 0) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", s->path);
  const long r = s->rows++;
  s->time[r] = time;
  s->step[r] = step;
  for (int i = 0; i < s->ncol; i++) {
    s->cols[i].values[r] = s->cols[i].pending;
    s->cols[i].pending = NAN;
  }
  s->dirty = 1;
  if (wall_seconds() - s->last_end < PUBLISH_RATIO * s->last_cost) return MRN_OK; /* published soon */
  return publish_quietly(s);
}

int mrn_series_flush(mrn_series *s) {
  if (!s || (!s->dirty && !s->broken)) return MRN_OK;
  return publish_quietly(s);
}

/* a copy of text into *slot (NULL: none); 0, or -1 out of memory */
static int replace_text(char **slot, const char *text) {
  char *copy = text ? strdup(text) : NULL;
  if (text && !copy) return -1;
  free(*slot);
  *slot = copy;
  return 0;
}

int mrn_series_describe(mrn_series *s, const char *run_name, const char *deck_path, const char *deck) {
  s->dirty = 1;
  if (replace_text(&s->run_name, run_name) != 0 || replace_text(&s->deck_path, deck_path) != 0 ||
      replace_text(&s->deck, deck) != 0)
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", s->path);
  return MRN_OK;
}

/* ---- queries and closing ---------------------------------------------------------- */

long mrn_series_rows(const mrn_series *s) { return s ? s->rows : 0; }
int mrn_series_column_count(const mrn_series *s) { return s ? s->ncol : 0; }
const char *mrn_series_column_name(const mrn_series *s, int column) {
  return s && column >= 0 && column < s->ncol ? s->cols[column].name : NULL;
}

double mrn_series_pending(const mrn_series *s, int column) {
  return s && column >= 0 && column < s->ncol ? s->cols[column].pending : NAN;
}

int mrn_series_close(mrn_series *s) {
  if (!s) return MRN_OK;
  /* columns named but never given a row still appear, empty */
  int rc = s->dirty && !s->broken ? publish_quietly(s) : MRN_OK;
  release(s);
  return rc;
}

/* ---- continuing a series from its file ---------------------------------------------- */

/* the 1D dataset `name` of `rows` entries (at least) into values[0 .. keep) */
static int read_column(hid_t file, const char *name, hid_t mem_type, long keep, void *values) {
  hid_t ds = H5Dopen2(file, name, H5P_DEFAULT);
  if (ds < 0) return -1;
  hid_t space = H5Dget_space(ds);
  hsize_t dims[2] = {0, 0};
  int ok = space >= 0 && H5Sget_simple_extent_ndims(space) == 1 && H5Sget_simple_extent_dims(space, dims, NULL) == 1 &&
           dims[0] >= (hsize_t)keep;
  if (ok && keep > 0) {
    hsize_t start = 0, count = (hsize_t)keep;
    hid_t mem = H5Screate_simple(1, &count, NULL);
    ok = mem >= 0 && H5Sselect_hyperslab(space, H5S_SELECT_SET, &start, NULL, &count, NULL) >= 0 &&
         H5Dread(ds, mem_type, mem, space, H5P_DEFAULT, values) >= 0;
    if (mem >= 0) H5Sclose(mem);
  }
  if (space >= 0) H5Sclose(space);
  H5Dclose(ds);
  return ok ? 0 : -1;
}

/* an attribute string of `obj` (dataset name or "." for the root), or NULL */
static char *read_text(hid_t file, const char *obj, const char *name) {
  if (H5Aexists_by_name(file, obj, name, H5P_DEFAULT) <= 0) return NULL;
  hid_t a = H5Aopen_by_name(file, obj, name, H5P_DEFAULT, H5P_DEFAULT);
  hid_t t = a >= 0 ? H5Aget_type(a) : H5I_INVALID_HID;
  char *text = NULL;
  if (t >= 0 && H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) == 0) {
    size_t size = H5Tget_size(t);
    text = calloc(size + 1, 1);
    if (text && H5Aread(a, t, text) < 0) text[0] = '\0';
  }
  if (t >= 0) H5Tclose(t);
  if (a >= 0) H5Aclose(a);
  return text;
}

typedef struct reopen_ctx {
  mrn_series *s;
  long keep;
  int failed;
} reopen_ctx;

/* every dataset of the root but time and step is a column, in creation order */
static herr_t reopen_column(hid_t file, const char *name, const H5L_info_t *info, void *user) {
  (void)info;
  reopen_ctx *c = user;
  if (!strcmp(name, "time") || !strcmp(name, "step")) return 0;
  hid_t o = H5Oopen(file, name, H5P_DEFAULT);
  H5I_type_t type = o >= 0 ? H5Iget_type(o) : H5I_BADID;
  if (o >= 0) H5Oclose(o);
  if (type != H5I_DATASET) return 0;
  char *units = read_text(file, name, "units"), *description = read_text(file, name, "description");
  int rc = mrn_series_add_column(c->s, name, units, description);
  free(units), free(description);
  if (rc == MRN_OK && read_column(file, name, H5T_NATIVE_DOUBLE, c->keep, c->s->cols[c->s->ncol - 1].values) == 0)
    return 0;
  c->failed = 1;
  return -1;
}

/* the first `keep` rows of the file into the empty series s */
static int reopen_rows(mrn_series *s, hid_t file, long keep) {
  if (grow_rows(s, keep > 0 ? keep : 1) != 0) return -1;
  if (read_column(file, "time", H5T_NATIVE_DOUBLE, keep, s->time) != 0 ||
      read_column(file, "step", H5T_NATIVE_INT64, keep, s->step) != 0)
    return -1;
  reopen_ctx c = {s, keep, 0};
  hsize_t idx = 0;
  if (H5Literate(file, H5_INDEX_CRT_ORDER, H5_ITER_INC, &idx, reopen_column, &c) < 0) {
    idx = 0; /* a file written without creation order: by name */
    if (c.failed || H5Literate(file, H5_INDEX_NAME, H5_ITER_INC, &idx, reopen_column, &c) < 0) return -1;
  }
  s->rows = keep;
  s->run_name = read_text(file, ".", "run_name");
  s->deck = read_text(file, ".", "deck");
  return 0;
}

int mrn_series_reopen(mrn_series **out, const char *path, long keep) {
  *out = NULL;
  mrn_series *s = calloc(1, sizeof *s);
  if (!s || !(s->path = strdup(path))) {
    free(s);
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", path);
  }
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  int bad = file < 0 || reopen_rows(s, file, keep) != 0;
  if (file >= 0) H5Fclose(file);
  mrn_h5_restore(&quiet);
  if (bad) {
    release(s);
    return mrn_error_code(MRN_ERR_IO, "cannot continue the series '%s': it is not a series of at least %ld rows",
                          path, keep);
  }
  int rc = publish_quietly(s); /* the rows after `keep` are gone from the file too */
  if (rc != MRN_OK) {
    release(s);
    return rc;
  }
  *out = s;
  return MRN_OK;
}
