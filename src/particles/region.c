#include "particles/region.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

static mrn_region *region_new(mrn_region_kind kind, const char *what) {
  mrn_region *r = calloc(1, sizeof *r);
  if (!r) {
    mrn_error("%s: out of memory", what);
    return NULL;
  }
  r->kind = kind;
  r->refcount = 1;
  r->depth = 1;
  return r;
}

static int finite3(const double x[3]) { return isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]); }

static int check_radius(const char *what, double radius) {
  if (!(radius > 0) || !isfinite(radius)) return mrn_error("%s: radius must be a finite number > 0, got %s", what, mrn_num(radius).s);
  return MRN_OK;
}

/* ---- constructors ------------------------------------------------------ */

/* x and y must have a positive extent; z may be flat (lo[2] == hi[2], e.g.
 * 0..0 for a 2D box) because 2D points always have z = 0. */
static int check_box(const double lo[3], const double hi[3]) {
  for (int d = 0; d < 3; d++) {
    if (isnan(lo[d]) || isnan(hi[d])) return mrn_error("box: min[%d] and max[%d] must be numbers", d + 1, d + 1);
    if (d < 2 && !(lo[d] < hi[d]))
      return mrn_error("box: min[%d] = %g is not below max[%d] = %g", d + 1, lo[d], d + 1, hi[d]);
    if (d == 2 && !(lo[d] <= hi[d]))
      return mrn_error("box: min[%d] = %g is above max[%d] = %g", d + 1, lo[d], d + 1, hi[d]);
  }
  return MRN_OK;
}

mrn_region *mrn_region_box(const double lo[3], const double hi[3]) {
  if (check_box(lo, hi) != MRN_OK) return NULL;
  mrn_region *r = region_new(MRN_REGION_BOX, "box");
  if (!r) return NULL;
  for (int d = 0; d < 3; d++) {
    r->p0[d] = r->lo[d] = lo[d];
    r->p1[d] = r->hi[d] = hi[d];
  }
  return r;
}

mrn_region *mrn_region_sphere(const double center[3], double radius) {
  if (!finite3(center)) {
    mrn_error("sphere: the center (%s, %s, %s) must be finite", mrn_num(center[0]).s, mrn_num(center[1]).s,
              mrn_num(center[2]).s);
    return NULL;
  }
  if (check_radius("sphere", radius) != MRN_OK) return NULL;
  mrn_region *r = region_new(MRN_REGION_SPHERE, "sphere");
  if (!r) return NULL;
  r->radius = radius;
  for (int d = 0; d < 3; d++) {
    r->p0[d] = center[d];
    r->lo[d] = center[d] - radius;
    r->hi[d] = center[d] + radius;
  }
  return r;
}

mrn_region *mrn_region_cylinder(const double p0[3], const double p1[3], double radius) {
  if (!finite3(p0) || !finite3(p1)) {
    mrn_error("cylinder: the axis end points must be finite");
    return NULL;
  }
  if (p0[0] == p1[0] && p0[1] == p1[1] && p0[2] == p1[2]) {
    mrn_error("cylinder: the axis end points must differ, both are (%g, %g, %g)", p0[0], p0[1], p0[2]);
    return NULL;
  }
  if (check_radius("cylinder", radius) != MRN_OK) return NULL;
  mrn_region *r = region_new(MRN_REGION_CYLINDER, "cylinder");
  if (!r) return NULL;
  r->radius = radius;
  /* the end points padded by the radius: not tight for a slanted axis, but
   * always enclosing */
  for (int d = 0; d < 3; d++) {
    r->p0[d] = p0[d];
    r->p1[d] = p1[d];
    r->lo[d] = fmin(p0[d], p1[d]) - radius;
    r->hi[d] = fmax(p0[d], p1[d]) + radius;
  }
  return r;
}

mrn_region *mrn_region_polygon(const double *xy, int nvert) {
  if (!xy || nvert < 3) {
    mrn_error("polygon: needs at least 3 vertices, got %d", xy ? nvert : 0);
    return NULL;
  }
  for (int i = 0; i < 2 * nvert; i++)
    if (!isfinite(xy[i])) {
      mrn_error("polygon: vertex %d has a coordinate that is not finite (%s)", i / 2 + 1, mrn_num(xy[i]).s);
      return NULL;
    }
  mrn_region *r = region_new(MRN_REGION_POLYGON, "polygon");
  if (!r) return NULL;
  r->vertices = malloc(2 * (size_t)nvert * sizeof(double));
  if (!r->vertices) {
    free(r);
    mrn_error("polygon: out of memory for %d vertices", nvert);
    return NULL;
  }
  memcpy(r->vertices, xy, 2 * (size_t)nvert * sizeof(double));
  r->nvert = nvert;
  r->dim = 2;
  r->lo[0] = r->hi[0] = xy[0];
  r->lo[1] = r->hi[1] = xy[1];
  for (int i = 1; i < nvert; i++)
    for (int d = 0; d < 2; d++) {
      r->lo[d] = fmin(r->lo[d], xy[2 * i + d]);
      r->hi[d] = fmax(r->hi[d], xy[2 * i + d]);
    }
  /* a polygon says nothing about z */
  r->lo[2] = -HUGE_VAL;
  r->hi[2] = HUGE_VAL;
  return r;
}

static void combine_bounds(mrn_region *r) {
  const mrn_region *a = r->a, *b = r->b;
  for (int d = 0; d < 3; d++) {
    switch (r->kind) {
      case MRN_REGION_UNION:
        r->lo[d] = fmin(a->lo[d], b->lo[d]);
        r->hi[d] = fmax(a->hi[d], b->hi[d]);
        break;
      case MRN_REGION_INTERSECTION: /* may come out empty (lo > hi) */
        r->lo[d] = fmax(a->lo[d], b->lo[d]);
        r->hi[d] = fmin(a->hi[d], b->hi[d]);
        break;
      default: /* difference: removing b never grows a */
        r->lo[d] = a->lo[d];
        r->hi[d] = a->hi[d];
        break;
    }
  }
}

mrn_region *mrn_region_combine(mrn_region_kind kind, mrn_region *a, mrn_region *b) {
  if (kind != MRN_REGION_UNION && kind != MRN_REGION_INTERSECTION && kind != MRN_REGION_DIFFERENCE) {
    mrn_error("region: combine needs union, intersection or difference, got kind %d", (int)kind);
    return NULL;
  }
  if (!a || !b) {
    mrn_error("region: combine needs two regions, got %s", !a && !b ? "none" : "one");
    return NULL;
  }
  if (a->dim && b->dim && a->dim != b->dim) {
    mrn_error("region: cannot combine a %dD region with a %dD region", a->dim, b->dim);
    return NULL;
  }
  const int depth = 1 + (a->depth > b->depth ? a->depth : b->depth);
  if (depth > MRN_REGION_MAX_DEPTH) {
    mrn_error("region: the combination would nest regions %d levels deep, more than the limit of %d (combine many "
              "regions in one call rather than one at a time)", depth, MRN_REGION_MAX_DEPTH);
    return NULL;
  }
  mrn_region *r = region_new(kind, "region");
  if (!r) return NULL;
  r->dim = a->dim ? a->dim : b->dim;
  r->depth = depth;
  mrn_region_ref(a);
  mrn_region_ref(b);
  r->a = a;
  r->b = b;
  combine_bounds(r);
  return r;
}

mrn_region *mrn_region_predicate_new(mrn_region_predicate fn, void *ctx, void (*release)(void *)) {
  if (!fn) {
    mrn_error("region: a predicate region needs a function");
    return NULL;
  }
  mrn_region *r = region_new(MRN_REGION_PREDICATE, "region");
  if (!r) return NULL;
  r->predicate = fn;
  r->ctx = ctx;
  r->release = release;
  for (int d = 0; d < 3; d++) {
    r->lo[d] = -HUGE_VAL;
    r->hi[d] = HUGE_VAL;
  }
  return r;
}

/* ---- reference counting ------------------------------------------------ */

void mrn_region_ref(mrn_region *r) {
  if (r) r->refcount++;
}

void mrn_region_unref(mrn_region *r) {
  if (!r || --r->refcount > 0) return;
  mrn_region_unref(r->a);
  mrn_region_unref(r->b);
  free(r->vertices);
  if (r->release) r->release(r->ctx);
  free(r);
}

/* ---- point tests ------------------------------------------------------- */

static int box_contains(const mrn_region *r, const double x[3]) {
  for (int d = 0; d < 3; d++)
    if (!(x[d] >= r->p0[d] && x[d] <= r->p1[d])) return 0;
  return 1;
}

static int sphere_contains(const mrn_region *r, const double x[3]) {
  double d2 = 0;
  for (int d = 0; d < 3; d++) d2 += (x[d] - r->p0[d]) * (x[d] - r->p0[d]);
  return d2 <= r->radius * r->radius;
}

/* inside when the projection onto the axis falls between the end points and
 * the distance from the axis is at most the radius (flat ends, no caps) */
static int cylinder_contains(const mrn_region *r, const double x[3]) {
  double u[3], v[3], uu = 0, uv = 0;
  for (int d = 0; d < 3; d++) {
    u[d] = r->p1[d] - r->p0[d];
    v[d] = x[d] - r->p0[d];
    uu += u[d] * u[d];
    uv += u[d] * v[d];
  }
  double t = uv / uu;
  if (t < 0 || t > 1) return 0;
  double d2 = 0;
  for (int d = 0; d < 3; d++) d2 += (v[d] - t * u[d]) * (v[d] - t * u[d]);
  return d2 <= r->radius * r->radius;
}

/* even-odd rule: count the edges crossed by a ray from x towards +x */
static int polygon_contains(const mrn_region *r, const double x[3]) {
  if (x[0] < r->lo[0] || x[0] > r->hi[0] || x[1] < r->lo[1] || x[1] > r->hi[1]) return 0;
  const double *v = r->vertices;
  int inside = 0;
  for (int i = 0, j = r->nvert - 1; i < r->nvert; j = i++) {
    double xi = v[2 * i], yi = v[2 * i + 1], xj = v[2 * j], yj = v[2 * j + 1];
    /* the half-open test (yi > y) != (yj > y) counts a vertex on the ray once */
    if ((yi > x[1]) != (yj > x[1])) {
      double xc = xi + (x[1] - yi) / (yj - yi) * (xj - xi);
      if (x[0] < xc) inside = !inside;
    }
  }
  return inside;
}

int mrn_region_contains(const mrn_region *r, const double x[3]) {
  int in;
  switch (r->kind) {
    case MRN_REGION_BOX: return box_contains(r, x);
    case MRN_REGION_SPHERE: return sphere_contains(r, x);
    case MRN_REGION_CYLINDER: return cylinder_contains(r, x);
    case MRN_REGION_POLYGON: return polygon_contains(r, x);
    case MRN_REGION_UNION:
      in = mrn_region_contains(r->a, x);
      return in != 0 ? in : mrn_region_contains(r->b, x);
    case MRN_REGION_INTERSECTION:
      in = mrn_region_contains(r->a, x);
      return in != 1 ? in : mrn_region_contains(r->b, x);
    case MRN_REGION_DIFFERENCE:
      in = mrn_region_contains(r->a, x);
      if (in != 1) return in;
      in = mrn_region_contains(r->b, x);
      return in < 0 ? -1 : !in;
    case MRN_REGION_PREDICATE:
      in = r->predicate(r->ctx, x);
      return in < 0 ? -1 : in != 0;
  }
  mrn_error("region: unknown kind %d", (int)r->kind);
  return -1;
}

int mrn_region_bounded(const mrn_region *r, int dim) {
  for (int d = 0; d < dim && d < 3; d++)
    if (!isfinite(r->lo[d]) || !isfinite(r->hi[d])) return 0;
  return 1;
}
