#include "io/provenance.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "io/atomic_file.h"

#define PROVENANCE_DIR "provenance"

/* ---- the deck copy ---------------------------------------------------------- */

static int copy_deck(const char *deck_path, const char *dest) {
  FILE *in = fopen(deck_path, "rb");
  if (!in)
    return mrn_error_code(MRN_ERR_IO, "cannot read '%s' to copy it into '%s': %s", deck_path, dest, strerror(errno));
  mrn_atomic_file out;
  int rc = mrn_atomic_open(&out, dest);
  if (rc != MRN_OK) {
    fclose(in);
    return rc;
  }
  char buf[65536];
  size_t got;
  while (!out.err && (got = fread(buf, 1, sizeof buf, in)) > 0) mrn_atomic_write(&out, buf, got);
  int read_err = ferror(in) ? errno : 0;
  fclose(in);
  if (read_err) {
    mrn_atomic_abort(&out);
    return mrn_error_code(MRN_ERR_IO, "cannot read '%s' to copy it into '%s': %s", deck_path, dest, strerror(read_err));
  }
  return mrn_atomic_commit(&out);
}

/* ---- values on one line -------------------------------------------------------- */

/* C-style escapes for anything that would break the "key: value" line */
static void put_escaped(mrn_atomic_file *f, const char *s) {
  for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
    switch (*p) {
      case '\\': mrn_atomic_printf(f, "\\\\"); break;
      case '\n': mrn_atomic_printf(f, "\\n"); break;
      case '\r': mrn_atomic_printf(f, "\\r"); break;
      case '\t': mrn_atomic_printf(f, "\\t"); break;
      default:
        if (*p < 0x20 || *p == 0x7f)
          mrn_atomic_printf(f, "\\x%02x", *p);
        else
          mrn_atomic_printf(f, "%c", *p);
    }
  }
}

static void put_line(mrn_atomic_file *f, const char *key, const char *value) {
  mrn_atomic_printf(f, "%s: ", key);
  put_escaped(f, value ? value : "");
  mrn_atomic_printf(f, "\n");
}

/* one shell word: as is when only harmless characters, else in single quotes
 * (a quote inside becomes '\''), so the command line can be pasted back */
static void put_shell_word(mrn_atomic_file *f, const char *s) {
  const char *safe = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-+=./,:@%^";
  if (*s && strspn(s, safe) == strlen(s)) {
    put_escaped(f, s);
    return;
  }
  mrn_atomic_printf(f, "'");
  for (const char *p = s; *p; p++) {
    if (*p == '\'') {
      mrn_atomic_printf(f, "'\\''");
    } else {
      char one[2] = {*p, '\0'};
      put_escaped(f, one);
    }
  }
  mrn_atomic_printf(f, "'");
}

/* ---- what the run was --------------------------------------------------------- */

static void put_start_time(mrn_atomic_file *f) {
  char stamp[64] = "unknown";
  time_t now = time(NULL);
  struct tm utc;
  if (now != (time_t)-1 && gmtime_r(&now, &utc)) strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", &utc);
  put_line(f, "started_utc", stamp);
}

static void put_host(mrn_atomic_file *f) {
  char host[256];
  if (gethostname(host, sizeof host) != 0) snprintf(host, sizeof host, "unknown");
  host[sizeof host - 1] = '\0';
  put_line(f, "hostname", host);
}

static int thread_count(void) {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

static void put_paths(mrn_atomic_file *f, const char *deck_path) {
  char buf[PATH_MAX];
  put_line(f, "working_directory", getcwd(buf, sizeof buf) ? buf : "unknown");
  if (!deck_path) {
    put_line(f, "deck", "(none given; no copy)");
    return;
  }
  int from_stdin = !strcmp(deck_path, "-");
  put_line(f, "deck", from_stdin ? "- (standard input)" : deck_path);
  if (!from_stdin && realpath(deck_path, buf)) put_line(f, "deck_absolute", buf);
  put_line(f, "deck_copy", PROVENANCE_DIR "/deck.lua");
}

static void put_command(mrn_atomic_file *f, int argc, const char *const *argv) {
  mrn_atomic_printf(f, "command: ");
  for (int i = 0; argv && i < argc; i++) {
    if (i) mrn_atomic_printf(f, " ");
    put_shell_word(f, argv[i] ? argv[i] : "");
  }
  mrn_atomic_printf(f, "\n");
}

static int write_run_txt(const char *dest, const char *deck_path, int argc, const char *const *argv,
                         const char *const *sets, int nsets) {
  mrn_atomic_file out, *f = &out;
  int rc = mrn_atomic_open(f, dest);
  if (rc != MRN_OK) return rc;
  mrn_atomic_printf(f, "# moraine provenance: how the files of this directory were made.\n"
                       "# One \"key: value\" per line; values use C escapes (\\n, \\t, \\\\, \\xHH);\n"
                       "# one \"set:\" line per --set, in the order given.\n");
  put_line(f, "moraine_version", MORAINE_VERSION);
  put_line(f, "git_commit", MORAINE_GIT_COMMIT);
  put_start_time(f);
  put_host(f);
  mrn_atomic_printf(f, "threads: %d\n", thread_count());
  put_paths(f, deck_path);
  put_command(f, argc, argv);
  for (int i = 0; sets && i < nsets; i++) put_line(f, "set", sets[i]);
  return mrn_atomic_commit(f);
}

/* ---- entry point ------------------------------------------------------------- */

/* the deck copied from deck_path, or `text` (len bytes) when not NULL */
static int write_all(const char *outdir, const char *deck_path, const char *text, size_t len, int argc,
                     const char *const *argv, const char *const *sets, int nsets) {
  char *dir = mrn_path_join(outdir ? outdir : ".", PROVENANCE_DIR);
  char *deck_dest = dir ? mrn_path_join(dir, "deck.lua") : NULL;
  char *run_dest = dir ? mrn_path_join(dir, "run.txt") : NULL;
  int rc = MRN_OK;
  if (!dir || !deck_dest || !run_dest)
    rc = mrn_error_code(MRN_ERR_IO, "cannot write the provenance into '%s': out of memory", outdir ? outdir : ".");
  if (rc == MRN_OK) rc = mrn_mkdir_p(dir);
  /* the copy first: run.txt names it */
  if (rc == MRN_OK && text) rc = mrn_atomic_write_file(deck_dest, text, len);
  else if (rc == MRN_OK && deck_path) rc = copy_deck(deck_path, deck_dest);
  if (rc == MRN_OK) rc = write_run_txt(run_dest, deck_path, argc, argv, sets, nsets);
  free(dir);
  free(deck_dest);
  free(run_dest);
  return rc;
}

int mrn_provenance_write(const char *outdir, const char *deck_path, int argc, const char *const *argv,
                         const char *const *sets, int nsets) {
  return write_all(outdir, deck_path, NULL, 0, argc, argv, sets, nsets);
}

int mrn_provenance_write_text(const char *outdir, const char *text, size_t len, int argc, const char *const *argv,
                              const char *const *sets, int nsets) {
  return write_all(outdir, "-", text, len, argc, argv, sets, nsets);
}
