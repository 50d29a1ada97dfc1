/* moraine: HDF5 time series (io/series_h5.h).
 *
 *   test_series_h5        unit checks in a fresh directory under /tmp
 *   test_series_h5 DIR    also leaves series files, each with the CSV of the
 *                         same rows, for tests/python/check_series_h5.py:
 *                           DIR/series.h5 + series.csv   the diagnostics
 *                               columns, dt, and recorded values that come
 *                               and go (NaN where not given)
 *                           DIR/killed.h5 + killed.csv   written by a process
 *                               killed with SIGKILL after a flush, with a row staged
 *
 * The series are read back here with HDF5's C library (through io/h5util.h),
 * while the writer still has the file open (h5dump, another process), and
 * after the writer was killed. */
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "testfs.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/h5util.h"
#include "io/series_h5.h"
#include "solver/diagnostics.h"

/* ---- small helpers ------------------------------------------------------ */

/* NaN equals NaN; everything else exactly */
static int same(double a, double b) { return (isnan(a) && isnan(b)) || a == b; }

/* a whole float64 dataset of `rows` entries, or NULL (the reader's message is printed) */
static double *read_doubles(mrn_h5r *r, const char *name, long rows) {
  double *v = mrn_h5r_dataset(r, name, MRN_H5_FLOAT64, rows, MRN_H5_RANK1);
  if (!v) fprintf(stderr, "%s\n", mrn_error_message());
  return v;
}

/* ---- the basics ------------------------------------------------------------- */

static void test_rows_and_padding(const char *dir) {
  char *path = mrn_path_join(dir, "basic.h5");
  mrn_series *s = NULL;
  CHECK(mrn_series_create(&s, path) == MRN_OK);
  if (!s) {
    free(path);
    return;
  }
  CHECK(mrn_series_add_column(s, "E_kinetic", "J", "kinetic energy") == MRN_OK);
  CHECK(mrn_series_add_column(s, "mass", "kg", NULL) == MRN_OK);
  CHECK(mrn_series_column_count(s) == 2 && mrn_series_find(s, "mass") == 1);

  /* row 0: both; row 1: mass only; row 2: a recorded value appears; row 3: nothing */
  CHECK(mrn_series_set_at(s, 0, 1.5) == MRN_OK);
  CHECK(mrn_series_set(s, "mass", 2.0) == MRN_OK);
  CHECK(mrn_series_append(s, 0, 0.0) == MRN_OK);
  CHECK(mrn_series_set(s, "mass", 2.5) == MRN_OK);
  CHECK(mrn_series_append(s, 10, 0.1) == MRN_OK);
  CHECK(mrn_series_set(s, "runout", 3.25) == MRN_OK);
  CHECK(mrn_series_set(s, "runout", 3.5) == MRN_OK); /* the last value set wins */
  CHECK(mrn_series_append(s, 20, 0.2) == MRN_OK);
  CHECK(mrn_series_append(s, 30, 0.30000000000000004) == MRN_OK);
  CHECK(mrn_series_rows(s) == 4 && mrn_series_column_count(s) == 3);
  CHECK(strcmp(mrn_series_column_name(s, 2), "runout") == 0);
  CHECK(mrn_series_column_name(s, 3) == NULL);
  /* units given later reach the attribute */
  CHECK(mrn_series_add_column(s, "runout", "m", "front position") == MRN_OK);
  CHECK(mrn_series_set_at(s, 7, 1.0) == MRN_ERR);
  /* declared, never given a value: there all the same, all NaN */
  CHECK(mrn_series_add_column(s, "declared", "Pa", "") == MRN_OK);
  CHECK(mrn_series_close(s) == MRN_OK);

  mrn_h5r r;
  CHECK(mrn_h5r_open(&r, path) == MRN_OK);
  double *t = read_doubles(&r, "/time", 4);
  int64_t *step = mrn_h5r_dataset(&r, "/step", MRN_H5_INT64, 4, MRN_H5_RANK1);
  double *ek = read_doubles(&r, "/E_kinetic", 4);
  double *m = read_doubles(&r, "/mass", 4);
  double *ro = read_doubles(&r, "/runout", 4);
  double *declared = read_doubles(&r, "/declared", 4);
  CHECK(declared && isnan(declared[0]) && isnan(declared[3]));
  free(declared);
  CHECK(t && t[0] == 0.0 && t[1] == 0.1 && t[3] == 0.30000000000000004);
  CHECK(step && step[0] == 0 && step[3] == 30);
  CHECK(ek && ek[0] == 1.5 && isnan(ek[1]) && isnan(ek[2]) && isnan(ek[3]));
  CHECK(m && m[0] == 2.0 && m[1] == 2.5 && isnan(m[2]));
  CHECK(ro && isnan(ro[0]) && isnan(ro[1]) && ro[2] == 3.5 && isnan(ro[3])); /* padded before, NaN after */
  char text[128];
  CHECK(mrn_h5r_string(&r, "/E_kinetic", "units", text, sizeof text) == MRN_OK && strcmp(text, "J") == 0);
  CHECK(mrn_h5r_string(&r, "/E_kinetic", "description", text, sizeof text) == MRN_OK &&
        strcmp(text, "kinetic energy") == 0);
  CHECK(mrn_h5r_string(&r, "/mass", "description", text, sizeof text) == MRN_OK && strcmp(text, "") == 0);
  CHECK(mrn_h5r_string(&r, "/runout", "units", text, sizeof text) == MRN_OK && strcmp(text, "m") == 0);
  CHECK(mrn_h5r_string(&r, "/time", "units", text, sizeof text) == MRN_OK && strcmp(text, "s") == 0);
  CHECK(mrn_h5r_string(&r, "/", "format", text, sizeof text) == MRN_OK && strcmp(text, "moraine-series") == 0);
  free(t);
  free(step);
  free(ek);
  free(m);
  free(ro);
  mrn_h5r_close(&r);
  free(path);
}

/* more rows than one chunk holds, and a column that starts in a later chunk */
static void test_many_rows(const char *dir) {
  enum { ROWS = 1300, LATE = 1100 };
  char *path = mrn_path_join(dir, "long.h5");
  mrn_series *s = NULL;
  CHECK(mrn_series_create(&s, path) == MRN_OK);
  if (!s) {
    free(path);
    return;
  }
  int ok = 1;
  for (long i = 0; i < ROWS && ok; i++) {
    ok = mrn_series_set(s, "x", 0.5 * i) == MRN_OK;
    if (ok && i >= LATE) ok = mrn_series_set(s, "late", -1.0 * i) == MRN_OK;
    if (ok) ok = mrn_series_append(s, i, i * 1e-3) == MRN_OK;
  }
  CHECK(ok);
  CHECK(mrn_series_close(s) == MRN_OK);
  mrn_h5r r;
  CHECK(mrn_h5r_open(&r, path) == MRN_OK);
  double *x = read_doubles(&r, "/x", ROWS);
  double *late = read_doubles(&r, "/late", ROWS);
  int good = x && late;
  for (long i = 0; good && i < ROWS; i++)
    good = x[i] == 0.5 * i && same(late[i], i >= LATE ? -1.0 * i : NAN);
  CHECK(good);
  free(x);
  free(late);
  mrn_h5r_close(&r);
  free(path);
}

static void test_errors(const char *dir) {
  mrn_series *s = NULL;
  char *missing = mrn_path_join(dir, "nope/series.h5");
  mrn_error_clear();
  CHECK(mrn_series_create(&s, missing) == MRN_ERR_IO && s == NULL);
  CHECK(strstr(mrn_error_message(), missing) != NULL);
  free(missing);

  char *path = mrn_path_join(dir, "names.h5");
  CHECK(mrn_series_create(&s, path) == MRN_OK);
  if (s) {
    CHECK(mrn_series_add_column(s, "", "J", "") == MRN_ERR);
    CHECK(mrn_series_add_column(s, "a/b", "", "") == MRN_ERR);
    CHECK(strstr(mrn_error_message(), "'a/b'") != NULL);
    CHECK(mrn_series_set(s, "time", 1.0) == MRN_ERR);
    CHECK(mrn_series_set(s, "step", 1.0) == MRN_ERR);
    CHECK(mrn_series_set(s, ".", 1.0) == MRN_ERR);
    CHECK(mrn_series_set(s, "a.b c", 1.0) == MRN_OK); /* any other text is a fine name */
    CHECK(mrn_series_column_count(s) == 1);
    CHECK(mrn_series_close(s) == MRN_OK);
  }
  CHECK(mrn_series_close(NULL) == MRN_OK);
  free(path);
}

/* ---- the diagnostics series with its CSV -------------------------------------- */

/* The columns a run writes: every diagnostics column with its unit, dt, and
 * values recorded from a deck that come and go. The CSV has the same rows
 * in the diagnostics CSV's format (step,time,dt,...; %.17g; "nan" when
 * absent), so check_series_h5.py can compare the two. */
typedef struct pair {
  mrn_series *s;
  FILE *csv;
} pair;

static const char *const recorded[] = {"runout", "front_speed"};

static int pair_open(pair *p, const char *dir, const char *name) {
  char file[64];
  snprintf(file, sizeof file, "%s.h5", name);
  char *h5 = mrn_path_join(dir, file);
  snprintf(file, sizeof file, "%s.csv", name);
  char *csv = mrn_path_join(dir, file);
  int rc = mrn_series_create(&p->s, h5);
  if (rc == MRN_OK) rc = mrn_series_add_column(p->s, "dt", "s", "time step");
  for (int i = 0; rc == MRN_OK && i < mrn_diagnostics_column_count(); i++)
    rc = mrn_series_add_column(p->s, mrn_diagnostics_column_name(i), mrn_diagnostics_column_unit(i), "diagnostics");
  p->csv = rc == MRN_OK ? fopen(csv, "w") : NULL;
  if (p->csv) {
    fprintf(p->csv, "step,time,dt");
    for (int i = 0; i < mrn_diagnostics_column_count(); i++) fprintf(p->csv, ",%s", mrn_diagnostics_column_name(i));
    for (int i = 0; i < 2; i++) fprintf(p->csv, ",%s", recorded[i]);
    fputc('\n', p->csv);
    fflush(p->csv);
  }
  free(h5);
  free(csv);
  return p->csv ? MRN_OK : MRN_ERR_IO;
}

/* row `r` of made-up diagnostics; recorded values only on some rows */
static int pair_row(pair *p, long r) {
  double v[64], rec[2] = {NAN, NAN};
  mrn_diagnostics d = {0};
  d.kinetic = 0.5 * r * r / 3.0;
  d.gravity = -9.81 * r / 7.0;
  d.total = d.kinetic + d.gravity;
  d.mass = 1.0 / 3.0;
  d.momentum[0] = r * 1e-7;
  d.com[1] = 1.0 - r * 1e-3;
  d.particles = 1000;
  mrn_diagnostics_values(&d, v);
  long step = 10 * r;
  double time = r * 0.1, dt = 1.0 / (r + 3);
  int rc = mrn_series_set(p->s, "dt", dt);
  for (int i = 0; rc == MRN_OK && i < mrn_diagnostics_column_count(); i++) rc = mrn_series_set_at(p->s, i + 1, v[i]);
  if (r >= 3) rec[0] = 2.0 + r / 9.0;      /* appears after three rows */
  if (r % 2 == 1) rec[1] = r * 1e300;      /* every other row */
  for (int i = 0; rc == MRN_OK && i < 2; i++)
    if (!isnan(rec[i])) rc = mrn_series_set(p->s, recorded[i], rec[i]);
  if (rc == MRN_OK) rc = mrn_series_append(p->s, step, time);
  fprintf(p->csv, "%ld,%.17g,%.17g", step, time, dt);
  for (int i = 0; i < mrn_diagnostics_column_count(); i++) fprintf(p->csv, ",%.17g", v[i]);
  for (int i = 0; i < 2; i++) fprintf(p->csv, ",%.17g", rec[i]);
  fputc('\n', p->csv);
  fflush(p->csv);
  return rc;
}

static int pair_close(pair *p) {
  int rc = mrn_series_close(p->s);
  if (p->csv) fclose(p->csv);
  return rc;
}

/* runs h5dump on a series the writer still holds open: another process must
 * be able to read it (HDF5's file lock would refuse it) */
static void test_readable_while_open(const char *dir) {
  if (system("command -v h5dump > /dev/null 2>&1") != 0) {
    printf("h5dump not found: the open-file read is not checked\n");
    return;
  }
  pair p = {0};
  CHECK(pair_open(&p, dir, "open") == MRN_OK);
  for (long r = 0; r < 5 && p.s; r++) CHECK(pair_row(&p, r) == MRN_OK);
  CHECK(p.s && mrn_series_flush(p.s) == MRN_OK); /* every appended row on disk */
  char *h5 = mrn_path_join(dir, "open.h5");
  char *out = mrn_path_join(dir, "open.txt");
  char cmd[1024];
  snprintf(cmd, sizeof cmd, "h5dump -d /step -y -w0 '%s' > '%s' 2>&1", h5, out);
  CHECK(system(cmd) == 0);
  FILE *fp = fopen(out, "r");
  char text[4096] = "";
  if (fp) {
    text[fread(text, 1, sizeof text - 1, fp)] = '\0';
    fclose(fp);
  }
  CHECK(strstr(text, "0, 10, 20, 30, 40") != NULL);
  if (!strstr(text, "0, 10, 20, 30, 40")) fprintf(stderr, "h5dump said:\n%s\n", text);
  CHECK(pair_close(&p) == MRN_OK);
  free(h5);
  free(out);
}

/* A child appends rows, flushes, stages one more and is killed: the file it
 * leaves holds every appended row and nothing of the staged one. */
static int write_killed(const char *dir, long rows) {
  pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    pair p = {0};
    if (pair_open(&p, dir, "killed") != MRN_OK) _exit(3);
    for (long r = 0; r < rows; r++)
      if (pair_row(&p, r) != MRN_OK) _exit(4);
    if (mrn_series_flush(p.s) != MRN_OK) _exit(6);
    mrn_series_set(p.s, "runout", 99.0); /* staged, never appended */
    mrn_series_set(p.s, "never_appended", 1.0);
    raise(SIGKILL);
    _exit(5);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL ? 0 : -1;
}

static void test_killed(const char *dir) {
  CHECK(write_killed(dir, 6) == 0);
  char *h5 = mrn_path_join(dir, "killed.h5");
  mrn_h5r r;
  CHECK(mrn_h5r_open(&r, h5) == MRN_OK);
  double *t = read_doubles(&r, "/time", 6);
  double *ro = read_doubles(&r, "/runout", 6);
  CHECK(t && t[5] == 0.5);
  CHECK(ro && isnan(ro[2]) && ro[5] == 2.0 + 5 / 9.0);
  CHECK(mrn_h5r_exists(&r, "/never_appended") == 0); /* staged only: not in the file */
  CHECK(r.failed == 0);
  mrn_h5r_close(&r);
  free(t);
  free(ro);
  free(h5);
}

/* ---- files for check_series_h5.py ------------------------------------------------ */

static int write_for_python(const char *dir) {
  if (mrn_mkdir_p(dir) != MRN_OK) return MRN_ERR_IO;
  pair p = {0};
  int rc = pair_open(&p, dir, "series");
  for (long r = 0; rc == MRN_OK && r < 40; r++) rc = pair_row(&p, r);
  if (p.s) {
    int crc = pair_close(&p);
    if (rc == MRN_OK) rc = crc;
  }
  if (rc == MRN_OK && write_killed(dir, 6) != 0)
    rc = mrn_error_code(MRN_ERR_IO, "the killed writer did not die by SIGKILL");
  return rc;
}

int main(int argc, char **argv) {
  char dir[64];
  if (make_temp_dir(dir, sizeof dir, "/tmp/moraine_test_series") != 0) return 1;
  test_rows_and_padding(dir);
  test_many_rows(dir);
  test_errors(dir);
  test_readable_while_open(dir);
  test_killed(dir);
  CHECK(count_temp_files(dir) == 0);
  remove_tree(dir);

  if (argc > 1) {
    int rc = write_for_python(argv[1]);
    if (rc != MRN_OK) fprintf(stderr, "%s\n", mrn_error_message());
    CHECK(rc == MRN_OK);
    CHECK(count_temp_files(argv[1]) == 0);
  }
  CHECK_DONE();
}
