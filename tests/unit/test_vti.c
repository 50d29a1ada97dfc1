/* moraine: the grid as VTK ImageData (.vti).
 *
 *   test_vti            unit checks in a fresh directory under /tmp
 *   test_vti DIR        also leaves grid files in DIR for
 *                       tests/python/check_vti.py, which reads them with VTK
 *   test_vti --bench [DIR]
 *                       times writing a 1000 x 1000 grid (not a ctest test)
 *
 * The node values follow node_value() below, mirrored in check_vti.py; ghost
 * nodes hold -999 so that any of them reaching a file shows. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "testfs.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/vti.h"

/* ---- a grid with known values ------------------------------------------- */

#define GHOST_VALUE (-999.0)

/* value of component c of array a (0 mass, 1 velocity, 2 force) at node (i, j, k) */
static double node_value(int a, int c, int i, int j, int k) {
  return (a + 1) * 1000.0 + c * 0.25 + i + 10.0 * j + 100.0 * k + 1.0 / (i + j + k + 3); /* 1/3, 1/7: not exact */
}

static int in_domain(const mrn_grid *g, const int ijk[3]) {
  for (int d = 0; d < g->dim; d++)
    if (ijk[d] < 0 || ijk[d] > g->ncell[d]) return 0;
  return 1;
}

static void fill_grid(mrn_grid *g) {
  double *arrays[3] = {g->mass, g->vel, g->force};
  const int ncomp[3] = {1, 3, 3};
  for (size_t n = 0; n < g->n; n++) {
    int ijk[3];
    mrn_grid_node_ijk(g, n, ijk);
    int inside = in_domain(g, ijk);
    for (int a = 0; a < 3; a++)
      for (int c = 0; c < ncomp[a]; c++)
        arrays[a][ncomp[a] * n + c] = inside ? node_value(a, c, ijk[0], ijk[1], ijk[2]) : GHOST_VALUE;
  }
}

static int make_grid(mrn_grid *g, int dim) {
  const double origin[3] = {-1.0, 2.0, 0.5};
  const double size[3] = {2.0, 1.5, 1.0}; /* 4 x 3 (x 2) cells of 0.5 */
  int rc = mrn_grid_init(g, dim, origin, size, 0.5);
  if (rc == MRN_OK) fill_grid(g);
  return rc;
}

/* the domain nodes of array a in file order (x fastest), as the file must hold them */
static double *expected_array(const mrn_grid *g, int a, int ncomp, size_t *count) {
  int np[3];
  for (int d = 0; d < 3; d++) np[d] = d < g->dim ? g->ncell[d] + 1 : 1;
  size_t n = (size_t)np[0] * np[1] * np[2] * ncomp, m = 0;
  double *out = malloc(n * sizeof *out);
  for (int k = 0; k < np[2]; k++)
    for (int j = 0; j < np[1]; j++)
      for (int i = 0; i < np[0]; i++)
        for (int c = 0; c < ncomp; c++) out[m++] = node_value(a, c, i, j, k);
  *count = n;
  return out;
}

static int block_matches(const char *file, size_t len, const mrn_grid *g, const char *name, int a, int ncomp) {
  size_t count;
  double *expect = expected_array(g, a, ncomp, &count);
  uint64_t nbytes = 0;
  const unsigned char *p = appended_block(file, len, name, &nbytes);
  int ok = p && nbytes == count * sizeof(double) && memcmp(p, expect, nbytes) == 0;
  free(expect);
  return ok;
}

/* ---- tests ------------------------------------------------------------- */

static void test_binary(const char *dir, const mrn_grid *g, const char *file_name, const char *extent,
                        const char *spacing) {
  char *path = mrn_path_join(dir, file_name);
  CHECK(mrn_vti_write_grid(path, g, 0.125, MRN_VTK_BINARY) == MRN_OK);
  size_t len = 0;
  char *file = read_all(path, &len);
  CHECK(file != NULL);
  if (file) {
    char key[160];
    CHECK(strstr(file, "<VTKFile type=\"ImageData\"") != NULL);
    CHECK(strstr(file, "header_type=\"UInt64\"") != NULL);
    snprintf(key, sizeof key, "WholeExtent=\"%s\"", extent);
    CHECK(strstr(file, key) != NULL);
    snprintf(key, sizeof key, "<Piece Extent=\"%s\">", extent);
    CHECK(strstr(file, key) != NULL);
    snprintf(key, sizeof key, "Spacing=\"%s\"", spacing);
    CHECK(strstr(file, key) != NULL);
    CHECK(strstr(file, "Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">0.125<") != NULL);
    CHECK(strstr(file, "Name=\"velocity\" NumberOfComponents=\"3\" format=\"appended\"") != NULL);
    CHECK(block_matches(file, len, g, "mass", 0, 1));
    CHECK(block_matches(file, len, g, "velocity", 1, 3));
    CHECK(block_matches(file, len, g, "force", 2, 3));
    CHECK(len > 11 && strcmp(file + len - 11, "</VTKFile>\n") == 0);
  }
  free(file);
  free(path);
}

static void test_ascii_and_no_time(const char *dir, const mrn_grid *g) {
  char *path = mrn_path_join(dir, "ascii.vti");
  CHECK(mrn_vti_write_grid(path, g, NAN, MRN_VTK_ASCII) == MRN_OK);
  char *file = read_all(path, NULL);
  CHECK(file != NULL);
  if (file) {
    CHECK(strstr(file, "format=\"ascii\"") != NULL);
    CHECK(strstr(file, "AppendedData") == NULL);
    CHECK(strstr(file, "TimeValue") == NULL); /* NAN: no time */
    CHECK(strstr(file, "-999") == NULL);      /* no ghost node */
    char expect[128];
    /* the last node's velocity, one node per line */
    snprintf(expect, sizeof expect, "%.17g %.17g %.17g\n", node_value(1, 0, 4, 3, 0), node_value(1, 1, 4, 3, 0),
             node_value(1, 2, 4, 3, 0));
    CHECK(strstr(file, expect) != NULL);
  }
  free(file);
  free(path);
}

/* arrays of any type through the generic call */
static void test_generic(const char *dir, const mrn_grid *g) {
  int32_t *index = malloc(g->n * sizeof *index);
  for (size_t n = 0; n < g->n; n++) index[n] = (int32_t)n;
  mrn_vtk_array a = {.name = "node", .ncomp = 1, .type = MRN_VTK_INT32, .data = index};
  char *path = mrn_path_join(dir, "generic.vti");
  CHECK(mrn_vti_write(path, g, 1.0, &a, 1, MRN_VTK_BINARY) == MRN_OK);
  size_t len = 0;
  char *file = read_all(path, &len);
  uint64_t nbytes = 0;
  const unsigned char *p = file ? appended_block(file, len, "node", &nbytes) : NULL;
  CHECK(p != NULL && nbytes == 5 * 4 * sizeof(int32_t));
  if (p) {
    int32_t first, last;
    memcpy(&first, p, 4);
    memcpy(&last, p + nbytes - 4, 4);
    CHECK(first == (int32_t)mrn_grid_index(g, 0, 0, 0));
    CHECK(last == (int32_t)mrn_grid_index(g, 4, 3, 0));
  }
  CHECK(file && strstr(file, "type=\"Int32\" Name=\"node\"") != NULL);
  /* no arrays at all is still a valid image */
  CHECK(mrn_vti_write(path, g, 1.0, NULL, 0, MRN_VTK_BINARY) == MRN_OK);
  free(file);
  free(path);
  free(index);
}

static void test_errors(const char *dir, const mrn_grid *g) {
  char *path = mrn_path_join(dir, "nope/deeper/g.vti");
  mrn_error_clear();
  CHECK(mrn_vti_write_grid(path, g, 0.0, MRN_VTK_BINARY) == MRN_ERR_IO);
  CHECK(strstr(mrn_error_message(), path) != NULL);
  CHECK(strstr(mrn_error_message(), "No such file or directory") != NULL);
  free(path);

  path = mrn_path_join(dir, "bad.vti");
  mrn_vtk_array unnamed = {.name = "", .ncomp = 1, .type = MRN_VTK_FLOAT64, .data = g->mass};
  CHECK(mrn_vti_write(path, g, 0.0, &unnamed, 1, MRN_VTK_BINARY) == MRN_ERR_IO);
  CHECK(strstr(mrn_error_message(), "has no name") != NULL);
  mrn_vtk_array nodata = {.name = "mass", .ncomp = 1, .type = MRN_VTK_FLOAT64, .data = NULL};
  CHECK(mrn_vti_write(path, g, 0.0, &nodata, 1, MRN_VTK_BINARY) == MRN_ERR_IO);
  CHECK(mrn_vti_write_grid(path, NULL, 0.0, MRN_VTK_BINARY) == MRN_ERR_IO);
  struct stat st;
  CHECK(stat(path, &st) != 0); /* refused before any file was made */
  free(path);
}

/* ---- files for check_vti.py -------------------------------------------- */

static int write_roundtrip(const char *dir, const mrn_grid *g2, const mrn_grid *g3) {
  if (mrn_mkdir_p(dir) != MRN_OK) return MRN_ERR_IO;
  const char *names[] = {"grid2d.vti", "grid2d_ascii.vti", "grid3d.vti"};
  char *paths[3];
  for (int i = 0; i < 3; i++) paths[i] = mrn_path_join(dir, names[i]);
  int rc = mrn_vti_write_grid(paths[0], g2, 0.0, MRN_VTK_BINARY);
  if (rc == MRN_OK) rc = mrn_vti_write_grid(paths[1], g2, 0.5, MRN_VTK_ASCII);
  if (rc == MRN_OK) rc = mrn_vti_write_grid(paths[2], g3, 0.25, MRN_VTK_BINARY);
  /* the two 2D files as a series, as a run lists its grid files */
  char *pvd_path = mrn_path_join(dir, "grid2d.pvd");
  mrn_pvd pvd;
  mrn_pvd_init(&pvd, pvd_path);
  if (rc == MRN_OK) rc = mrn_pvd_add(&pvd, 0.0, names[0]);
  if (rc == MRN_OK) rc = mrn_pvd_add(&pvd, 0.5, names[1]);
  mrn_pvd_free(&pvd);
  free(pvd_path);
  for (int i = 0; i < 3; i++) free(paths[i]);
  return rc;
}

/* ---- write speed --------------------------------------------------------- */

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* a 1000 x 1000 cell 2D grid (1001^2 nodes, mass + velocity + force): the
 * best of a few writes, including the fsync and rename of the atomic file */
static int bench(const char *dir) {
  mrn_grid g;
  const double origin[3] = {0, 0, 0}, size[3] = {1000, 1000, 0};
  if (mrn_grid_init(&g, 2, origin, size, 1.0) != MRN_OK) return 1;
  for (size_t n = 0; n < g.n; n++) {
    g.mass[n] = (double)n;
    for (int c = 0; c < 3; c++) g.vel[3 * n + c] = g.force[3 * n + c] = (double)n + c;
  }
  char *path = mrn_path_join(dir, "bench_grid.vti");
  double best = HUGE_VAL;
  for (int rep = 0; rep < 5; rep++) {
    double t0 = now_seconds();
    if (mrn_vti_write_grid(path, &g, 0.0, MRN_VTK_BINARY) != MRN_OK) {
      fprintf(stderr, "%s\n", mrn_error_message());
      return 1;
    }
    double t = now_seconds() - t0;
    if (t < best) best = t;
  }
  struct stat st;
  stat(path, &st);
  printf("vti 1000 x 1000 grid: %.1f MB in %.3f s = %.0f MB/s (best of 5, with fsync)\n", st.st_size / 1e6, best,
         st.st_size / 1e6 / best);
  unlink(path);
  free(path);
  mrn_grid_free(&g);
  return 0;
}

int main(int argc, char **argv) {
  if (argc > 1 && strcmp(argv[1], "--bench") == 0) return bench(argc > 2 ? argv[2] : "/tmp");
  mrn_grid g2, g3;
  if (make_grid(&g2, 2) != MRN_OK || make_grid(&g3, 3) != MRN_OK) {
    fprintf(stderr, "%s\n", mrn_error_message());
    return 1;
  }
  char dir[64];
  if (make_temp_dir(dir, sizeof dir, "/tmp/moraine_test_vti") != 0) return 1;
  test_binary(dir, &g2, "g2.vti", "0 4 0 3 0 0", "0.5 0.5 1");
  test_binary(dir, &g3, "g3.vti", "0 4 0 3 0 2", "0.5 0.5 0.5");
  test_ascii_and_no_time(dir, &g2);
  test_generic(dir, &g2);
  test_errors(dir, &g2);
  CHECK(count_temp_files(dir) == 0);
  remove_tree(dir);

  if (argc > 1) {
    int rc = write_roundtrip(argv[1], &g2, &g3);
    if (rc != MRN_OK) fprintf(stderr, "%s\n", mrn_error_message());
    CHECK(rc == MRN_OK);
    CHECK(count_temp_files(argv[1]) == 0);
  }
  mrn_grid_free(&g2);
  mrn_grid_free(&g3);
  CHECK_DONE();
}
