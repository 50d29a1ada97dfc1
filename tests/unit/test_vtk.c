/* moraine: the VTK writers and the atomic file layer.
 *
 * Writes small .vtp/.pvd files into a fresh directory under /tmp and reads
 * the binary ones back by parsing the appended section. With a directory as
 * argv[1] it also leaves roundtrip files there for
 * tests/python/test_vtk_roundtrip.py, which reads them with VTK itself. */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "testfs.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/vtk.h"
#include "io/vtkhdf.h"

/* ---- deterministic test data (mirrored in test_vtk_roundtrip.py) -------- */

#define NPTS 37

typedef struct sample {
  double points[NPTS * 3];
  double stress[NPTS * 6]; /* a symmetric tensor: 6 components */
  double mass[NPTS];
  int32_t material[NPTS];
  int64_t id[NPTS];
  mrn_vtk_array arrays[4];
} sample;

static void make_sample(sample *s) {
  for (int i = 0; i < NPTS; i++) {
    s->points[3 * i + 0] = i * 0.25;
    s->points[3 * i + 1] = -i * 0.125;
    s->points[3 * i + 2] = 1.0 / (i + 1); /* not exact in binary: tests %.17g */
    for (int c = 0; c < 6; c++) s->stress[6 * i + c] = i * 0.5 + c;
    s->mass[i] = 0.1 * i;
    s->material[i] = -i;
    s->id[i] = (int64_t)i * 4294967296LL + i; /* beyond 32 bits */
  }
  s->arrays[0] = (mrn_vtk_array){.name = "stress", .ncomp = 6, .type = MRN_VTK_FLOAT64, .data = s->stress};
  s->arrays[1] = (mrn_vtk_array){.name = "mass", .ncomp = 1, .type = MRN_VTK_FLOAT64, .data = s->mass};
  s->arrays[2] = (mrn_vtk_array){.name = "material", .ncomp = 1, .type = MRN_VTK_INT32, .data = s->material};
  s->arrays[3] = (mrn_vtk_array){.name = "id", .ncomp = 1, .type = MRN_VTK_INT64, .data = s->id};
}

/* ---- reading the appended section back --------------------------------- */

static int block_equals(const char *file, size_t len, const char *name, const void *expect, size_t size) {
  uint64_t nbytes = 0;
  const unsigned char *p = appended_block(file, len, name, &nbytes);
  return p && nbytes == size && memcmp(p, expect, size) == 0;
}

/* ---- tests ------------------------------------------------------------- */

static void test_binary(const char *dir, const sample *s) {
  char *path = mrn_path_join(dir, "p.vtp");
  CHECK(mrn_vtp_write(path, NPTS, s->points, s->arrays, 4, MRN_VTK_BINARY) == MRN_OK);
  size_t len = 0;
  char *file = read_all(path, &len);
  CHECK(file != NULL);
  if (file) {
    CHECK(strstr(file, "header_type=\"UInt64\"") != NULL);
    CHECK(strstr(file, "NumberOfPoints=\"37\" NumberOfVerts=\"37\"") != NULL);
    CHECK(strstr(file, "Name=\"stress\" NumberOfComponents=\"6\" format=\"appended\"") != NULL);
    CHECK(block_equals(file, len, "stress", s->stress, sizeof s->stress));
    CHECK(block_equals(file, len, "mass", s->mass, sizeof s->mass));
    CHECK(block_equals(file, len, "material", s->material, sizeof s->material));
    CHECK(block_equals(file, len, "id", s->id, sizeof s->id));
    CHECK(block_equals(file, len, "Points", s->points, sizeof s->points));
    int64_t conn[NPTS], offs[NPTS];
    for (int i = 0; i < NPTS; i++) conn[i] = i, offs[i] = i + 1;
    CHECK(block_equals(file, len, "connectivity", conn, sizeof conn));
    CHECK(block_equals(file, len, "offsets", offs, sizeof offs));
    CHECK(len > 11 && strcmp(file + len - 11, "</VTKFile>\n") == 0);
  }
  free(file);
  free(path);
}

static void test_ascii(const char *dir, const sample *s) {
  char *path = mrn_path_join(dir, "a.vtp");
  CHECK(mrn_vtp_write(path, NPTS, s->points, s->arrays, 4, MRN_VTK_ASCII) == MRN_OK);
  char *file = read_all(path, NULL);
  CHECK(file != NULL);
  if (file) {
    CHECK(strstr(file, "format=\"ascii\"") != NULL);
    CHECK(strstr(file, "format=\"appended\"") == NULL);
    CHECK(strstr(file, "AppendedData") == NULL);
    char expect[64];
    snprintf(expect, sizeof expect, "%.17g", s->points[3 * 2 + 2]); /* 1/3 */
    CHECK(strstr(file, expect) != NULL);
    snprintf(expect, sizeof expect, "%lld\n", (long long)s->id[NPTS - 1]);
    CHECK(strstr(file, expect) != NULL);
  }
  free(file);
  free(path);
}

static void test_empty(const char *dir) {
  char *path = mrn_path_join(dir, "empty.vtp");
  double dummy = 0;
  mrn_vtk_array a = {.name = "mass", .ncomp = 1, .type = MRN_VTK_FLOAT64, .data = NULL};
  CHECK(mrn_vtp_write(path, 0, NULL, &a, 1, MRN_VTK_BINARY) == MRN_OK);
  size_t len = 0;
  char *file = read_all(path, &len);
  uint64_t nbytes = 1;
  CHECK(file && strstr(file, "NumberOfPoints=\"0\"") != NULL);
  CHECK(file && appended_block(file, len, "Points", &nbytes) != NULL && nbytes == 0);
  free(file);
  CHECK(mrn_vtp_write(path, 0, &dummy, NULL, 0, MRN_VTK_ASCII) == MRN_OK);
  free(path);
}

static void test_pvd(const char *dir) {
  char *path = mrn_path_join(dir, "series.pvd");
  mrn_pvd pvd;
  mrn_pvd_init(&pvd, path);
  CHECK(mrn_pvd_add(&pvd, 0.0, "p.vtp") == MRN_OK);
  CHECK(mrn_pvd_add(&pvd, 0.1, "sub/a&b.vtp") == MRN_OK);
  CHECK(pvd.count == 2);
  char *file = read_all(path, NULL);
  CHECK(file != NULL);
  if (file) {
    CHECK(strstr(file, "<VTKFile type=\"Collection\"") != NULL);
    CHECK(count_occurrences(file, "<DataSet ") == 2);
    CHECK(strstr(file, "<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"p.vtp\"/>") != NULL);
    CHECK(strstr(file, "timestep=\"0.10000000000000001\"") != NULL);
    CHECK(strstr(file, "file=\"sub/a&amp;b.vtp\"") != NULL); /* escaped, still parseable */
    CHECK(strstr(file, "</Collection>\n</VTKFile>\n") != NULL);
  }
  free(file);
  mrn_pvd_free(&pvd);
  CHECK(pvd.path == NULL && pvd.count == 0);
  mrn_pvd_free(&pvd); /* a second free is harmless */

  /* a failed rewrite leaves the collection as it was */
  char *bad = mrn_path_join(dir, "missing/series.pvd");
  mrn_pvd_init(&pvd, bad);
  CHECK(mrn_pvd_add(&pvd, 1.0, "x.vtp") == MRN_ERR_IO);
  CHECK(pvd.count == 0);
  mrn_pvd_free(&pvd);
  free(bad);
  free(path);
}

static void test_missing_dir(const char *dir, const sample *s) {
  char *path = mrn_path_join(dir, "nope/deeper/p.vtp");
  mrn_error_clear();
  CHECK(mrn_vtp_write(path, NPTS, s->points, s->arrays, 4, MRN_VTK_BINARY) == MRN_ERR_IO);
  CHECK(strstr(mrn_error_message(), path) != NULL);
  CHECK(strstr(mrn_error_message(), "No such file or directory") != NULL);
  free(path);
}

static void test_atomic(const char *dir) {
  char *path = mrn_path_join(dir, "aborted.txt");
  mrn_atomic_file f;
  CHECK(mrn_atomic_open(&f, path) == MRN_OK);
  CHECK(strstr(f.temp_path, "/.aborted.txt.tmp.") != NULL);
  fputs("partial", f.fp);
  CHECK(!exists(path)); /* nothing visible under the final name yet */
  mrn_atomic_abort(&f);
  CHECK(!exists(path));

  CHECK(mrn_atomic_open(&f, path) == MRN_OK);
  fputs("whole\n", f.fp);
  CHECK(mrn_atomic_commit(&f) == MRN_OK);
  char *text = read_all(path, NULL);
  CHECK(text && strcmp(text, "whole\n") == 0);
  free(text);
  CHECK(f.fp == NULL && f.temp_path == NULL && f.final_path == NULL);
  free(path);
}

static void test_mkdir_p(const char *dir) {
  char *nested = mrn_path_join(dir, "a/b//c/");
  CHECK(mrn_mkdir_p(nested) == MRN_OK);
  CHECK(mrn_mkdir_p(nested) == MRN_OK); /* existing directories are fine */
  char *c = mrn_path_join(dir, "a/b/c");
  struct stat st;
  CHECK(stat(c, &st) == 0 && S_ISDIR(st.st_mode));

  /* a component that is a file */
  char *file = mrn_path_join(dir, "a/plain");
  make_empty_file(file);
  char *below = mrn_path_join(dir, "a/plain/d");
  CHECK(mrn_mkdir_p(below) == MRN_ERR_IO);
  CHECK(strstr(mrn_error_message(), below) != NULL);
  CHECK(mrn_mkdir_p(file) == MRN_ERR_IO);
  CHECK(mrn_mkdir_p("") == MRN_OK);
  free(nested);
  free(c);
  free(file);
  free(below);
}

static void test_path_join(void) {
  char *p;
  CHECK((p = mrn_path_join("out", "p.vtp")) && strcmp(p, "out/p.vtp") == 0);
  free(p);
  CHECK((p = mrn_path_join("out/", "p.vtp")) && strcmp(p, "out/p.vtp") == 0);
  free(p);
  CHECK((p = mrn_path_join("", "p.vtp")) && strcmp(p, "p.vtp") == 0);
  free(p);
  CHECK((p = mrn_path_join(NULL, "p.vtp")) && strcmp(p, "p.vtp") == 0);
  free(p);
  CHECK((p = mrn_path_join("out", "/abs/p.vtp")) && strcmp(p, "/abs/p.vtp") == 0);
  free(p);
}

/* A file of several zlib blocks: 20,000 points with a 6-component field
 * (960,000 bytes, 15 blocks of MRN_VTK_ZLIB_BLOCK), raw and compressed. */
static int write_big(const char *dir) {
  enum { N = 20000 };
  double *points = malloc(3 * N * sizeof(double)), *stress = malloc(6 * N * sizeof(double));
  int rc = points && stress ? MRN_OK : MRN_ERR_IO;
  for (size_t i = 0; rc == MRN_OK && i < N; i++) {
    for (int c = 0; c < 3; c++) points[3 * i + c] = 1e-3 * (double)i + c;
    for (int c = 0; c < 6; c++) stress[6 * i + c] = sin(1e-3 * (double)i * (c + 1)); /* smooth, not exact */
  }
  const mrn_vtk_array a = {.name = "stress", .ncomp = 6, .type = MRN_VTK_FLOAT64, .data = stress};
  const mrn_vtp_options raw = {0}, zlib = {.compress = 6};
  char *pr = mrn_path_join(dir, "big.vtp"), *pz = mrn_path_join(dir, "big_zlib.vtp");
  if (rc == MRN_OK) rc = mrn_vtp_write_with(pr, N, points, &a, 1, &raw);
  if (rc == MRN_OK) rc = mrn_vtp_write_with(pz, N, points, &a, 1, &zlib);
  free(pr), free(pz), free(points), free(stress);
  return rc;
}

/* VTKHDF files in the plain and the compressed Float32 forms, and a
 * ParaView file series listing them under names JSON must escape */
static int write_vtkhdf(const char *dir, const sample *s) {
  const struct { const char *name; mrn_vtp_options o; size_t n; } forms[] = {
      {"roundtrip.vtkhdf", {.has_time = 1, .time = 0.125}, NPTS},
      {"roundtrip_empty.vtkhdf", {0}, 0},
      {"roundtrip_zlib_f32.vtkhdf", {.compress = 6, .float32 = 1, .has_time = 1, .time = 0.25}, NPTS},
      {"roundtrip_zlib_empty.vtkhdf", {.compress = 6}, 0},
  };
  int rc = MRN_OK;
  for (size_t k = 0; k < sizeof forms / sizeof forms[0] && rc == MRN_OK; k++) {
    char *path = mrn_path_join(dir, forms[k].name);
    rc = mrn_vtkhdf_write(path, forms[k].n, forms[k].n ? s->points : NULL, s->arrays, 4, &forms[k].o);
    free(path);
  }
  char *series_path = mrn_path_join(dir, "roundtrip.vtkhdf.series");
  mrn_pvd series;
  mrn_file_series_init(&series, series_path);
  if (rc == MRN_OK) rc = mrn_pvd_add(&series, 0.125, "roundtrip.vtkhdf");
  if (rc == MRN_OK) rc = mrn_pvd_add(&series, 0.25, "roundtrip_zlib_f32.vtkhdf");
  if (rc == MRN_OK) rc = mrn_pvd_add(&series, 1e-300, "odd \"name\"\\\t.vtkhdf");
  mrn_pvd_free(&series);
  free(series_path);
  return rc;
}

/* files for the Python check with the real VTK reader */
static int write_roundtrip(const char *dir, const sample *s) {
  if (mrn_mkdir_p(dir) != MRN_OK) return MRN_ERR_IO;
  char *bin = mrn_path_join(dir, "roundtrip.vtp");
  char *asc = mrn_path_join(dir, "roundtrip_ascii.vtp");
  char *empty = mrn_path_join(dir, "roundtrip_empty.vtp");
  char *pvd_path = mrn_path_join(dir, "roundtrip.pvd");
  int rc = mrn_vtp_write(bin, NPTS, s->points, s->arrays, 4, MRN_VTK_BINARY);
  if (rc == MRN_OK) rc = mrn_vtp_write(asc, NPTS, s->points, s->arrays, 4, MRN_VTK_ASCII);
  if (rc == MRN_OK) rc = mrn_vtp_write(empty, 0, NULL, s->arrays, 4, MRN_VTK_BINARY);
  /* the other forms: zlib, Float32 (raw, zlib, ASCII), a time, and an empty compressed file */
  const struct { const char *name; mrn_vtp_options o; size_t n; } forms[] = {
      {"roundtrip_zlib.vtp", {.compress = 6}, NPTS},
      {"roundtrip_f32.vtp", {.float32 = 1}, NPTS},
      {"roundtrip_f32_zlib.vtp", {.float32 = 1, .compress = 1}, NPTS},
      {"roundtrip_f32_ascii.vtp", {.encoding = MRN_VTK_ASCII, .float32 = 1}, NPTS},
      {"roundtrip_time.vtp", {.compress = 9, .has_time = 1, .time = 0.125}, NPTS},
      {"roundtrip_empty_zlib.vtp", {.compress = 6}, 0},
  };
  for (size_t k = 0; k < sizeof forms / sizeof forms[0] && rc == MRN_OK; k++) {
    char *path = mrn_path_join(dir, forms[k].name);
    rc = mrn_vtp_write_with(path, forms[k].n, forms[k].n ? s->points : NULL, s->arrays, 4, &forms[k].o);
    free(path);
  }
  if (rc == MRN_OK) rc = write_big(dir);
  if (rc == MRN_OK) rc = write_vtkhdf(dir, s);
  mrn_pvd pvd;
  mrn_pvd_init(&pvd, pvd_path);
  if (rc == MRN_OK) rc = mrn_pvd_add(&pvd, 0.0, "roundtrip.vtp");
  if (rc == MRN_OK) rc = mrn_pvd_add(&pvd, 0.25, "roundtrip_ascii.vtp");
  if (rc == MRN_OK) rc = mrn_pvd_add(&pvd, 1.0 / 3.0, "roundtrip_empty.vtp");
  mrn_pvd_free(&pvd);
  free(bin);
  free(asc);
  free(empty);
  free(pvd_path);
  return rc;
}

/* Arrays made on demand (mrn_vtk_array.fill) give the file that held arrays
 * give, byte for byte, in both encodings; with 25,000 points a 6-component
 * array takes three fills (at most MRN_VTK_FILL_POINTS(6) = 10,922 points
 * each), the others one. Each fill must be asked for a range in order,
 * within the points, and no larger than promised. */
enum { BIG = 25000 };
typedef struct fill_log {
  const double *values;
  int ncomp;
  size_t next, calls, max_count;
  int ok;
} fill_log;

static void fill_doubles(const void *ctx, size_t first, size_t count, void *out) {
  fill_log *log = (fill_log *)ctx;
  log->ok &= first == log->next % BIG && first + count <= BIG && count <= MRN_VTK_FILL_POINTS(log->ncomp);
  memcpy(out, log->values + first * (size_t)log->ncomp, count * (size_t)log->ncomp * sizeof(double));
  log->next = first + count;
  log->calls++;
}

static void test_fill(const char *dir) {
  double *points = malloc(3 * BIG * sizeof(double)), *stress = malloc(6 * BIG * sizeof(double));
  double *mass = malloc(BIG * sizeof(double));
  for (size_t i = 0; i < BIG; i++) {
    for (int c = 0; c < 3; c++) points[3 * i + c] = 0.001 * (double)i + c;
    for (int c = 0; c < 6; c++) stress[6 * i + c] = 1.0 / (double)(i + 1) + c;
    mass[i] = 0.5 + 1e-3 * (double)i;
  }
  static const char *const form_names[] = {"binary", "ASCII", "zlib"};
  for (int enc = 0; enc < 3; enc++) {
    const mrn_vtp_options e = {.encoding = enc == 1 ? MRN_VTK_ASCII : MRN_VTK_BINARY, .compress = enc == 2 ? 6 : 0};
    mrn_vtk_array held[2] = {{.name = "stress", .ncomp = 6, .type = MRN_VTK_FLOAT64, .data = stress},
                             {.name = "mass", .ncomp = 1, .type = MRN_VTK_FLOAT64, .data = mass}};
    fill_log ls = {stress, 6, 0, 0, 0, 1}, lm = {mass, 1, 0, 0, 0, 1};
    mrn_vtk_array made[2] = {{.name = "stress", .ncomp = 6, .type = MRN_VTK_FLOAT64, .fill = fill_doubles, .ctx = &ls},
                             {.name = "mass", .ncomp = 1, .type = MRN_VTK_FLOAT64, .fill = fill_doubles, .ctx = &lm}};
    char *a = mrn_path_join(dir, "held.vtp"), *b = mrn_path_join(dir, "made.vtp");
    CHECK(mrn_vtp_write_with(a, BIG, points, held, 2, &e) == MRN_OK);
    CHECK(mrn_vtp_write_with(b, BIG, points, made, 2, &e) == MRN_OK);
    size_t la = 0, lb = 0;
    char *fa = read_all(a, &la), *fb = read_all(b, &lb);
    /* raw and ASCII hold every value; zlib packs these smooth arrays */
    CHECK(fa && fb && la == lb && memcmp(fa, fb, la) == 0);
    CHECK(enc == 2 ? la < BIG * 7 * sizeof(double) : la > BIG * 7 * sizeof(double));
    CHECK(ls.ok && lm.ok);
    CHECK(ls.calls == 3 && lm.calls == 1);
    printf("on-demand arrays, %s: %zu bytes, the same as held arrays: %s (fills: stress %zu, mass %zu)\n",
           form_names[enc], lb, fa && fb && la == lb && memcmp(fa, fb, la) == 0 ? "yes" : "no", ls.calls,
           lm.calls);
    free(fa), free(fb), free(a), free(b);
  }
  free(points), free(stress), free(mass);
}

int main(int argc, char **argv) {
  static sample s;
  make_sample(&s);
  char dir[64];
  if (make_temp_dir(dir, sizeof dir, "/tmp/moraine_test_vtk") != 0) return 1;
  test_binary(dir, &s);
  test_ascii(dir, &s);
  test_empty(dir);
  test_fill(dir);
  test_pvd(dir);
  test_missing_dir(dir, &s);
  test_atomic(dir);
  test_mkdir_p(dir);
  test_path_join();
  CHECK(count_temp_files(dir) == 0);
  remove_tree(dir);

  if (argc > 1) {
    int rc = write_roundtrip(argv[1], &s);
    if (rc != MRN_OK) fprintf(stderr, "%s\n", mrn_error_message());
    CHECK(rc == MRN_OK);
    CHECK(count_temp_files(argv[1]) == 0);
  }
  CHECK_DONE();
}
