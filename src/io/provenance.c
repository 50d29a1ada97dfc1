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

/* ---- writing through an atomic file, remembering the first error -------- */

static int finish(mrn_atomic_file *f) {
  if (ferror(f->fp)) {
    int rc = mrn_error_code(MRN_ERR_IO, "cannot write '%s': %s", f->final_path, strerror(errno ? errno : EIO));
    mrn_atomic_abort(f);
    return rc;
  }
  return mrn_atomic_commit(f);
}

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
  while ((got = fread(buf, 1, sizeof buf, in)) > 0)
    if (fwrite(buf, 1, got, out.fp) != got) break;
  int read_err = ferror(in) ? errno : 0;
  fclose(in);
  if (read_err) {
    mrn_atomic_abort(&out);
    return mrn_error_code(MRN_ERR_IO, "cannot read '%s' to copy it into '%s': %s", deck_path, dest, strerror(read_err));
  }
  return finish(&out);
}

/* ---- values on one line -------------------------------------------------------- */

/* C-style escapes for anything that would break the "key: value" line */
static void put_escaped(FILE *fp, const char *s) {
  for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
    switch (*p) {
      case '\\': fputs("\\\\", fp); break;
      case '\n': fputs("\\n", fp); break;
      case '\r': fputs("\\r", fp); break;
      case '\t': fputs("\\t", fp); break;
      default:
        if (*p < 0x20 || *p == 0x7f)
          fprintf(fp, "\\x%02x", *p);
        else
          fputc(*p, fp);
    }
  }
}

static void put_line(FILE *fp, const char *key, const char *value) {
  fprintf(fp, "%s: ", key);
  put_escaped(fp, value ? value : "");
  fputc('\n', fp);
}

/* one shell word: as is when only harmless characters, else in single quotes
 * (a quote inside becomes '\''), so the command line can be pasted back */
static void put_shell_word(FILE *fp, const char *s) {
  const char *safe = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-+=./,:@%^";
  if (*s && strspn(s, safe) == strlen(s)) {
    put_escaped(fp, s);
    return;
  }
  fputc('\'', fp);
  for (const char *p = s; *p; p++) {
    if (*p == '\'') {
      fputs("'\\''", fp);
    } else {
      char one[2] = {*p, '\0'};
      put_escaped(fp, one);
    }
  }
  fputc('\'', fp);
}

/* ---- what the run was --------------------------------------------------------- */

static void put_start_time(FILE *fp) {
  char stamp[64] = "unknown";
  time_t now = time(NULL);
  struct tm utc;
  if (now != (time_t)-1 && gmtime_r(&now, &utc)) strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", &utc);
  put_line(fp, "started_utc", stamp);
}

static void put_host(FILE *fp) {
  char host[256];
  if (gethostname(host, sizeof host) != 0) snprintf(host, sizeof host, "unknown");
  host[sizeof host - 1] = '\0';
  put_line(fp, "hostname", host);
}

static int thread_count(void) {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

static void put_paths(FILE *fp, const char *deck_path) {
  char buf[PATH_MAX];
  put_line(fp, "working_directory", getcwd(buf, sizeof buf) ? buf : "unknown");
  if (!deck_path) {
    put_line(fp, "deck", "(none given; no copy)");
    return;
  }
  put_line(fp, "deck", deck_path);
  if (realpath(deck_path, buf)) put_line(fp, "deck_absolute", buf);
  put_line(fp, "deck_copy", PROVENANCE_DIR "/deck.lua");
}

static void put_command(FILE *fp, int argc, const char *const *argv) {
  fputs("command: ", fp);
  for (int i = 0; argv && i < argc; i++) {
    if (i) fputc(' ', fp);
    put_shell_word(fp, argv[i] ? argv[i] : "");
  }
  fputc('\n', fp);
}

static int write_run_txt(const char *dest, const char *deck_path, int argc, const char *const *argv,
                         const char *const *sets, int nsets) {
  mrn_atomic_file f;
  int rc = mrn_atomic_open(&f, dest);
  if (rc != MRN_OK) return rc;
  FILE *fp = f.fp;
  fputs("# moraine provenance: how the files of this directory were made.\n"
        "# One \"key: value\" per line; values use C escapes (\\n, \\t, \\\\, \\xHH);\n"
        "# one \"set:\" line per --set, in the order given.\n",
        fp);
  put_line(fp, "moraine_version", MORAINE_VERSION);
  put_line(fp, "git_commit", MORAINE_GIT_COMMIT);
  put_start_time(fp);
  put_host(fp);
  fprintf(fp, "threads: %d\n", thread_count());
  put_paths(fp, deck_path);
  put_command(fp, argc, argv);
  for (int i = 0; sets && i < nsets; i++) put_line(fp, "set", sets[i]);
  return finish(&f);
}

/* ---- entry point ------------------------------------------------------------- */

int mrn_provenance_write(const char *outdir, const char *deck_path, int argc, const char *const *argv,
                         const char *const *sets, int nsets) {
  char *dir = mrn_path_join(outdir ? outdir : ".", PROVENANCE_DIR);
  char *deck_dest = dir ? mrn_path_join(dir, "deck.lua") : NULL;
  char *run_dest = dir ? mrn_path_join(dir, "run.txt") : NULL;
  int rc = MRN_OK;
  if (!dir || !deck_dest || !run_dest)
    rc = mrn_error_code(MRN_ERR_IO, "cannot write the provenance into '%s': out of memory", outdir ? outdir : ".");
  if (rc == MRN_OK) rc = mrn_mkdir_p(dir);
  /* the copy first: run.txt names it */
  if (rc == MRN_OK && deck_path) rc = copy_deck(deck_path, deck_dest);
  if (rc == MRN_OK) rc = write_run_txt(run_dest, deck_path, argc, argv, sets, nsets);
  free(dir);
  free(deck_dest);
  free(run_dest);
  return rc;
}
