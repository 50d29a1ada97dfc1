/* moraine: one run at a time in an output directory.
 *
 * A run holds OUTDIR/.moraine.lock while it writes there: the file holds its
 * process id and is flock()ed. A second run into the same directory finds
 * the lock held and is refused, naming the process. A lock file left by a
 * process that died without removing it (SIGKILL, a second Ctrl-C) is not
 * held by anyone: the next run takes it over, with a warning naming the
 * dead process. */
#ifndef MRN_IO_DIRLOCK_H
#define MRN_IO_DIRLOCK_H

#define MRN_DIRLOCK_NAME ".moraine.lock"

typedef struct mrn_dirlock {
  int fd; /* -1 when not held */
  char *path;
} mrn_dirlock;

/* Take the lock of directory `dir` (which must exist). 0, or MRN_ERR with a
 * message naming the process that holds it, or MRN_ERR_IO when the lock
 * file cannot be written. */
int mrn_dirlock_take(mrn_dirlock *lock, const char *dir);
/* remove the lock file and let go (a lock not held is fine) */
void mrn_dirlock_release(mrn_dirlock *lock);

#endif
