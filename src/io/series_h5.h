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
 * Every dataset carries `units` and `description` attributes (fixed-length
 * UTF-8 strings; h5py gives bytes, .decode() gives the text); the root group
 * carries `format` = "moraine-series", `version` and `moraine_version`. The
 * datasets are chunked with an unlimited maximum size and a fill value of NaN.
 *
 * Rows are staged and then appended: mrn_series_set() gives a value for the
 * next row, mrn_series_append() writes the row. A column that gets no value
 * for a row holds NaN there, and a column first named after some rows exist
 * holds NaN for the earlier rows, so values recorded from Lua can come and go
 * by name. Columns are kept in memory until the next append (or the close)
 * creates their datasets: the open file changes only inside
 * mrn_series_append() and mrn_series_close().
 *
 * Crash-safety: the empty file is created under a temporary name and renamed
 * into place (io/atomic_file.h), so it is never seen half made. After that
 * the file is appended in place (HDF5's single-writer/multiple-reader mode is
 * not needed): every mrn_series_append() creates the new columns, extends all
 * datasets, writes the row and flushes the file (H5Fflush), so between
 * appends the file on disk is complete and consistent, and a reader opening
 * it then (or after the run is killed) sees every appended row. A kill
 * during an append itself (an append of 30 columns takes about 0.1 ms) can
 * leave datasets of unequal length (a reader should take the shortest) or,
 * rarely, a file HDF5 cannot open; the CSV of the same values is then the
 * fallback. HDF5's file locking is turned off for this file so that readers
 * can open it while the run holds it open. */
#ifndef MRN_IO_SERIES_H5_H
#define MRN_IO_SERIES_H5_H

typedef struct mrn_series mrn_series;

/* Create the series file at `path` (an existing file is replaced), with no
 * columns and no rows. The directory must exist. 0 or MRN_ERR_IO; on success
 * *out holds the series, to be closed with mrn_series_close(). */
int mrn_series_create(mrn_series **out, const char *path);

/* Declare a column before any value is set for it, so it has units, a
 * description and its place in the order (its dataset appears with the next
 * append, or at the close). Declaring a name that exists updates its units
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

/* Append the staged row at (step, time): every dataset grows by one entry,
 * columns without a value get NaN, and the file is flushed. The staged values
 * are cleared. 0 or MRN_ERR_IO; after a failure the series refuses further
 * appends (the file may have been left part-way). */
int mrn_series_append(mrn_series *s, long step, double time);

/* rows appended so far; columns and their names in order */
long mrn_series_rows(const mrn_series *s);
int mrn_series_column_count(const mrn_series *s);
const char *mrn_series_column_name(const mrn_series *s, int column);
/* the index of column `name`, or -1 */
int mrn_series_find(const mrn_series *s, const char *name);

/* Close the file and free the series (NULL is fine). Values set since the
 * last append are dropped. 0 or MRN_ERR_IO if closing failed. */
int mrn_series_close(mrn_series *s);

#endif
