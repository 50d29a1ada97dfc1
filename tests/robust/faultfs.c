/* faultfs: an LD_PRELOAD library that makes one file operation fail, for the
 * fault-injection test (tests/robust/faults.py, doc/robustness.md).
 *
 *   FAULT_PATH=substring  only files whose path contains it (required)
 *   FAULT_OP=op           open | write | flush | close | rename
 *   FAULT_ERRNO=name      ENOSPC | EIO | EDQUOT | EFBIG | EACCES (or a number)
 *   FAULT_NTH=n           fail the n-th matching call (default 1) ...
 *   FAULT_REPEAT=1        ... and every matching call after it (a disk that stays full)
 *   FAULT_SHORT=1         a failing write first stores half its bytes and
 *                         returns that count, and the next write to the file
 *                         fails (a disk filling up within a write)
 *   FAULT_ARM=substring   count nothing until a file whose path contains it is opened
 *   FAULT_LOG=file        append one line per injected failure
 *   FAULT_TRACE=file      append the path of every file opened for writing
 *
 * The operations, for files opened for writing (write-only, created, truncated
 * or appended to) whose path matches:
 *   open    open, open64, openat, openat64, creat, fopen, fopen64
 *   write   write, pwrite, pwrite64, writev, and every write a stdio stream
 *           makes (its buffer reaching the system)
 *   flush   fsync, fdatasync
 *   close   close, fclose (the file is closed, and the call reports the error,
 *           as the kernel does for a delayed write error)
 *   rename  rename, renameat, renameat2 (either name matching)
 *
 * glibc's stdio writes through internal calls that no preloaded library sees,
 * so a stream opened for writing on a matching path is made here with
 * fopencookie over a file descriptor, and fileno() answers that descriptor.
 * Only the I/O moraine itself does on its output files goes through here;
 * reads and non-matching files take the ordinary path. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/uio.h>
#include <unistd.h>

enum { OP_NONE, OP_OPEN, OP_WRITE, OP_FLUSH, OP_CLOSE, OP_RENAME };
static const char *const op_names[] = {"", "open", "write", "flush", "close", "rename"};
#define MAX_FD 4096
#define MAX_STREAMS 64

static struct {
  int ready, op, err, repeat, short_write, armed;
  long nth, seen;
  const char *path, *arm, *log, *trace;
} cfg;

static unsigned char tracked[MAX_FD]; /* descriptors open for writing on a matching path */
static unsigned char full[MAX_FD];    /* a short write was injected: the next write fails */
static struct {
  FILE *fp;
  int fd;
} streams[MAX_STREAMS];

#define REAL(ret, name, args) \
  static ret(*real_##name) args; \
  if (!real_##name) real_##name = (ret(*) args)dlsym(RTLD_NEXT, #name)

static int errno_of(const char *s) {
  static const struct { const char *name; int value; } names[] = {
      {"ENOSPC", ENOSPC}, {"EIO", EIO}, {"EDQUOT", EDQUOT}, {"EFBIG", EFBIG}, {"EACCES", EACCES}};
  for (size_t i = 0; s && i < sizeof names / sizeof names[0]; i++)
    if (strcmp(s, names[i].name) == 0) return names[i].value;
  return s ? atoi(s) : 0;
}

static void configure(void) {
  if (cfg.ready) return;
  const char *op = getenv("FAULT_OP");
  for (int i = 1; op && i <= OP_RENAME; i++)
    if (strcmp(op, op_names[i]) == 0) cfg.op = i;
  cfg.path = getenv("FAULT_PATH");
  cfg.err = errno_of(getenv("FAULT_ERRNO"));
  if (!cfg.err) cfg.err = ENOSPC;
  cfg.nth = getenv("FAULT_NTH") ? atol(getenv("FAULT_NTH")) : 1;
  cfg.repeat = getenv("FAULT_REPEAT") && atoi(getenv("FAULT_REPEAT"));
  cfg.short_write = getenv("FAULT_SHORT") && atoi(getenv("FAULT_SHORT"));
  cfg.arm = getenv("FAULT_ARM");
  cfg.armed = !cfg.arm;
  cfg.log = getenv("FAULT_LOG");
  cfg.trace = getenv("FAULT_TRACE");
  if (!cfg.path || !*cfg.path) cfg.op = OP_NONE;
  cfg.ready = 1;
}

static int matches(const char *path) {
  configure();
  return cfg.op != OP_NONE && path && strstr(path, cfg.path);
}

/* an open that writes a file; O_RDWR alone opens an existing file for update,
 * which is how HDF5 looks whether a file it is to create exists already */
static int writes(int flags) { return (flags & (O_WRONLY | O_CREAT | O_TRUNC | O_APPEND)) != 0; }

static void append_line(const char *file, const char *line) {
  REAL(int, open, (const char *, int, ...));
  REAL(int, close, (int));
  int fd = real_open(file, O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) return;
  dprintf(fd, "%s\n", line);
  real_close(fd);
}

/* every open, matching or not: arming and the trace */
static void seen_open(const char *path, int flags) {
  configure();
  if (!path) return;
  if (!cfg.armed && strstr(path, cfg.arm)) cfg.armed = 1;
  if (cfg.trace && writes(flags)) append_line(cfg.trace, path);
}

/* 1 when this call (operation `op` on a matching file) is the one to fail;
 * errno is then set */
static int inject(int op, const char *what) {
  configure();
  if (op != cfg.op || !cfg.armed) return 0;
  long n = ++cfg.seen;
  if (n < cfg.nth || (n > cfg.nth && !cfg.repeat)) return 0;
  if (cfg.log) {
    char line[4200];
    snprintf(line, sizeof line, "faultfs: call %ld: %s on %s -> %s", n, op_names[op], what, strerror(cfg.err));
    append_line(cfg.log, line);
  }
  errno = cfg.err;
  return 1;
}

static int is_tracked(int fd) { return fd >= 0 && fd < MAX_FD && tracked[fd]; }

static char *fd_name(int fd, char *buf, size_t len) {
  char link[64];
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  ssize_t n = readlink(link, buf, len - 1);
  buf[n > 0 ? n : 0] = '\0';
  return buf;
}

/* ---- open ---------------------------------------------------------------- */

/* the common part of every open: fail it, or remember the descriptor */
static int opened(const char *path, int flags, int fd_or_fail) {
  if (fd_or_fail >= 0 && fd_or_fail < MAX_FD) tracked[fd_or_fail] = full[fd_or_fail] = 0;
  if (fd_or_fail >= 0 && writes(flags) && matches(path)) tracked[fd_or_fail] = 1;
  return fd_or_fail;
}

static int refuse_open(const char *path, int flags) {
  seen_open(path, flags);
  return writes(flags) && matches(path) && inject(OP_OPEN, path);
}

static mode_t mode_arg(int flags, va_list ap) {
  return (flags & O_CREAT) || (flags & O_TMPFILE) == O_TMPFILE ? (mode_t)va_arg(ap, int) : 0;
}

int open(const char *path, int flags, ...) {
  va_list ap;
  va_start(ap, flags);
  mode_t mode = mode_arg(flags, ap);
  va_end(ap);
  REAL(int, open, (const char *, int, ...));
  if (refuse_open(path, flags)) return -1;
  return opened(path, flags, real_open(path, flags, mode));
}

int open64(const char *path, int flags, ...) {
  va_list ap;
  va_start(ap, flags);
  mode_t mode = mode_arg(flags, ap);
  va_end(ap);
  REAL(int, open64, (const char *, int, ...));
  if (refuse_open(path, flags)) return -1;
  return opened(path, flags, real_open64(path, flags, mode));
}

int openat(int dirfd, const char *path, int flags, ...) {
  va_list ap;
  va_start(ap, flags);
  mode_t mode = mode_arg(flags, ap);
  va_end(ap);
  REAL(int, openat, (int, const char *, int, ...));
  if (refuse_open(path, flags)) return -1;
  return opened(path, flags, real_openat(dirfd, path, flags, mode));
}

int openat64(int dirfd, const char *path, int flags, ...) {
  va_list ap;
  va_start(ap, flags);
  mode_t mode = mode_arg(flags, ap);
  va_end(ap);
  REAL(int, openat64, (int, const char *, int, ...));
  if (refuse_open(path, flags)) return -1;
  return opened(path, flags, real_openat64(dirfd, path, flags, mode));
}

int creat(const char *path, mode_t mode) { return open(path, O_WRONLY | O_CREAT | O_TRUNC, mode); }

/* ---- stdio streams --------------------------------------------------------- */

static ssize_t cookie_read(void *c, char *buf, size_t size) { return read((int)(long)c, buf, size); }

static ssize_t cookie_write(void *c, const char *buf, size_t size) { return write((int)(long)c, buf, size); }

static int cookie_seek(void *c, off64_t *offset, int whence) {
  off64_t at = lseek64((int)(long)c, *offset, whence);
  if (at < 0) return -1;
  *offset = at;
  return 0;
}

static int cookie_close(void *c) {
  int fd = (int)(long)c;
  for (int i = 0; i < MAX_STREAMS; i++)
    if (streams[i].fp && streams[i].fd == fd) streams[i].fp = NULL;
  return close(fd);
}

static int open_flags_of(const char *mode) {
  int plus = strchr(mode, '+') != NULL;
  switch (mode[0]) {
    case 'w': return (plus ? O_RDWR : O_WRONLY) | O_CREAT | O_TRUNC;
    case 'a': return (plus ? O_RDWR : O_WRONLY) | O_CREAT | O_APPEND;
    default: return plus ? O_RDWR : O_RDONLY;
  }
}

FILE *fopen(const char *path, const char *mode) {
  REAL(FILE *, fopen, (const char *, const char *));
  int flags = open_flags_of(mode);
  seen_open(path, flags);
  if (!writes(flags) || !matches(path)) return real_fopen(path, mode);
  int fd = open(path, flags | O_CLOEXEC, 0666); /* counts as the open, tracks the descriptor */
  if (fd < 0) return NULL;
  int slot = 0;
  while (slot < MAX_STREAMS && streams[slot].fp) slot++;
  cookie_io_functions_t io = {cookie_read, cookie_write, cookie_seek, cookie_close};
  FILE *fp = slot < MAX_STREAMS ? fopencookie((void *)(long)fd, mode, io) : NULL;
  if (!fp) {
    close(fd);
    errno = ENOMEM;
    return NULL;
  }
  if (flags & O_APPEND) lseek64(fd, 0, SEEK_END);
  streams[slot].fp = fp;
  streams[slot].fd = fd;
  return fp;
}

FILE *fopen64(const char *path, const char *mode) { return fopen(path, mode); }

int fileno(FILE *fp) {
  REAL(int, fileno, (FILE *));
  for (int i = 0; i < MAX_STREAMS; i++)
    if (fp && streams[i].fp == fp) return streams[i].fd;
  return real_fileno(fp);
}

/* ---- write, flush, close, rename ----------------------------------------- */

/* 1 when this call of `op` on descriptor fd is the one to fail; errno is then set */
static int fails(int op, int fd) {
  char name[4096];
  return is_tracked(fd) && inject(op, fd_name(fd, name, sizeof name));
}

/* how many of `size` bytes a write lets through: all, -1 (errno set) for
 * the injected failure, or with FAULT_SHORT half of them */
static ssize_t write_allowance(int fd, size_t size) {
  if (is_tracked(fd) && full[fd]) {
    errno = cfg.err;
    return -1;
  }
  if (!fails(OP_WRITE, fd)) return (ssize_t)size;
  if (!cfg.short_write || size < 2) return -1;
  full[fd] = 1;
  return (ssize_t)(size / 2);
}

ssize_t write(int fd, const void *buf, size_t size) {
  REAL(ssize_t, write, (int, const void *, size_t));
  ssize_t n = write_allowance(fd, size);
  return n < 0 ? -1 : real_write(fd, buf, (size_t)n);
}

ssize_t pwrite(int fd, const void *buf, size_t size, off_t at) {
  REAL(ssize_t, pwrite, (int, const void *, size_t, off_t));
  ssize_t n = write_allowance(fd, size);
  return n < 0 ? -1 : real_pwrite(fd, buf, (size_t)n, at);
}

ssize_t pwrite64(int fd, const void *buf, size_t size, off64_t at) {
  REAL(ssize_t, pwrite64, (int, const void *, size_t, off64_t));
  ssize_t n = write_allowance(fd, size);
  return n < 0 ? -1 : real_pwrite64(fd, buf, (size_t)n, at);
}

ssize_t writev(int fd, const struct iovec *iov, int n) {
  REAL(ssize_t, writev, (int, const struct iovec *, int));
  size_t total = 0;
  for (int i = 0; i < n; i++) total += iov[i].iov_len;
  /* all or nothing: a short write is not cut out of the vectors */
  if (write_allowance(fd, total) != (ssize_t)total) return -1;
  return real_writev(fd, iov, n);
}

int fsync(int fd) {
  REAL(int, fsync, (int));
  return fails(OP_FLUSH, fd) ? -1 : real_fsync(fd);
}

int fdatasync(int fd) {
  REAL(int, fdatasync, (int));
  return fails(OP_FLUSH, fd) ? -1 : real_fdatasync(fd);
}

int close(int fd) {
  REAL(int, close, (int));
  int fail = fails(OP_CLOSE, fd);
  int err = errno;
  if (fd >= 0 && fd < MAX_FD) tracked[fd] = full[fd] = 0;
  int rc = real_close(fd);
  if (fail) errno = err;
  return fail ? -1 : rc;
}

static int refuse_rename(const char *from, const char *to) {
  return (matches(from) || matches(to)) && inject(OP_RENAME, to);
}

int rename(const char *from, const char *to) {
  REAL(int, rename, (const char *, const char *));
  return refuse_rename(from, to) ? -1 : real_rename(from, to);
}

int renameat(int fromfd, const char *from, int tofd, const char *to) {
  REAL(int, renameat, (int, const char *, int, const char *));
  return refuse_rename(from, to) ? -1 : real_renameat(fromfd, from, tofd, to);
}

int renameat2(int fromfd, const char *from, int tofd, const char *to, unsigned flags) {
  REAL(int, renameat2, (int, const char *, int, const char *, unsigned));
  return refuse_rename(from, to) ? -1 : real_renameat2(fromfd, from, tofd, to, flags);
}
