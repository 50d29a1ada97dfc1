/* moraine: time series in an HDF5 file (diagnostics and values recorded from
 * Lua), readable with h5py or h5dump while the simulation runs.
 *
 * Layout: in the root group, one extendable 1D dataset per column, all of the
 * same length (one entry per row):
 *
 *   /time     float64, units "s"     the model time of each row
 *   /step     int64                  the step number of each row
 *   /<name>   float64                one per column, in the order added
 *
 * /time is the HDF5 dimension scale of the row axis, attached to every other
 * dataset, as netCDF-4 stores a coordinate: xarray
 * (`xarray.open_dataset(path, engine="h5netcdf")`) reads the file as
 * variables over one dimension `time`.
 *
 * Every dataset carries `units` and `description` attributes (fixed-length
 * UTF-8 strings; h5py gives bytes, .decode() gives the text); the root group
 * carries `format` = "moraine-series", `version`, `moraine_version`,
 * `description`, and `run_name`, `deck_path` and `deck` when given
 * (mrn_series_describe). The datasets are chunked (512 rows) with an unlimited
 * maximum size and a fill value of NaN.
 *
 * Rows are staged and then appended: mrn_series_set() gives a value for the
 * next row, mrn_series_append() adds the row. A column that gets no value
 * for a row holds NaN there, and a column first named after some rows exist
 * holds NaN for the earlier rows, so values recorded from Lua can come and go
 * by name.
 *
 * Crash-safety: the series is kept in memory and the file is a copy of it,
 * built in memory (io/h5image.h) and written whole under a temporary name
 * (`.NAME.tmp.PID`, io/atomic_file.h), fsynced and renamed over NAME. A reader, or a run killed at any instant
 * (SIGKILL included), therefore finds either no file or a complete series
 * that HDF5 opens, never a half-written one; a kill during a rewrite can
 * leave the hidden temporary file, which no reader looks at. The file is
 * rewritten at an append when the wall time since the last rewrite is at
 * least 20 times what that rewrite cost (so rewriting costs at most about 5 %
 * of the run, however long the series grows), at mrn_series_flush() and at
 * the close: while a run goes on, the file may lag the appended rows by that
 * interval (a few milliseconds for a short series; the CSV beside it is
 * written row by row). Memory: 8 bytes per value, rows x (columns + 2), and
 * the size of the file again while a rewrite is built. */
#ifndef MRN_IO_SERIES_H5_H
#define MRN_IO_SERIES_H5_H

typedef struct mrn_series mrn_series;

/* Create the series file at `path` (an existing file is replaced), with no
 * columns and no rows. The directory must exist. 0 or MRN_ERR_IO; on success
 * *out holds the series, to be closed with mrn_series_close(). */
int mrn_series_create(mrn_series **out, const char *path);

/* Continue the series in the file at `path`, written by mrn_series_create:
 * its columns (with their units and descriptions, in their order), its root
 * attributes run_name and deck, and its first `keep` rows; the file is
 * rewritten with those rows only, and later appends follow them. 0, or
 * MRN_ERR_IO when the file is not such a series or holds fewer rows. */
int mrn_series_reopen(mrn_series **out, const char *path, long keep);

/* Declare a column before any value is set for it, so it has units, a
 * description and its place in the order (its dataset appears with the next
 * rewrite of the file). Declaring a name that exists updates its units
 * and description where these are given (non-NULL, non-empty). Names are
 * non-empty, contain no '/', and are neither "time", "step" nor ".".
 * 0, MRN_ERR (bad name, message set) or MRN_ERR_IO (out of memory). */
int mrn_series_add_column(mrn_series *s, const char *name, const char *units, const char *description);

/* The value of column `name` for the next row; a new name declares a column
 * with no units. Setting a column twice before the append keeps the last
 * value. 0, MRN_ERR (bad name) or MRN_ERR_IO. */
int mrn_series_set(mrn_series *s, const char *name, double value);
/* the same by column index (0 = the first column added); MRN_ERR if out of range */
int mrn_series_set_at(mrn_series *s, int column, double value);

/* Append the staged row at (step, time): every column grows by one entry,
 * columns without a value get NaN; the file is rewritten if one is due (see
 * above). The staged values are cleared. 0 or MRN_ERR_IO; after a failed
 * rewrite the series refuses further appends (the file on disk stays the
 * last complete one). */
int mrn_series_append(mrn_series *s, long step, double time);
/* Rewrite the file now if anything changed since the last rewrite: every
 * appended row is then on disk. 0 or MRN_ERR_IO. */
int mrn_series_flush(mrn_series *s);

/* The run's name, its deck's path and the deck's text, stored as the root
 * attributes `run_name`, `deck_path` and `deck` from the next rewrite on
 * (NULL: none). 0 or MRN_ERR_IO (out of memory). */
int mrn_series_describe(mrn_series *s, const char *run_name, const char *deck_path, const char *deck);

/* rows appended so far; columns and their names in order */
long mrn_series_rows(const mrn_series *s);
int mrn_series_column_count(const mrn_series *s);
const char *mrn_series_column_name(const mrn_series *s, int column);
/* the value set for the next row of a column, NaN when none */
double mrn_series_pending(const mrn_series *s, int column);
/* the index of column `name`, or -1 */
int mrn_series_find(const mrn_series *s, const char *name);

/* Close the file and free the series (NULL is fine). Values set since the
 * last append are dropped. 0 or MRN_ERR_IO if closing failed. */
int mrn_series_close(mrn_series *s);

#endif
