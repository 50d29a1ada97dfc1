/* moraine: regions and particle seeding. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "grid/grid.h"
#include "particles/region.h"
#include "particles/seed.h"

static const double PI = 3.14159265358979323846;

/* ---- helpers ----------------------------------------------------------- */

typedef struct {
  long calls;
  double volume;
  double first[4][3]; /* the first few points, to check the ordering */
  long stop_after;    /* return 7 on this call (1-based); 0 never */
} tally;

static int count_cb(void *user, const double x[3], double vol) {
  tally *t = user;
  if (t->calls < 4) memcpy(t->first[t->calls], x, sizeof t->first[0]);
  t->calls++;
  if (t->stop_after && t->calls == t->stop_after) return 7;
  t->volume += vol;
  return 0;
}

static void grid2(mrn_grid *g, double sx, double sy, double h) {
  double o[3] = {0, 0, 0}, s[3] = {sx, sy, 0};
  CHECK(mrn_grid_init(g, 2, o, s, h) == MRN_OK);
}

static void grid3(mrn_grid *g, double sx, double sy, double sz, double h) {
  double o[3] = {0, 0, 0}, s[3] = {sx, sy, sz};
  CHECK(mrn_grid_init(g, 3, o, s, h) == MRN_OK);
}

/* seeds r and returns the tally; *rc receives mrn_seed's result */
static tally seed(const mrn_grid *g, const mrn_region *r, int n, mrn_seed_placement p, int *rc, long *count) {
  tally t = {0};
  *rc = mrn_seed(g, r, n, p, count_cb, &t, count);
  return t;
}

static mrn_region *box2(double x0, double y0, double x1, double y1) {
  return mrn_region_box((double[3]){x0, y0, 0}, (double[3]){x1, y1, 0});
}

/* ---- Gauss-Legendre ---------------------------------------------------- */

static void test_gauss_legendre(void) {
  double x[8], w[8];
  mrn_gauss_legendre(2, x, w);
  CHECK_CLOSE(x[0], -1.0 / sqrt(3.0), 1e-15);
  CHECK_CLOSE(x[1], 1.0 / sqrt(3.0), 1e-15);
  CHECK_CLOSE(w[0], 1.0, 1e-15);
  CHECK_CLOSE(w[1], 1.0, 1e-15);

  mrn_gauss_legendre(3, x, w);
  CHECK_CLOSE(x[0], -sqrt(0.6), 1e-15);
  CHECK(x[1] == 0.0);
  CHECK_CLOSE(x[2], sqrt(0.6), 1e-15);
  CHECK_CLOSE(w[0], 5.0 / 9.0, 1e-15);
  CHECK_CLOSE(w[1], 8.0 / 9.0, 1e-15);
  CHECK_CLOSE(w[2], 5.0 / 9.0, 1e-15);
  CHECK(w[0] == 5.0 / 9.0 && w[1] == 8.0 / 9.0); /* correctly rounded */

  /* an n-point rule integrates polynomials up to degree 2n-1 exactly */
  for (int n = 1; n <= MRN_SEED_MAX_PER_AXIS; n++) {
    mrn_gauss_legendre(n, x, w);
    double sum = 0, odd = 0, even = 0;
    for (int i = 0; i < n; i++) {
      sum += w[i];
      odd += w[i] * pow(x[i], 2 * n - 1);
      even += w[i] * pow(x[i], 2 * n - 2);
      CHECK(x[i] > -1 && x[i] < 1 && w[i] > 0);
      if (i > 0) CHECK(x[i] > x[i - 1]);
    }
    CHECK_CLOSE(sum, 2.0, 1e-14);
    CHECK_CLOSE(odd, 0.0, 1e-14);
    CHECK_CLOSE(even, 2.0 / (2 * n - 1), 1e-14);
  }
}

/* ---- regions ----------------------------------------------------------- */

static void test_region_basics(void) {
  mrn_region *b = box2(0, 0, 2, 1);
  CHECK(b && b->refcount == 1);
  CHECK(mrn_region_contains(b, (double[3]){2, 1, 0}) == 1); /* boundary counts as inside */
  CHECK(mrn_region_contains(b, (double[3]){2.001, 1, 0}) == 0);
  CHECK(mrn_region_bounded(b, 3));

  mrn_region *poly = mrn_region_polygon((double[]){0, 0, 2, 0, 0, 2}, 3);
  CHECK(poly && poly->dim == 2);
  CHECK(mrn_region_bounded(poly, 2) && !mrn_region_bounded(poly, 3));
  CHECK(mrn_region_contains(poly, (double[3]){0.5, 0.5, 0}) == 1);
  CHECK(mrn_region_contains(poly, (double[3]){1.5, 1.5, 0}) == 0);
  CHECK(mrn_region_contains(poly, (double[3]){0.5, 0.5, 100}) == 1); /* z is ignored */

  mrn_region *cyl = mrn_region_cylinder((double[3]){0, 0, 0}, (double[3]){0, 0, 1}, 0.5);
  CHECK(cyl && mrn_region_contains(cyl, (double[3]){0.4, 0, 0.5}) == 1);
  CHECK(mrn_region_contains(cyl, (double[3]){0.4, 0, 1.1}) == 0); /* flat ends, no caps */
  CHECK(mrn_region_contains(cyl, (double[3]){0.4, 0.4, 0.5}) == 0);
  CHECK_CLOSE(cyl->lo[0], -0.5, 0);
  CHECK_CLOSE(cyl->hi[2], 1.5, 0);

  mrn_region *u = mrn_region_combine(MRN_REGION_UNION, b, poly);
  CHECK(u && b->refcount == 2 && poly->refcount == 2 && u->dim == 2);
  CHECK(u->lo[0] == 0 && u->hi[0] == 2 && u->hi[1] == 2);
  mrn_region *i = mrn_region_combine(MRN_REGION_INTERSECTION, b, poly);
  CHECK(i && i->hi[1] == 1 && i->lo[2] == 0 && i->hi[2] == 0);
  mrn_region *d = mrn_region_combine(MRN_REGION_DIFFERENCE, poly, b);
  CHECK(d && d->hi[1] == 2);
  CHECK(mrn_region_contains(d, (double[3]){0.5, 0.5, 0}) == 0);
  CHECK(mrn_region_contains(d, (double[3]){0.5, 1.2, 0}) == 1);
  CHECK(mrn_region_combine(MRN_REGION_BOX, b, poly) == NULL);
  CHECK(mrn_region_combine(MRN_REGION_UNION, b, NULL) == NULL);

  mrn_region_unref(u);
  mrn_region_unref(i);
  mrn_region_unref(d);
  CHECK(b->refcount == 1 && poly->refcount == 1);
  mrn_region_unref(b);
  mrn_region_unref(poly);
  mrn_region_unref(cyl);
  mrn_region_unref(NULL);
}

static void test_region_errors(void) {
  CHECK(box2(0, 3, 1, 1) == NULL);
  CHECK(strstr(mrn_error_message(), "min[2] = 3 is not below max[2] = 1") != NULL);
  CHECK(mrn_region_box((double[3]){0, 0, 0}, (double[3]){1, NAN, 0}) == NULL);
  CHECK(mrn_region_box((double[3]){0, 0, 1}, (double[3]){1, 1, 0}) == NULL);
  CHECK(strstr(mrn_error_message(), "min[3]") != NULL);
  CHECK(mrn_region_sphere((double[3]){0, 0, 0}, 0) == NULL);
  CHECK(strstr(mrn_error_message(), "radius") != NULL);
  CHECK(mrn_region_sphere((double[3]){0, 0, 0}, INFINITY) == NULL);
  CHECK(mrn_region_sphere((double[3]){NAN, 0, 0}, 1) == NULL);
  CHECK(mrn_region_cylinder((double[3]){1, 1, 1}, (double[3]){1, 1, 1}, 1) == NULL);
  CHECK(strstr(mrn_error_message(), "differ") != NULL);
  CHECK(mrn_region_cylinder((double[3]){0, 0, 0}, (double[3]){1, 1, 1}, -1) == NULL);
  CHECK(mrn_region_polygon((double[]){0, 0, 1, 0}, 2) == NULL);
  CHECK(strstr(mrn_error_message(), "at least 3") != NULL);
  CHECK(mrn_region_polygon((double[]){0, 0, 1, 0, 1, INFINITY}, 3) == NULL);
  CHECK(mrn_region_predicate_new(NULL, NULL, NULL) == NULL);
}

/* ---- seeding ----------------------------------------------------------- */

static void test_seed_box(void) {
  mrn_grid g;
  grid2(&g, 4, 3, 1);
  mrn_region *b = box2(0, 0, 4, 3);
  for (int p = MRN_SEED_GAUSS; p <= MRN_SEED_REGULAR; p++) {
    int rc;
    long count = -1;
    tally t = seed(&g, b, 2, (mrn_seed_placement)p, &rc, &count);
    CHECK(rc == MRN_OK);
    CHECK(count == 48 && t.calls == 48);
    CHECK_CLOSE(t.volume, 12.0, 1e-12);
  }
  /* z outermost, then y, then x, with sub-points nested the same way within
   * each half-cell */
  int rc;
  long count;
  tally t = seed(&g, b, 2, MRN_SEED_REGULAR, &rc, &count);
  const double want[4][2] = {{0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}};
  for (int k = 0; k < 4; k++) {
    CHECK_CLOSE(t.first[k][0], want[k][0], 1e-15);
    CHECK_CLOSE(t.first[k][1], want[k][1], 1e-15);
    CHECK(t.first[k][2] == 0.0);
  }
  /* within a cell by half-cells: the lower-left quadrant's 2 x 2 first
   * (per_axis 4); with 3 per axis the centre counts as the upper half */
  const double want4[4][2] = {{0.125, 0.125}, {0.375, 0.125}, {0.125, 0.375}, {0.375, 0.375}};
  t = seed(&g, b, 4, MRN_SEED_REGULAR, &rc, &count);
  for (int k = 0; k < 4; k++) {
    CHECK_CLOSE(t.first[k][0], want4[k][0], 1e-15);
    CHECK_CLOSE(t.first[k][1], want4[k][1], 1e-15);
  }
  t = seed(&g, b, 3, MRN_SEED_REGULAR, &rc, &count);
  const double want3[4][2] = {{1.0 / 6, 1.0 / 6}, {0.5, 1.0 / 6}, {5.0 / 6, 1.0 / 6}, {1.0 / 6, 0.5}};
  for (int k = 0; k < 4; k++) {
    CHECK_CLOSE(t.first[k][0], want3[k][0], 1e-15);
    CHECK_CLOSE(t.first[k][1], want3[k][1], 1e-15);
  }
  /* a callback that stops seeding: its value comes back, and the point it
   * refused is not counted */
  tally stop = {.stop_after = 5};
  CHECK(mrn_seed(&g, b, 2, MRN_SEED_GAUSS, count_cb, &stop, &count) == 7);
  CHECK(count == 4 && stop.calls == 5);
  /* a NULL callback only counts */
  CHECK(mrn_seed(&g, b, 3, MRN_SEED_GAUSS, NULL, NULL, &count) == MRN_OK && count == 108);
  mrn_region_unref(b);
  mrn_grid_free(&g);
}

static void test_seed_shapes_2d(void) {
  mrn_grid g;
  grid2(&g, 2, 2, 0.02);
  int rc;
  long count;

  mrn_region *disk = mrn_region_sphere((double[3]){1, 1, 0}, 0.5);
  tally t = seed(&g, disk, 2, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_OK && count > 0);
  CHECK(fabs(t.volume / (PI * 0.25) - 1) < 0.02);

  /* a triangle in both orientations (vertices off the lattice of candidates,
   * so that no candidate sits on an edge) */
  const double v[6] = {0.103, 0.107, 1.901, 0.109, 0.104, 1.903};
  double area = 0.5 * ((v[2] - v[0]) * (v[5] - v[1]) - (v[4] - v[0]) * (v[3] - v[1]));
  mrn_region *tri = mrn_region_polygon(v, 3);
  mrn_region *irt = mrn_region_polygon((double[]){v[4], v[5], v[2], v[3], v[0], v[1]}, 3);
  t = seed(&g, tri, 2, MRN_SEED_REGULAR, &rc, &count);
  CHECK(rc == MRN_OK);
  CHECK(fabs(t.volume / area - 1) < 0.02);
  long c2;
  tally t2 = seed(&g, irt, 2, MRN_SEED_REGULAR, &rc, &c2);
  CHECK(rc == MRN_OK && c2 == count && t2.volume == t.volume);

  /* a slanted 2D cylinder is a rotated rectangle 2r wide */
  mrn_region *cyl = mrn_region_cylinder((double[3]){0.5, 0.5, 0}, (double[3]){1.5, 1.5, 0}, 0.25);
  t = seed(&g, cyl, 2, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_OK);
  CHECK(fabs(t.volume / (0.5 * sqrt(2.0)) - 1) < 0.02);

  mrn_region_unref(disk);
  mrn_region_unref(tri);
  mrn_region_unref(irt);
  mrn_region_unref(cyl);
  mrn_grid_free(&g);
}

static void test_seed_3d(void) {
  mrn_grid g;
  grid3(&g, 1, 1, 1, 0.025);
  int rc;
  long count;

  mrn_region *ball = mrn_region_sphere((double[3]){0.5, 0.5, 0.5}, 0.3);
  tally t = seed(&g, ball, 2, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_OK && count == t.calls);
  CHECK(fabs(t.volume / (4.0 / 3.0 * PI * 0.027) - 1) < 0.03);
  CHECK(t.first[0][2] > 0.2); /* z really varies */

  mrn_region *cyl = mrn_region_cylinder((double[3]){0.2, 0.5, 0.5}, (double[3]){0.8, 0.5, 0.5}, 0.2);
  t = seed(&g, cyl, 2, MRN_SEED_REGULAR, &rc, &count);
  CHECK(rc == MRN_OK);
  CHECK(fabs(t.volume / (PI * 0.04 * 0.6) - 1) < 0.03);

  /* a polygon in 3D is a prism through the whole grid */
  mrn_region *tri = mrn_region_polygon((double[]){0, 0, 1, 0, 0, 1}, 3);
  t = seed(&g, tri, 1, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_OK);
  CHECK(fabs(t.volume / 0.5 - 1) < 0.05);

  /* a whole box: exact */
  mrn_region *b = mrn_region_box((double[3]){0, 0, 0}, (double[3]){1, 1, 1});
  t = seed(&g, b, 3, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_OK && count == 40L * 40 * 40 * 27);
  CHECK_CLOSE(t.volume, 1.0, 1e-10); /* a sum of 1.7 million terms */

  mrn_region_unref(ball);
  mrn_region_unref(cyl);
  mrn_region_unref(tri);
  mrn_region_unref(b);
  mrn_grid_free(&g);
}

static void test_seed_composites(void) {
  mrn_grid g;
  grid2(&g, 4, 3, 1);
  mrn_region *a = box2(0, 0, 2, 2), *b = box2(1, 0, 3, 2);
  mrn_region *u = mrn_region_combine(MRN_REGION_UNION, a, b);
  mrn_region *i = mrn_region_combine(MRN_REGION_INTERSECTION, a, b);
  mrn_region *d = mrn_region_combine(MRN_REGION_DIFFERENCE, a, b);
  int rc;
  long count;
  seed(&g, a, 1, MRN_SEED_REGULAR, &rc, &count);
  CHECK(rc == MRN_OK && count == 4);
  seed(&g, u, 1, MRN_SEED_REGULAR, &rc, &count);
  CHECK(rc == MRN_OK && count == 6);
  seed(&g, i, 1, MRN_SEED_REGULAR, &rc, &count);
  CHECK(rc == MRN_OK && count == 2);
  tally t = seed(&g, d, 2, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_OK && count == 8);
  CHECK_CLOSE(t.volume, 2.0, 1e-12);

  /* disjoint boxes intersect in nothing */
  mrn_region *far = box2(3, 2.5, 4, 3);
  mrn_region *none = mrn_region_combine(MRN_REGION_INTERSECTION, a, far);
  seed(&g, none, 2, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_OK && count == 0);

  mrn_region_unref(a);
  mrn_region_unref(b);
  mrn_region_unref(far);
  mrn_region_unref(u);
  mrn_region_unref(i);
  mrn_region_unref(d);
  mrn_region_unref(none);
  mrn_grid_free(&g);
}

typedef struct {
  int released;
  double fail_x; /* fail for points beyond this x */
} pred_ctx;

static int below_diagonal(void *ctx, const double x[3]) {
  pred_ctx *c = ctx;
  if (x[0] > c->fail_x) {
    mrn_error("predicate: no answer at x = %g", x[0]);
    return -1;
  }
  return x[1] < x[0];
}

static void release_ctx(void *ctx) { ((pred_ctx *)ctx)->released++; }

static void test_seed_predicate(void) {
  mrn_grid g;
  grid2(&g, 4, 4, 1);
  int rc;
  long count;
  pred_ctx c = {.fail_x = 1e300};
  mrn_region *p = mrn_region_predicate_new(below_diagonal, &c, release_ctx);
  CHECK(p && !mrn_region_bounded(p, 2));
  /* unbounded: clipped to the grid; strictly below the diagonal are 6 of 16 cells */
  tally t = seed(&g, p, 1, MRN_SEED_REGULAR, &rc, &count);
  CHECK(rc == MRN_OK && count == 6);
  CHECK_CLOSE(t.volume, 6.0, 1e-15);

  /* a failing predicate stops seeding and keeps its message, also through composites */
  c.fail_x = 2;
  mrn_region *b = box2(0, 0, 4, 4);
  mrn_region *i = mrn_region_combine(MRN_REGION_INTERSECTION, b, p);
  mrn_region_unref(p);
  CHECK(c.released == 0);
  seed(&g, i, 1, MRN_SEED_REGULAR, &rc, &count);
  CHECK(rc == MRN_ERR);
  CHECK(strstr(mrn_error_message(), "no answer at x = 2.5") != NULL);
  CHECK(mrn_region_contains(i, (double[3]){3, 0, 0}) == -1);
  mrn_region_unref(i);
  CHECK(c.released == 1);
  mrn_region_unref(b);
  mrn_grid_free(&g);
}

static void test_seed_errors(void) {
  mrn_grid g;
  grid2(&g, 4, 3, 1);
  int rc;
  long count;

  mrn_region *sticking_out = box2(-1, 0, 2, 1);
  seed(&g, sticking_out, 2, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_ERR);
  CHECK(strstr(mrn_error_message(), "outside") != NULL);
  CHECK(strstr(mrn_error_message(), "[0, 4] x [0, 3]") != NULL);

  /* only the bounding box sticks out: the region itself is empty */
  mrn_region *diff = mrn_region_combine(MRN_REGION_DIFFERENCE, sticking_out, sticking_out);
  seed(&g, diff, 2, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_OK && count == 0);

  mrn_region *far = mrn_region_sphere((double[3]){1e30, 0, 0}, 1);
  seed(&g, far, 2, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_ERR && strstr(mrn_error_message(), "outside") != NULL);

  mrn_region *huge = mrn_region_sphere((double[3]){0, 0, 0}, 1e8);
  mrn_region *hole = mrn_region_combine(MRN_REGION_DIFFERENCE, huge, huge);
  seed(&g, hole, 2, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_ERR);

  mrn_region *b = box2(0, 0, 1, 1);
  seed(&g, b, 0, MRN_SEED_GAUSS, &rc, &count);
  CHECK(rc == MRN_ERR && count == 0);
  CHECK(strstr(mrn_error_message(), "must be in 1..8, got 0") != NULL);
  seed(&g, b, MRN_SEED_MAX_PER_AXIS + 1, MRN_SEED_REGULAR, &rc, &count);
  CHECK(rc == MRN_ERR);
  seed(&g, b, MRN_SEED_MAX_PER_AXIS, MRN_SEED_REGULAR, &rc, &count);
  CHECK(rc == MRN_OK && count == 64);

  mrn_region_unref(sticking_out);
  mrn_region_unref(diff);
  mrn_region_unref(far);
  mrn_region_unref(huge);
  mrn_region_unref(hole);
  mrn_region_unref(b);
  mrn_grid_free(&g);
}

int main(void) {
  test_gauss_legendre();
  test_region_basics();
  test_region_errors();
  test_seed_box();
  test_seed_shapes_2d();
  test_seed_3d();
  test_seed_composites();
  test_seed_predicate();
  test_seed_errors();
  CHECK_DONE();
}
