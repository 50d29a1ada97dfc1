/* grid/trimesh: the signed distance of a closed mesh against brute force,
 * capped searches, orientation, planar groups and the checks of bad meshes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "grid/trimesh.h"

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* squared distance from p to the segment ab */
static double segment2(const double *a, const double *b, const double p[3]) {
  double ab[3], ap[3], r[3];
  for (int d = 0; d < 3; d++) ab[d] = b[d] - a[d], ap[d] = p[d] - a[d];
  double t = dot(ap, ab) / dot(ab, ab);
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  for (int d = 0; d < 3; d++) r[d] = ap[d] - t * ab[d];
  return dot(r, r);
}

/* squared distance from p to triangle t (9 numbers): the plane when p
 * projects inside, else the nearest edge */
static double triangle2(const double *t, const double p[3]) {
  double e1[3], e2[3], n[3], r[3];
  for (int d = 0; d < 3; d++) e1[d] = t[3 + d] - t[d], e2[d] = t[6 + d] - t[d], r[d] = p[d] - t[d];
  n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  const double h = dot(r, n) / dot(n, n);
  double q[3], inside = 1;
  for (int d = 0; d < 3; d++) q[d] = p[d] - h * n[d];
  for (int k = 0; k < 3; k++) { /* q on the inner side of each edge */
    const double *a = t + 3 * k, *b = t + 3 * ((k + 1) % 3);
    double ab[3], aq[3], c[3];
    for (int d = 0; d < 3; d++) ab[d] = b[d] - a[d], aq[d] = q[d] - a[d];
    c[0] = ab[1] * aq[2] - ab[2] * aq[1], c[1] = ab[2] * aq[0] - ab[0] * aq[2], c[2] = ab[0] * aq[1] - ab[1] * aq[0];
    if (dot(c, n) < 0) inside = 0;
  }
  if (inside) return h * h * dot(n, n);
  double best = segment2(t, t + 3, p);
  best = fmin(best, segment2(t + 3, t + 6, p));
  return fmin(best, segment2(t + 6, t, p));
}

/* an icosphere: the icosahedron's faces split `levels` times, corners on the
 * sphere of radius r about c; 20 * 4^levels triangles, outward */
static double *icosphere(int levels, double r, const double c[3], size_t *n) {
  const double p = (1 + sqrt(5.0)) / 2;
  const double v[12][3] = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                           {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  const int f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                        {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  size_t count = 20;
  double *t = malloc(9 * count * sizeof *t);
  for (int i = 0; i < 20; i++)
    for (int k = 0; k < 3; k++) memcpy(t + 9 * i + 3 * k, v[f[i][k]], 3 * sizeof(double));
  for (int l = 0; l < levels; l++) {
    double *u = malloc(36 * count * sizeof *u);
    for (size_t i = 0; i < count; i++) {
      const double *a = t + 9 * i, *b = a + 3, *cc = a + 6;
      double m[3][3];
      for (int d = 0; d < 3; d++) m[0][d] = (a[d] + b[d]) / 2, m[1][d] = (b[d] + cc[d]) / 2, m[2][d] = (cc[d] + a[d]) / 2;
      const double *tri[4][3] = {{a, m[0], m[2]}, {m[0], b, m[1]}, {m[2], m[1], cc}, {m[0], m[1], m[2]}};
      for (int s = 0; s < 4; s++)
        for (int k = 0; k < 3; k++) memcpy(u + 36 * i + 9 * s + 3 * k, tri[s][k], 3 * sizeof(double));
    }
    free(t), t = u, count *= 4;
  }
  for (size_t i = 0; i < 3 * count; i++) { /* onto the sphere */
    double *x = t + 3 * i;
    const double len = sqrt(dot(x, x));
    for (int d = 0; d < 3; d++) x[d] = c[d] + r * x[d] / len;
  }
  *n = count;
  return t;
}

static double lcg(unsigned long *s) {
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

/* random points against brute force; capped queries agree or stay beyond */
static void sphere_distances(const double *tri, size_t n, const mrn_trimesh *m, const double c[3]) {
  unsigned long seed = 7;
  int wrong = 0, capped = 0;
  for (int i = 0; i < 3000; i++) {
    double x[3], nrm[3];
    for (int d = 0; d < 3; d++) x[d] = c[d] + 1.6 * (lcg(&seed) - 0.5);
    double best = HUGE_VAL;
    for (size_t t = 0; t < n; t++) best = fmin(best, triangle2(tri + 9 * t, x));
    best = sqrt(best);
    const double r = sqrt((x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) + (x[2] - c[2]) * (x[2] - c[2]));
    int group;
    const double d = mrn_trimesh_distance(m, x, HUGE_VAL, HUGE_VAL, nrm, &group);
    if (fabs(fabs(d) - best) > 1e-12 || (fabs(r - 0.5) > 0.01 && (d < 0) != (r < 0.5))) wrong++;
    if (fabs(dot(nrm, nrm) - 1) > 1e-12 || group < 0) wrong++;
    const double e = mrn_trimesh_distance(m, x, 0.05, 0.05, nrm, &group);
    if (fabs(d) <= 0.05 && e != d) wrong++;
    if (fabs(d) > 0.1 && ((e < 0) != (d < 0) || fabs(e) < 0.05 || fabs(e) > fabs(d))) wrong++;
    capped += fabs(d) > 0.1;
  }
  CHECK(wrong == 0);
  CHECK(capped > 1000);
}

static void sphere(void) {
  const double c[3] = {0.1, 0.2, 0.3};
  size_t n;
  double *tri = icosphere(3, 0.5, c, &n); /* 1280 triangles */
  mrn_trimesh *m = mrn_trimesh_new(tri, n, 0.04, "sphere");
  CHECK(m != NULL);
  if (m) sphere_distances(tri, n, m, c);
  mrn_trimesh_free(m);
  for (size_t t = 0; t < n; t++) /* wound inward: turned around, the same distances */
    for (int d = 0; d < 3; d++) {
      const double s = tri[9 * t + 3 + d];
      tri[9 * t + 3 + d] = tri[9 * t + 6 + d], tri[9 * t + 6 + d] = s;
    }
  m = mrn_trimesh_new(tri, n, 0.04, "sphere");
  CHECK(m != NULL);
  if (m) sphere_distances(tri, n, m, c);
  mrn_trimesh_free(m);
  free(tri);
}

/* a unit cube's 12 triangles, outward */
static void cube(double t[108]) {
  static const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (int f = 0; f < 6; f++)
    for (int h = 0; h < 2; h++) {
      const int k[3] = {faces[f][0], faces[f][1 + h], faces[f][2 + h]};
      for (int j = 0; j < 3; j++)
        for (int d = 0; d < 3; d++) t[18 * f + 9 * h + 3 * j + d] = (k[j] >> d) & 1;
    }
}

static void cube_groups(void) {
  double t[108], n[3];
  cube(t);
  mrn_trimesh *m = mrn_trimesh_new(t, 12, 0.1, "cube");
  CHECK(m != NULL);
  if (!m) return;
  int g1, g2, g3;
  const double a[3] = {0.2, 0.7, 1.1}, b[3] = {0.7, 0.2, 1.1}, c[3] = {0.5, 0.5, -0.3}, in[3] = {0.5, 0.45, 0.9};
  CHECK_CLOSE(mrn_trimesh_distance(m, a, HUGE_VAL, HUGE_VAL, n, &g1), 0.1, 1e-14);
  CHECK(n[2] == 1.0);
  mrn_trimesh_distance(m, b, HUGE_VAL, HUGE_VAL, n, &g2);
  CHECK(g1 == g2); /* the two triangles of the top: one planar group */
  mrn_trimesh_distance(m, c, HUGE_VAL, HUGE_VAL, n, &g3);
  CHECK(g3 != g1 && n[2] == -1.0);
  CHECK_CLOSE(mrn_trimesh_distance(m, in, HUGE_VAL, HUGE_VAL, n, &g3), -0.1, 1e-14);
  CHECK(g3 == g1 && n[2] == 1.0);
  const double corner[3] = {1.3, 1.4, 1.0};
  CHECK_CLOSE(mrn_trimesh_distance(m, corner, HUGE_VAL, HUGE_VAL, n, &g3), 0.5, 1e-14);
  CHECK_CLOSE(n[0], 0.6, 1e-14);
  mrn_trimesh_free(m);
}

/* a bad mesh: NULL, and the message holds `what` */
static void refused(const double *t, size_t n, const char *what) {
  mrn_trimesh *m = mrn_trimesh_new(t, n, 0.1, "bad.stl");
  CHECK(m == NULL);
  CHECK(strstr(mrn_error_message(), what) != NULL);
  if (!strstr(mrn_error_message(), what)) fprintf(stderr, "  message: %s\n", mrn_error_message());
  mrn_trimesh_free(m);
}

static void bad_meshes(void) {
  double t[108], u[108];
  cube(t);
  refused(t, 11, "(1, 0, 1)-(1, 1, 1) of triangle 3 borders no other triangle (the mesh has a hole)");
  memcpy(u, t, sizeof u);
  for (int d = 0; d < 3; d++) { /* triangle 5 turned around */
    const double s = u[36 + 3 + d];
    u[36 + 3 + d] = u[36 + 6 + d], u[36 + 6 + d] = s;
  }
  refused(u, 12, "inconsistent orientation");
  memcpy(u, t, sizeof u);
  memcpy(u + 9 * 3 + 3, u + 9 * 3, 3 * sizeof(double)); /* two corners of triangle 4 at one point */
  refused(u, 12, "triangle 4 is degenerate");
  memcpy(u, t, sizeof u);
  u[7] = NAN;
  refused(u, 12, "triangle 1 has a coordinate that is not finite");
}

int main(void) {
  sphere();
  cube_groups();
  bad_meshes();
  CHECK_DONE();
}
