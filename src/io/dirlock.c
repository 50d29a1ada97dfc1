#include "io/dirlock.h"
#include "core/comm.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"
#include "core/log.h"
#include "io/atomic_file.h"

/* the process id written in the lock file, 0 if none */
static long lock_owner(int fd) {
  char buf[32] = "";
  ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  if (n <= 0) return 0;
  buf[n] = '\0';
  return strtol(buf, NULL, 10);
}

/* the open file is still the one at `path`: a run that ended removes its
 * lock file after others may have opened it, and a lock on a removed file
 * guards nothing */
static int still_linked(int fd, const char *path) {
  struct stat a, b;
  return fstat(fd, &a) == 0 && stat(path, &b) == 0 && a.st_ino == b.st_ino && a.st_dev == b.st_dev;
}

static int held_by_other(mrn_dirlock *lock, const char *dir, int fd) {
  long pid = lock_owner(fd);
  close(fd);
  free(lock->path);
  lock->path = NULL;
  return mrn_error("the output directory '%s' is in use by another moraine run (process %ld, lock file '%s/%s'): "
                   "wait for it to end or use another -o directory", dir, pid, dir, MRN_DIRLOCK_NAME);
}

int mrn_dirlock_take(mrn_dirlock *lock, const char *dir) {
  lock->fd = -1;
  lock->path = NULL;
  if (!mrn_comm_writes()) return MRN_OK; /* process 0 holds the directory for the whole run */
  lock->path = mrn_path_join(dir, MRN_DIRLOCK_NAME);
  for (int attempt = 0; attempt < 100; attempt++) {
    int fd = open(lock->path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      int rc = mrn_error_code(MRN_ERR_IO, "cannot write the lock file '%s': %s", lock->path, strerror(errno));
      free(lock->path);
      lock->path = NULL;
      return rc;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) return held_by_other(lock, dir, fd);
    if (!still_linked(fd, lock->path)) {
      close(fd);
      continue;
    }
    long stale = lock_owner(fd);
    if (stale > 0 && stale != (long)getpid())
      mrn_warn("took over the lock file '%s' of process %ld, which ended without removing it",
                  lock->path, stale);
    char pid[32];
    int len = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, pid, (size_t)len, 0) != len) {
      int rc = mrn_error_code(MRN_ERR_IO, "cannot write the lock file '%s': %s", lock->path, strerror(errno));
      close(fd);
      free(lock->path);
      lock->path = NULL;
      return rc;
    }
    lock->fd = fd;
    return MRN_OK;
  }
  return mrn_error("cannot take the lock file '%s': it keeps being replaced", lock->path);
}

void mrn_dirlock_release(mrn_dirlock *lock) {
  if (lock->fd >= 0) {
    unlink(lock->path); /* while still held: no other run can be between its open and its flock on this file */
    close(lock->fd);
  }
  lock->fd = -1;
  free(lock->path);
  lock->path = NULL;
}
