#include "core/log.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/comm.h"
#include "core/error.h"

static int quiet_mode = 0;

void mrn_log_set_quiet(int quiet) { quiet_mode = quiet; }
int mrn_log_quiet(void) { return quiet_mode; }

/* ---- the file ----------------------------------------------------------- */

static struct {
  int fd;          /* -1 while no log is open */
  char *path;
  off_t size;      /* bytes of whole messages in the file */
  char failure[1200]; /* the first failed write's message, "" while all is well */
} file = {-1, NULL, 0, ""};

static void fail(int err, const char *what) {
  if (!file.failure[0])
    snprintf(file.failure, sizeof file.failure, "cannot write '%s': %s%s", file.path, strerror(err), what);
  close(file.fd);
  file.fd = -1;
}

/* the whole message or none of it: a write cut short is truncated away */
static void file_write(const char *text, size_t len) {
  if (file.fd < 0) return;
  for (size_t done = 0; done < len;) {
    ssize_t n = write(file.fd, text + done, len - done);
    if (n > 0) {
      done += (size_t)n;
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    int err = n < 0 ? errno : EIO;
    fail(err, ftruncate(file.fd, file.size) != 0 ? " (and the part of a message written could not be removed)" : "");
    return;
  }
  file.size += (off_t)len;
}

int mrn_log_open(const char *path, int append) {
  mrn_log_close();
  file.failure[0] = '\0';
  if (!mrn_comm_writes()) return MRN_OK; /* process 0 keeps the run's log */
  /* O_APPEND also when new: each message lands at the end, whatever else wrote there */
  const int flags = O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW | O_CLOEXEC | (append ? 0 : O_TRUNC);
  int fd = open(path, flags, 0644);
  if (fd < 0) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': %s", path, strerror(errno));
  struct stat st;
  file.path = strdup(path);
  file.fd = fd;
  file.size = fstat(fd, &st) == 0 ? st.st_size : 0;
  if (!file.path) {
    mrn_log_close();
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", path);
  }
  return MRN_OK;
}

int mrn_log_close(void) {
  if (file.fd >= 0) {
    /* some file systems cannot sync (EINVAL); the messages are still written */
    if (fsync(file.fd) != 0 && errno != EINVAL && errno != ENOTSUP) fail(errno, "");
    if (file.fd >= 0 && close(file.fd) != 0 && !file.failure[0]) {
      file.fd = -1;
      fail(errno, "");
    }
    file.fd = -1;
  }
  int rc = file.failure[0] ? mrn_error_code(MRN_ERR_IO, "%s", file.failure) : MRN_OK;
  free(file.path);
  file.path = NULL;
  return rc;
}

int mrn_log_failed(void) { return file.failure[0] != '\0'; }
const char *mrn_log_failure(void) { return file.failure; }
int mrn_log_fd(void) { return file.fd; }

/* ---- the screen and its progress bar ------------------------------------ */

static struct {
  char text[256];
  int active;        /* a bar is running */
  int shown;         /* and is on the screen now */
  int at_line_start; /* the screen's cursor is at the start of a line */
} bar = {"", 0, 0, 1};

static void draw_bar(void) {
  fprintf(stderr, "\r%s\033[K", bar.text);
  fflush(stderr);
  bar.shown = 1;
}

/* before writing to the screen: the bar leaves its line */
static void screen_begin(void) {
  if (!bar.shown) return;
  fputs("\r\033[K", stderr);
  fflush(stderr);
  bar.shown = 0;
}

/* after: a whole line written, the bar comes back below it */
static void screen_end(const char *text, size_t len) {
  if (len) bar.at_line_start = text[len - 1] == '\n';
  if (bar.active && bar.at_line_start) draw_bar();
}

void mrn_log_bar(const char *text) {
  snprintf(bar.text, sizeof bar.text, "%s", text);
  bar.active = 1;
  if (bar.shown || bar.at_line_start) draw_bar();
}

void mrn_log_bar_end(int keep) {
  if (!bar.active) return;
  if (keep && !bar.shown && bar.at_line_start) draw_bar();
  if (bar.shown) {
    fputs(keep ? "\n" : "\r\033[K", stderr);
    fflush(stderr);
  }
  bar.active = bar.shown = 0;
  bar.at_line_start = 1;
}

/* ---- messages ------------------------------------------------------------ */

void mrn_log_text(FILE *screen, const char *text, size_t len) {
  if (!mrn_comm_writes()) return; /* a distributed run speaks through process 0 */
  if (screen) {
    screen_begin();
    fwrite(text, 1, len, screen);
    fflush(screen);
    screen_end(text, len);
  }
  file_write(text, len);
}

/* prefix, the formatted message and suffix as one message */
static void say(FILE *screen, const char *prefix, const char *suffix, const char *fmt, va_list ap) {
  char small[2048];
  va_list copy;
  va_copy(copy, ap);
  int n = vsnprintf(small, sizeof small, fmt, copy);
  va_end(copy);
  if (n < 0) return;
  size_t plen = strlen(prefix), slen = strlen(suffix), len = plen + (size_t)n + slen;
  char *text = malloc(len + 1);
  if (!text) return;
  memcpy(text, prefix, plen);
  if ((size_t)n < sizeof small) memcpy(text + plen, small, (size_t)n);
  else vsnprintf(text + plen, (size_t)n + 1, fmt, ap);
  memcpy(text + plen + n, suffix, slen + 1);
  mrn_log_text(screen, text, len);
  free(text);
}

void mrn_log_printf(FILE *screen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  say(screen, "", "", fmt, ap);
  va_end(ap);
}

void mrn_info(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  say(quiet_mode ? NULL : stderr, "", "\n", fmt, ap);
  va_end(ap);
}

void mrn_warn(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  say(stderr, "moraine: warning: ", "\n", fmt, ap);
  va_end(ap);
}

static char last_error[2048];

void mrn_log_error(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(last_error, sizeof last_error, fmt, ap);
  va_end(ap);
  /* an error only this process met is its own to say */
  if (!mrn_comm_writes() && !mrn_comm_shared_error())
    fprintf(stderr, "moraine (process %d): %s\n", mrn_comm_rank(), last_error);
  mrn_log_printf(stderr, "moraine: %s\n", last_error);
}

const char *mrn_log_last_error(void) { return last_error; }
