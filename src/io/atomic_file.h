/* moraine: crash-safe output files.
 *
 * A file is written under a temporary name in the same directory
 * (`.NAME.tmp.PID`) and renamed over its final name only when it is complete
 * and flushed to disk, so a reader (or a crash) only ever sees a whole file or
 * no file. */
#ifndef MRN_IO_ATOMIC_FILE_H
#define MRN_IO_ATOMIC_FILE_H

#include <stdio.h>

typedef struct mrn_atomic_file {
  FILE *fp;
  char *final_path;
  char *temp_path;
} mrn_atomic_file;

/* open a temporary file for `path`; returns 0 or an MRN_ERR_IO code with the path in the message */
int mrn_atomic_open(mrn_atomic_file *f, const char *path);
/* flush, fsync, close and rename into place; on any failure the temporary
 * file is removed and MRN_ERR_IO returned with the path and reason */
int mrn_atomic_commit(mrn_atomic_file *f);
/* close and remove the temporary file (after an error) */
void mrn_atomic_abort(mrn_atomic_file *f);

/* create a directory and its parents (like mkdir -p); 0 or MRN_ERR_IO */
int mrn_mkdir_p(const char *path);
/* join dir and name with a '/', returning a malloc'd string */
char *mrn_path_join(const char *dir, const char *name);

#endif
