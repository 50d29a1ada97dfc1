#include "io/atomic_file.h"
#include "core/comm.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "core/error.h"
#include "io/summary.h"

/* ---- temporary name ---------------------------------------------------- */

/* `.<basename>.tmp.<pid>` next to the final path: the same directory means
 * the same file system, so the final rename is atomic; the leading dot keeps
 * it out of ParaView's file dialogs and of `*.vtp` globs; the pid keeps two
 * moraine processes writing into one directory apart. */
static char *temp_name_for(const char *path) {
  const char *slash = strrchr(path, '/');
  size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
  const char *base = path + dir_len;
  size_t len = dir_len + 1 + strlen(base) + 32;
  char *temp = malloc(len);
  if (!temp) return NULL;
  snprintf(temp, len, "%.*s.%s.tmp.%ld", (int)dir_len, path, base, (long)getpid());
  return temp;
}

static void release(mrn_atomic_file *f) {
  free(f->final_path);
  free(f->temp_path);
  f->fp = NULL;
  f->final_path = NULL;
  f->temp_path = NULL;
}

/* ---- open / write / commit / abort ------------------------------------- */

/* writes: 1 on the process that puts the file in place, 0 on those that
 * go through the same calls into /dev/null */
static int open_as(mrn_atomic_file *f, const char *path, int writes) {
  f->fp = NULL;
  f->final_path = NULL;
  f->temp_path = NULL;
  f->err = 0;
  if (!path || !*path || path[strlen(path) - 1] == '/')
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': not a file name", path ? path : "");
  f->final_path = strdup(path);
  if (!writes) {
    f->fp = f->final_path ? fopen("/dev/null", "wb") : NULL;
    if (!f->fp) release(f);
    return f->fp ? MRN_OK : mrn_error_code(MRN_ERR_IO, "cannot open /dev/null");
  }
  f->temp_path = temp_name_for(path);
  if (!f->final_path || !f->temp_path) {
    release(f);
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", path);
  }
  f->fp = fopen(f->temp_path, "wb");
  if (!f->fp) {
    int rc = mrn_error_code(MRN_ERR_IO, "cannot write '%s': %s", path, strerror(errno));
    release(f);
    return rc;
  }
  return MRN_OK;
}

/* process 0 writes the files of a distributed run */
int mrn_atomic_open(mrn_atomic_file *f, const char *path) { return open_as(f, path, mrn_comm_writes()); }

int mrn_atomic_open_own(mrn_atomic_file *f, const char *path) { return open_as(f, path, 1); }

/* A stream may take the bytes into its buffer and still fail the write that
 * empties it: the error flag is checked after every call, while errno still
 * belongs to that write. */
static void check_stream(mrn_atomic_file *f, int failed) {
  if ((failed || ferror(f->fp)) && !f->err) f->err = errno ? errno : EIO;
}

void mrn_atomic_write(mrn_atomic_file *f, const void *data, size_t size) {
  if (f->err || !f->fp || size == 0) return;
  errno = 0;
  check_stream(f, fwrite(data, 1, size, f->fp) != size);
}

void mrn_atomic_vprintf(mrn_atomic_file *f, const char *fmt, va_list ap) {
  if (f->err || !f->fp) return;
  errno = 0;
  check_stream(f, vfprintf(f->fp, fmt, ap) < 0);
}

void mrn_atomic_printf(mrn_atomic_file *f, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  mrn_atomic_vprintf(f, fmt, ap);
  va_end(ap);
}

/* Push everything the stream holds to the disk. A stream error flag set by an
 * earlier write has lost its errno by now, so it is reported as EIO unless
 * errno still says something more precise. */
static int flush_to_disk(FILE *fp) {
  if (ferror(fp)) return errno ? errno : EIO;
  if (fflush(fp) != 0) return errno ? errno : EIO;
  /* some file systems cannot sync (EINVAL); the data is still complete */
  if (fsync(fileno(fp)) != 0 && errno != EINVAL && errno != ENOTSUP) return errno;
  return 0;
}

/* Best effort: make the rename itself durable. A failure here does not make
 * the file wrong, only possibly older after a power cut, so it is ignored. */
static void sync_parent_dir(const char *path) {
  const char *slash = strrchr(path, '/');
  char *dir = slash ? strndup(path, (size_t)(slash - path) + 1) : strdup(".");
  if (!dir) return;
  int fd = open(dir, O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    (void)fsync(fd);
    close(fd);
  }
  free(dir);
}

int mrn_atomic_commit(mrn_atomic_file *f) {
  if (!f->fp) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': file is not open",
                                    f->final_path ? f->final_path : "");
  errno = 0;
  int err = f->err ? f->err : flush_to_disk(f->fp);
  /* fclose must run in every case to release the stream; its own failure
   * (a delayed write error on some file systems) counts as well */
  if (fclose(f->fp) != 0 && !err) err = errno ? errno : EIO;
  f->fp = NULL;
  if (!f->temp_path) { /* not the writing process: nothing to put in place */
    release(f);
    return MRN_OK;
  }
  if (err) {
    int rc = mrn_error_code(MRN_ERR_IO, "cannot write '%s': %s", f->final_path, strerror(err));
    unlink(f->temp_path);
    release(f);
    return rc;
  }
  if (rename(f->temp_path, f->final_path) != 0) {
    int rc = mrn_error_code(MRN_ERR_IO, "cannot write '%s': rename from '%s' failed: %s", f->final_path,
                            f->temp_path, strerror(errno));
    unlink(f->temp_path);
    release(f);
    return rc;
  }
  sync_parent_dir(f->final_path);
  mrn_summary_note_file(f->final_path);
  release(f);
  return MRN_OK;
}

void mrn_atomic_abort(mrn_atomic_file *f) {
  if (f->fp) fclose(f->fp);
  if (f->temp_path) unlink(f->temp_path);
  release(f);
}

int mrn_atomic_write_file(const char *path, const void *data, size_t size) {
  mrn_atomic_file f;
  int rc = mrn_atomic_open(&f, path);
  if (rc != MRN_OK) return rc;
  mrn_atomic_write(&f, data, size);
  return mrn_atomic_commit(&f);
}

/* ---- directories ------------------------------------------------------- */

/* make one directory, accepting one that already exists */
static int make_one_dir(const char *dir, const char *whole) {
  if (mkdir(dir, 0755) == 0) return MRN_OK;
  int err = errno;
  struct stat st;
  /* EEXIST is the usual answer for an existing entry, but a read-only or
   * unwritable parent may answer EROFS/EACCES first: look before failing */
  if (stat(dir, &st) == 0) {
    if (S_ISDIR(st.st_mode)) return MRN_OK;
    err = ENOTDIR;
  }
  if (strcmp(dir, whole) == 0)
    return mrn_error_code(MRN_ERR_IO, "cannot create directory '%s': %s", whole, strerror(err));
  return mrn_error_code(MRN_ERR_IO, "cannot create directory '%s': '%s': %s", whole, dir, strerror(err));
}

int mrn_mkdir_p(const char *path) {
  if (!path || !*path) return MRN_OK;
  char *buf = strdup(path);
  if (!buf) return mrn_error_code(MRN_ERR_IO, "cannot create directory '%s': out of memory", path);
  /* create each prefix ending before a '/', then the whole path; repeated
   * and trailing slashes only produce prefixes that already exist */
  int rc = MRN_OK;
  for (char *p = buf + 1; *p && rc == MRN_OK; p++) {
    if (*p != '/' || p[-1] == '/') continue;
    *p = '\0';
    rc = make_one_dir(buf, path);
    *p = '/';
  }
  if (rc == MRN_OK) rc = make_one_dir(buf, path);
  free(buf);
  return rc;
}

char *mrn_path_join(const char *dir, const char *name) {
  if (!name) name = "";
  if (!dir || !*dir || name[0] == '/') return strdup(name);
  size_t dlen = strlen(dir), nlen = strlen(name);
  int need_slash = dir[dlen - 1] != '/';
  char *out = malloc(dlen + (size_t)need_slash + nlen + 1);
  if (!out) return NULL;
  memcpy(out, dir, dlen);
  if (need_slash) out[dlen] = '/';
  memcpy(out + dlen + need_slash, name, nlen + 1);
  return out;
}
