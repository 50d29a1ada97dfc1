/* moraine: crash-safe output files.
 *
 * A file is written under a temporary name in the same directory
 * (`.NAME.tmp.PID`) and renamed over its final name only when it is complete
 * and flushed to disk, so a reader (or a crash) only ever sees a whole file or
 * no file. */
#ifndef MRN_IO_ATOMIC_FILE_H
#define MRN_IO_ATOMIC_FILE_H

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

typedef struct mrn_atomic_file {
  FILE *fp;
  char *final_path;
  char *temp_path;
  int err; /* errno of the first failed write, 0 while all is well */
} mrn_atomic_file;

/* open a temporary file for `path`; returns 0 or an MRN_ERR_IO code with the
 * path in the message. In a distributed run (core/comm.h) only process 0
 * writes the file: the others write into /dev/null and put nothing in place. */
int mrn_atomic_open(mrn_atomic_file *f, const char *path);
/* the same, written by this process whichever it is: a file of its own, as
 * the pieces of a distributed snapshot (io/vtk.h) */
int mrn_atomic_open_own(mrn_atomic_file *f, const char *path);

/* Write through the stream. The first failure keeps its errno in f->err
 * (a stream loses it by the next call) and later writes are skipped: the
 * file is lost anyway, and mrn_atomic_commit reports that errno. */
void mrn_atomic_write(mrn_atomic_file *f, const void *data, size_t size);
void mrn_atomic_printf(mrn_atomic_file *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void mrn_atomic_vprintf(mrn_atomic_file *f, const char *fmt, va_list ap);

/* flush, fsync, close and rename into place; on any failure (f->err
 * included) the temporary file is removed and MRN_ERR_IO returned with the
 * path and reason */
int mrn_atomic_commit(mrn_atomic_file *f);
/* close and remove the temporary file (after an error) */
void mrn_atomic_abort(mrn_atomic_file *f);

/* `size` bytes as the whole file `path`, through a temporary file as above;
 * 0 or MRN_ERR_IO */
int mrn_atomic_write_file(const char *path, const void *data, size_t size);

/* create a directory and its parents (like mkdir -p); 0 or MRN_ERR_IO */
int mrn_mkdir_p(const char *path);
/* join dir and name with a '/', returning a malloc'd string */
char *mrn_path_join(const char *dir, const char *name);

#endif
