#include "io/confine.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"

/* `path` made absolute, not resolved: the current directory comes before a
 * relative path; malloc'd, NULL with errno set */
static char *absolute(const char *path) {
  if (path[0] == '/') return strdup(path);
  char cwd[PATH_MAX];
  if (!getcwd(cwd, sizeof cwd)) return NULL;
  size_t len = strlen(cwd) + strlen(path) + 2;
  char *abs = malloc(len);
  if (abs) snprintf(abs, len, "%s/%s", cwd, path);
  return abs;
}

/* an absolute path with ".", ".." and repeated slashes resolved as text
 * ("/a/./b//../c" -> "/a/c"); malloc'd */
static char *normalised(const char *abs) {
  char *out = malloc(strlen(abs) + 2);
  if (!out) return NULL;
  size_t len = 0;
  for (const char *p = abs; *p;) {
    while (*p == '/') p++;
    size_t n = strcspn(p, "/");
    if (n == 2 && p[0] == '.' && p[1] == '.') {
      while (len > 0 && out[--len] != '/') continue; /* drop the last component */
    } else if (n > 0 && !(n == 1 && p[0] == '.')) {
      out[len++] = '/';
      memcpy(out + len, p, n);
      len += n;
    }
    p += n;
  }
  if (len == 0) out[len++] = '/';
  out[len] = '\0';
  return out;
}

/* The real path `abs` (absolute) names: its longest existing prefix goes
 * through realpath(3), which follows every link in it; the rest does not
 * exist and is appended as text. NULL when the existing prefix cannot be
 * resolved (a link to nothing, a loop): errno is set and *stuck is the
 * prefix (malloc'd, for the message). */
static char *resolve(const char *abs, char **stuck) {
  char *prefix = strdup(abs);
  if (!prefix) return NULL;
  size_t cut = strlen(prefix);
  struct stat st;
  /* lstat, not stat: a link that leads nowhere exists, and must not be
   * taken for a name that is free to create */
  while (cut > 1 && lstat(prefix, &st) != 0) {
    char *slash = strrchr(prefix, '/');
    cut = slash == prefix ? 1 : (size_t)(slash - prefix);
    prefix[cut] = '\0';
  }
  char *real = realpath(prefix, NULL);
  if (!real) {
    *stuck = prefix;
    return NULL;
  }
  free(prefix);
  const char *rest = abs + cut;
  size_t len = strlen(real) + strlen(rest) + 2;
  char *joined = malloc(len);
  char *result = NULL;
  if (joined) {
    snprintf(joined, len, "%s/%s", real, rest);
    result = normalised(joined);
  }
  free(joined);
  free(real);
  return result;
}

/* 1 when the normalised path `real` lies strictly below the directory `root` */
static int below(const char *real, const char *root) {
  size_t n = strlen(root);
  if (n == 1) return real[1] != '\0'; /* the root is "/" */
  return strncmp(real, root, n) == 0 && real[n] == '/';
}

/* the refusal message for a resolved path outside root */
static int outside(const char *path, const char *dir, const char *abs, const char *real, const char *root) {
  if (strcmp(real, root) == 0) return mrn_error("'%s' is the output directory '%s' itself", path, dir);
  char *text = normalised(abs);
  int link = text && strcmp(text, real) != 0;
  free(text);
  if (link) return mrn_error("'%s' is outside the output directory '%s' (it resolves to '%s')", path, dir, real);
  return mrn_error("'%s' is outside the output directory '%s'", path, dir);
}

int mrn_confine_check(const char *dir, const char *path) {
  char *root = realpath(dir, NULL);
  if (!root) return mrn_error("the output directory '%s' cannot be resolved: %s", dir, strerror(errno));
  char *abs = absolute(path);
  char *stuck = NULL;
  char *real = abs ? resolve(abs, &stuck) : NULL;
  int err = errno;
  int rc = MRN_OK;
  if (!real && stuck) rc = mrn_error("'%s' cannot be resolved: '%s': %s", path, stuck, strerror(err));
  else if (!real) rc = mrn_error("'%s' cannot be resolved: %s", path, strerror(err));
  else if (!below(real, root)) rc = outside(path, dir, abs, real, root);
  free(stuck);
  free(real);
  free(abs);
  free(root);
  return rc;
}
