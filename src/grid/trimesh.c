#include "grid/trimesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

struct mrn_trimesh {
  size_t ntri, nvert;
  double *vert; /* 3 nvert */
  int *tri;     /* 3 ntri corners, counter-clockwise seen from outside */
  double *fn;   /* 3 ntri unit face normals */
  double *en;   /* 9 ntri: the pseudo-normal of edge k (corner k to k + 1) */
  double *vn;   /* 3 nvert: the vertices' pseudo-normals */
  double *box;  /* 6 ntri: each triangle's bounding box, lo then hi */
  int *group;   /* ntri: planar group */
  double *gn;   /* 3 ngroup: group normals */
  int ngroup;
  double lo[3];       /* the bucket grid: first corner, side, counts */
  double b;
  int nb[3];
  size_t *start;      /* nbucket + 1: bucket k holds item[start[k] .. start[k + 1] - 1] */
  int *item;
  signed char *sign;  /* nbucket: -1 when the bucket's centre is inside */
  double cap_min;     /* the least distance a query searches to */
};

/* how far apart two corners may be and still merge, in the mesh's size */
#define MERGE_TOL 1e-6
/* the most buckets: beyond, they grow wider than a cell */
#define MAX_BUCKETS (1 << 20)

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void sub3(const double a[3], const double b[3], double c[3]) {
  for (int d = 0; d < 3; d++) c[d] = a[d] - b[d];
}
static void cross3(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2], c[2] = a[0] * b[1] - a[1] * b[0];
}
static const double *corner(const mrn_trimesh *m, size_t t, int k) { return m->vert + 3 * m->tri[3 * t + k]; }

void mrn_trimesh_free(mrn_trimesh *m) {
  if (!m) return;
  free(m->vert), free(m->tri), free(m->fn), free(m->en), free(m->vn), free(m->box);
  free(m->group), free(m->gn), free(m->start), free(m->item), free(m->sign);
  free(m);
}

const double *mrn_trimesh_group_normal(const mrn_trimesh *m, int group) { return m->gn + 3 * group; }

/* ---- making the mesh --------------------------------------------------------------- */

static const double *sort_base;
static int by_x(const void *a, const void *b) {
  const double xa = sort_base[3 * *(const size_t *)a], xb = sort_base[3 * *(const size_t *)b];
  return (xa > xb) - (xa < xb);
}

/* Shared vertices: the corners in order of x, each merged with the later
 * ones within the tolerance along every axis; tri[] gets their numbers. */
static int merge_vertices(mrn_trimesh *m, const double *p, size_t ncorner) {
  size_t *order = malloc(ncorner * sizeof *order);
  m->vert = malloc(3 * ncorner * sizeof *m->vert);
  m->tri = malloc(ncorner * sizeof *m->tri);
  if (!order || !m->vert || !m->tri) return free(order), mrn_error("out of memory for a mesh");
  double size = 0.0;
  for (size_t i = 0; i < 3 * ncorner; i++) size = fmax(size, fabs(p[i]));
  const double tol = MERGE_TOL * size;
  for (size_t i = 0; i < ncorner; i++) order[i] = i, m->tri[i] = -1;
  sort_base = p;
  qsort(order, ncorner, sizeof *order, by_x);
  for (size_t i = 0; i < ncorner; i++) {
    const size_t a = order[i];
    if (m->tri[a] >= 0) continue;
    m->tri[a] = (int)m->nvert;
    memcpy(m->vert + 3 * m->nvert, p + 3 * a, 3 * sizeof(double));
    for (size_t j = i + 1; j < ncorner && p[3 * order[j]] - p[3 * a] <= tol; j++) {
      const double *q = p + 3 * order[j];
      if (m->tri[order[j]] < 0 && fabs(q[1] - p[3 * a + 1]) <= tol && fabs(q[2] - p[3 * a + 2]) <= tol)
        m->tri[order[j]] = (int)m->nvert;
    }
    m->nvert++;
  }
  free(order);
  return MRN_OK;
}

static int degenerate_check(const mrn_trimesh *m, const char *source) {
  for (size_t t = 0; t < m->ntri; t++) {
    const double *a = corner(m, t, 0), *b = corner(m, t, 1), *c = corner(m, t, 2);
    double ab[3], ac[3], bc[3], cr[3];
    sub3(b, a, ab), sub3(c, a, ac), sub3(c, b, bc), cross3(ab, ac, cr);
    const double longest = fmax(dot3(ab, ab), fmax(dot3(ac, ac), dot3(bc, bc)));
    if (!(dot3(cr, cr) > 1e-24 * longest * longest))
      return mrn_error("'%s': triangle %zu is degenerate (no area): corners (%g, %g, %g), (%g, %g, %g), (%g, %g, %g)",
                       source, t + 1, a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]);
  }
  return MRN_OK;
}

/* an edge as a triangle runs along it: its vertices in order, lo < hi */
typedef struct edge {
  int lo, hi, forward; /* forward: the triangle runs lo -> hi */
  int t, k;
} edge;

static int by_edge(const void *a, const void *b) {
  const edge *p = a, *q = b;
  if (p->lo != q->lo) return p->lo < q->lo ? -1 : 1;
  if (p->hi != q->hi) return p->hi < q->hi ? -1 : 1;
  return (p->t > q->t) - (p->t < q->t);
}

/* the edges of every triangle, sorted so that the uses of one edge follow each other */
static edge *edge_list(const mrn_trimesh *m) {
  edge *e = malloc(3 * m->ntri * sizeof *e);
  if (!e) return NULL;
  for (size_t t = 0; t < m->ntri; t++)
    for (int k = 0; k < 3; k++) {
      const int a = m->tri[3 * t + k], b = m->tri[3 * t + (k + 1) % 3];
      e[3 * t + k] = (edge){a < b ? a : b, a < b ? b : a, a < b, (int)t, k};
    }
  qsort(e, 3 * m->ntri, sizeof *e, by_edge);
  return e;
}

/* what is wrong with the uses e[0 .. count - 1] of one edge, or NULL */
static const char *edge_fault(const edge *e, size_t count) {
  if (count == 1) return "borders no other triangle (the mesh has a hole)";
  if (count > 2) return "is shared by more than two triangles";
  if (e[0].forward == e[1].forward) return "runs the same way in both its triangles (inconsistent orientation)";
  return NULL;
}

/* every edge used by two triangles in opposite directions; the message names
 * the bad edge of the first triangle (in the file's order) that has one */
static int edge_check(const mrn_trimesh *m, const edge *e, const char *source) {
  const edge *bad = NULL;
  const char *why = NULL;
  for (size_t i = 0, j; i < 3 * m->ntri; i = j) {
    for (j = i + 1; j < 3 * m->ntri && e[j].lo == e[i].lo && e[j].hi == e[i].hi;) j++;
    const char *fault = edge_fault(e + i, j - i);
    if (fault && (!bad || e[i].t < bad->t)) bad = e + i, why = fault;
  }
  if (!bad) return MRN_OK;
  const double *a = m->vert + 3 * bad->lo, *b = m->vert + 3 * bad->hi;
  return mrn_error("'%s': the mesh is not closed and oriented: the edge (%g, %g, %g)-(%g, %g, %g) of triangle %d %s",
                   source, a[0], a[1], a[2], b[0], b[1], b[2], bad->t + 1, why);
}

/* six times the enclosed volume; a mesh wound inward is turned around */
static int orient(mrn_trimesh *m, const char *source) {
  double vol = 0.0, size = 0.0;
  for (size_t t = 0; t < m->ntri; t++) {
    double cr[3];
    cross3(corner(m, t, 1), corner(m, t, 2), cr);
    vol += dot3(corner(m, t, 0), cr);
  }
  for (size_t i = 0; i < 3 * m->nvert; i++) size = fmax(size, fabs(m->vert[i]));
  if (!(fabs(vol) > 1e-12 * size * size * size) || !isfinite(vol))
    return mrn_error("'%s': the mesh encloses no volume", source);
  if (vol < 0.0)
    for (size_t t = 0; t < m->ntri; t++) {
      const int k = m->tri[3 * t + 1];
      m->tri[3 * t + 1] = m->tri[3 * t + 2], m->tri[3 * t + 2] = k;
    }
  return MRN_OK;
}

/* face normals, bounding boxes and the vertices' angle-weighted pseudo-normals */
static void face_normals(mrn_trimesh *m) {
  for (size_t t = 0; t < m->ntri; t++) {
    double *n = m->fn + 3 * t, *box = m->box + 6 * t;
    double e[3][3];
    for (int k = 0; k < 3; k++) sub3(corner(m, t, (k + 1) % 3), corner(m, t, k), e[k]);
    cross3(e[0], e[1], n);
    const double len = sqrt(dot3(n, n));
    for (int d = 0; d < 3; d++) n[d] /= len;
    for (int d = 0; d < 3; d++) {
      box[d] = fmin(corner(m, t, 0)[d], fmin(corner(m, t, 1)[d], corner(m, t, 2)[d]));
      box[3 + d] = fmax(corner(m, t, 0)[d], fmax(corner(m, t, 1)[d], corner(m, t, 2)[d]));
    }
    for (int k = 0; k < 3; k++) { /* the angle at corner k, between the edges out of it */
      const double *in = e[(k + 2) % 3], *out = e[k];
      const double c = -dot3(in, out) / sqrt(dot3(in, in) * dot3(out, out));
      const double angle = acos(fmax(-1.0, fmin(1.0, c)));
      for (int d = 0; d < 3; d++) m->vn[3 * m->tri[3 * t + k] + d] += angle * n[d];
    }
  }
}

/* edge pseudo-normals: the sum of the two faces' normals; planar groups:
 * triangles joined across an edge with the same normal (union-find) */
static void edge_normals(mrn_trimesh *m, const edge *e) {
  for (size_t t = 0; t < m->ntri; t++) m->group[t] = (int)t;
  for (size_t i = 0; i < 3 * m->ntri; i += 2) {
    const int t1 = e[i].t, t2 = e[i + 1].t;
    double *n1 = m->en + 9 * t1 + 3 * e[i].k, *n2 = m->en + 9 * t2 + 3 * e[i + 1].k;
    for (int d = 0; d < 3; d++) n1[d] = n2[d] = m->fn[3 * t1 + d] + m->fn[3 * t2 + d];
    if (dot3(m->fn + 3 * t1, m->fn + 3 * t2) < 1.0 - 1e-9) continue;
    int r1 = t1, r2 = t2;
    while (m->group[r1] != r1) r1 = m->group[r1];
    while (m->group[r2] != r2) r2 = m->group[r2];
    if (r1 != r2) m->group[r1 > r2 ? r1 : r2] = r1 < r2 ? r1 : r2;
  }
}

/* the groups numbered 0.. in order of their first triangle, each with its
 * area-weighted mean normal */
static int number_groups(mrn_trimesh *m) {
  int *id = malloc(m->ntri * sizeof *id);
  m->gn = calloc(3 * m->ntri, sizeof *m->gn);
  if (!id || !m->gn) return free(id), mrn_error("out of memory for a mesh");
  for (size_t t = 0; t < m->ntri; t++) {
    int r = (int)t;
    while (m->group[r] != r) r = m->group[r];
    id[t] = r == (int)t ? m->ngroup++ : id[r];
  }
  for (size_t t = 0; t < m->ntri; t++) {
    double e1[3], e2[3], cr[3];
    sub3(corner(m, t, 1), corner(m, t, 0), e1), sub3(corner(m, t, 2), corner(m, t, 0), e2), cross3(e1, e2, cr);
    m->group[t] = id[t];
    for (int d = 0; d < 3; d++) m->gn[3 * id[t] + d] += cr[d];
  }
  for (int g = 0; g < m->ngroup; g++) {
    const double len = sqrt(dot3(m->gn + 3 * g, m->gn + 3 * g));
    for (int d = 0; d < 3; d++) m->gn[3 * g + d] /= len;
  }
  free(id);
  return MRN_OK;
}

/* ---- the nearest triangle ---------------------------------------------------------- */

/* the features of a triangle the nearest point can lie on */
enum { ON_FACE = 0, ON_VERTEX = 1, ON_EDGE = 4 };

typedef struct hit {
  double d2, q[3];
  int tri, feature; /* ON_FACE, ON_VERTEX + k, ON_EDGE + k (edge k from corner k) */
} hit;

/* the point of triangle abc nearest p, by the regions of its barycentric
 * coordinates (Ericson, Real-Time Collision Detection, 5.1.5) */
static int closest_point(const double *a, const double *b, const double *c, const double p[3], double q[3]) {
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  sub3(b, a, ab), sub3(c, a, ac), sub3(p, a, ap), sub3(p, b, bp), sub3(p, c, cp);
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap), d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d1 <= 0.0 && d2 <= 0.0) return memcpy(q, a, 3 * sizeof *q), ON_VERTEX;
  if (d3 >= 0.0 && d4 <= d3) return memcpy(q, b, 3 * sizeof *q), ON_VERTEX + 1;
  if (d6 >= 0.0 && d5 <= d6) return memcpy(q, c, 3 * sizeof *q), ON_VERTEX + 2;
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    for (int d = 0; d < 3; d++) q[d] = a[d] + v * ab[d];
    return ON_EDGE;
  }
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int d = 0; d < 3; d++) q[d] = b[d] + w * (c[d] - b[d]);
    return ON_EDGE + 1;
  }
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    for (int d = 0; d < 3; d++) q[d] = a[d] + w * ac[d];
    return ON_EDGE + 2;
  }
  const double s = 1.0 / (va + vb + vc), v = vb * s, w = vc * s;
  for (int d = 0; d < 3; d++) q[d] = a[d] + v * ab[d] + w * ac[d];
  return ON_FACE;
}

/* the triangles of one bucket against the nearest so far */
static void bucket_test(const mrn_trimesh *m, size_t k, const double x[3], hit *h) {
  for (size_t i = m->start[k]; i < m->start[k + 1]; i++) {
    const int t = m->item[i];
    const double *box = m->box + 6 * t;
    double gap = 0.0, q[3], r[3];
    for (int d = 0; d < 3; d++) {
      const double below = box[d] - x[d], above = x[d] - box[3 + d];
      if (below > 0.0) gap += below * below;
      else if (above > 0.0) gap += above * above;
    }
    if (gap >= h->d2) continue;
    const int f = closest_point(corner(m, t, 0), corner(m, t, 1), corner(m, t, 2), x, q);
    sub3(x, q, r);
    const double d2 = dot3(r, r);
    if (d2 < h->d2) h->d2 = d2, h->tri = t, h->feature = f, memcpy(h->q, q, sizeof h->q);
  }
}

/* the bucket of x, clamped to the grid, and its distance from the grid */
static double bucket_of(const mrn_trimesh *m, const double x[3], int c[3]) {
  double out = 0.0;
  for (int d = 0; d < 3; d++) {
    const double u = (x[d] - m->lo[d]) / m->b;
    c[d] = !(u >= 0.0) ? 0 : u >= m->nb[d] ? m->nb[d] - 1 : (int)u; /* NaN: bucket 0, not UB */
    const double below = m->lo[d] - x[d], above = x[d] - (m->lo[d] + m->nb[d] * m->b);
    if (below > 0.0) out += below * below;
    else if (above > 0.0) out += above * above;
  }
  return sqrt(out);
}

static size_t bucket_index(const mrn_trimesh *m, int i, int j, int k) {
  return (size_t)i + (size_t)m->nb[0] * ((size_t)j + (size_t)m->nb[1] * (size_t)k);
}

/* the bucket (i, j, l) when it lies nearer x than the nearest so far */
static void bucket_near(const mrn_trimesh *m, int i, int j, int l, const double x[3], hit *h) {
  const int at[3] = {i, j, l};
  double gap = 0.0;
  for (int d = 0; d < 3; d++) {
    const double below = m->lo[d] + at[d] * m->b - x[d], above = x[d] - (m->lo[d] + (at[d] + 1) * m->b);
    if (below > 0.0) gap += below * below;
    else if (above > 0.0) gap += above * above;
  }
  if (gap < h->d2) bucket_test(m, bucket_index(m, i, j, l), x, h);
}

/* the buckets at Chebyshev distance k from c */
static void ring_test(const mrn_trimesh *m, const int c[3], int k, const double x[3], hit *h) {
  int lo[3], hi[3];
  for (int d = 0; d < 3; d++) lo[d] = c[d] - k < 0 ? 0 : c[d] - k, hi[d] = c[d] + k >= m->nb[d] ? m->nb[d] - 1 : c[d] + k;
  for (int j = lo[1]; j <= hi[1]; j++)
    for (int i = lo[0]; i <= hi[0]; i++) {
      if (abs(i - c[0]) == k || abs(j - c[1]) == k) { /* on the ring's side: the whole column */
        for (int l = lo[2]; l <= hi[2]; l++) bucket_near(m, i, j, l, x, h);
        continue;
      }
      if (c[2] - k >= 0) bucket_near(m, i, j, c[2] - k, x, h);
      if (c[2] + k < m->nb[2]) bucket_near(m, i, j, c[2] + k, x, h);
    }
}

/* the least distance from x to a bucket beyond ring k, or HUGE_VAL when none is left */
static double beyond_ring(const mrn_trimesh *m, const int c[3], int k, const double x[3]) {
  double least = HUGE_VAL;
  for (int d = 0; d < 3; d++) {
    if (c[d] - k > 0) least = fmin(least, fmax(0.0, x[d] - (m->lo[d] + (c[d] - k) * m->b)));
    if (c[d] + k < m->nb[d] - 1) least = fmin(least, fmax(0.0, m->lo[d] + (c[d] + k + 1) * m->b - x[d]));
  }
  return least;
}

/* the nearest triangle within `reach` of x (h->tri -1: none) */
static void nearest(const mrn_trimesh *m, const double x[3], double reach, hit *h) {
  int c[3];
  const double outside = bucket_of(m, x, c);
  h->tri = -1, h->d2 = reach * reach;
  if (outside >= reach) return;
  for (int k = 0;; k++) {
    ring_test(m, c, k, x, h);
    const double left = fmax(outside, beyond_ring(m, c, k, x));
    if (left == HUGE_VAL || left * left >= h->d2) return;
  }
}

/* the signed distance and outward normal of a hit */
static double resolve(const mrn_trimesh *m, const double x[3], const hit *h, double n[3]) {
  const double *fn = m->fn + 3 * h->tri;
  if (h->feature == ON_FACE) { /* along the face's own normal: exact on a grid-aligned face */
    memcpy(n, fn, 3 * sizeof *n);
    return dot3(x, fn) - dot3(corner(m, h->tri, 0), fn);
  }
  const double *pn = h->feature >= ON_EDGE ? m->en + 9 * h->tri + 3 * (h->feature - ON_EDGE)
                                           : m->vn + 3 * m->tri[3 * h->tri + h->feature - ON_VERTEX];
  double r[3];
  sub3(x, h->q, r);
  const double dist = sqrt(h->d2), sign = dot3(r, pn) < 0.0 ? -1.0 : 1.0;
  if (!(dist > 0.0)) pn = dot3(pn, pn) > 0.0 ? pn : fn; /* on the surface: the pseudo-normal (a knife edge: the face's) */
  const double len = dist > 0.0 ? dist : sqrt(dot3(pn, pn));
  for (int d = 0; d < 3; d++) n[d] = dist > 0.0 ? sign * r[d] / len : pn[d] / len;
  return sign * dist;
}

/* The side of x when nothing lies within *searched of it: outside the
 * grid, outside; in a bucket no triangle crosses, the bucket's side; else
 * the search goes on to cap_min, and when it finds nothing (h->tri < 0)
 * the bucket's centre lies on x's side (grid/trimesh.h) */
static double side_of(const mrn_trimesh *m, const double x[3], double *searched, hit *h) {
  int c[3];
  if (bucket_of(m, x, c) > 0.0) return 1.0;
  const size_t k = bucket_index(m, c[0], c[1], c[2]);
  if (m->start[k] < m->start[k + 1] && *searched < m->cap_min) {
    nearest(m, x, m->cap_min, h);
    *searched = m->cap_min;
  }
  return m->sign[k];
}

double mrn_trimesh_distance(const mrn_trimesh *m, const double x[3], double cap_in, double cap_out, double n[3],
                            int *group) {
  double searched = fmax(fmin(cap_in, cap_out), 0.0);
  hit h;
  nearest(m, x, searched, &h);
  if (h.tri < 0) {
    const double sign = side_of(m, x, &searched, &h), cap = sign > 0.0 ? cap_out : cap_in;
    if (h.tri < 0 && cap > searched) nearest(m, x, cap, &h);
    if (h.tri < 0) { /* nothing within the cap on x's side: a value strictly beyond it */
      n[0] = n[1] = n[2] = 0.0;
      *group = -1;
      return sign * nextafter(fmax(searched, cap), HUGE_VAL);
    }
  }
  *group = m->group[h.tri];
  return resolve(m, x, &h, n);
}

/* ---- the buckets ------------------------------------------------------------------- */

/* the buckets each triangle may reach: those whose centre lies within half
 * a bucket's diagonal of it (count only, when item is NULL) */
static size_t bucket_fill(mrn_trimesh *m, size_t *count, int *item) {
  const double half = 0.5 * sqrt(3.0) * m->b * (1.0 + 1e-9);
  size_t total = 0;
  for (size_t t = 0; t < m->ntri; t++) {
    int lo[3], hi[3];
    for (int d = 0; d < 3; d++) {
      /* centres within half a diagonal (0.87 b) of the box */
      lo[d] = (int)fmax(0.0, floor((m->box[6 * t + d] - m->lo[d]) / m->b - 1.4));
      hi[d] = (int)fmin(m->nb[d] - 1.0, floor((m->box[6 * t + 3 + d] - m->lo[d]) / m->b + 0.4));
    }
    for (int k = lo[2]; k <= hi[2]; k++)
      for (int j = lo[1]; j <= hi[1]; j++)
        for (int i = lo[0]; i <= hi[0]; i++) {
          const double c[3] = {m->lo[0] + (i + 0.5) * m->b, m->lo[1] + (j + 0.5) * m->b, m->lo[2] + (k + 0.5) * m->b};
          double q[3], r[3];
          closest_point(corner(m, t, 0), corner(m, t, 1), corner(m, t, 2), c, q);
          sub3(c, q, r);
          if (dot3(r, r) > half * half) continue;
          const size_t at = bucket_index(m, i, j, k);
          if (item) item[count[at]++] = (int)t;
          else count[at + 1]++;
          total++;
        }
  }
  return total;
}

/* The sign at each bucket's centre: from the nearest triangle within two
 * buckets, else from a neighbour's (no surface lies between them then) */
static int bucket_signs(mrn_trimesh *m, size_t nbucket) {
  size_t *queue = malloc(nbucket * sizeof *queue), head = 0, tail = 0;
  if (!queue) return mrn_error("out of memory for a mesh");
  for (size_t at = 0; at < nbucket; at++) {
    const int c[3] = {(int)(at % m->nb[0]), (int)(at / m->nb[0] % m->nb[1]), (int)(at / m->nb[0] / m->nb[1])};
    const double x[3] = {m->lo[0] + (c[0] + 0.5) * m->b, m->lo[1] + (c[1] + 0.5) * m->b, m->lo[2] + (c[2] + 0.5) * m->b};
    hit h;
    double n[3];
    nearest(m, x, 2.0 * m->b, &h);
    m->sign[at] = (signed char)(h.tri < 0 ? 0 : resolve(m, x, &h, n) < 0.0 ? -1 : 1);
    if (m->sign[at]) queue[tail++] = at;
  }
  const size_t step[3] = {1, (size_t)m->nb[0], (size_t)m->nb[0] * (size_t)m->nb[1]};
  while (head < tail) {
    const size_t at = queue[head++];
    const int c[3] = {(int)(at % m->nb[0]), (int)(at / m->nb[0] % m->nb[1]), (int)(at / m->nb[0] / m->nb[1])};
    for (int d = 0; d < 3; d++)
      for (int s = -1; s <= 1; s += 2) {
        if (c[d] + s < 0 || c[d] + s >= m->nb[d]) continue;
        const size_t to = s < 0 ? at - step[d] : at + step[d];
        if (!m->sign[to]) m->sign[to] = m->sign[at], queue[tail++] = to;
      }
  }
  free(queue);
  return MRN_OK;
}

/* buckets about a cell wide over the mesh's bounding box */
static int make_buckets(mrn_trimesh *m, double cell) {
  double hi[3], vol = 1.0;
  for (int d = 0; d < 3; d++) m->lo[d] = HUGE_VAL, hi[d] = -HUGE_VAL;
  for (size_t t = 0; t < m->ntri; t++)
    for (int d = 0; d < 3; d++) m->lo[d] = fmin(m->lo[d], m->box[6 * t + d]), hi[d] = fmax(hi[d], m->box[6 * t + 3 + d]);
  for (int d = 0; d < 3; d++) vol *= hi[d] - m->lo[d] + cell;
  m->b = fmax(cell, cbrt(vol / MAX_BUCKETS));
  size_t nbucket = 1;
  for (int d = 0; d < 3; d++) {
    m->nb[d] = (int)fmax(1.0, ceil((hi[d] - m->lo[d]) / m->b));
    nbucket *= (size_t)m->nb[d];
  }
  /* a point beyond cap_min of the surface lies more than half a bucket's
   * diagonal from it, with a margin, and its bucket's centre on its side */
  m->cap_min = 1.3 * m->b;
  m->start = calloc(nbucket + 1, sizeof *m->start);
  m->sign = calloc(nbucket, 1);
  if (!m->start || !m->sign) return mrn_error("out of memory for a mesh");
  const size_t total = bucket_fill(m, m->start, NULL);
  for (size_t k = 0; k < nbucket; k++) m->start[k + 1] += m->start[k];
  size_t *at = malloc((nbucket + 1) * sizeof *at);
  m->item = malloc((total ? total : 1) * sizeof *m->item);
  if (!at || !m->item) return free(at), mrn_error("out of memory for a mesh");
  memcpy(at, m->start, (nbucket + 1) * sizeof *at);
  bucket_fill(m, at, m->item);
  free(at);
  return bucket_signs(m, nbucket);
}

static int allocate(mrn_trimesh *m) {
  m->fn = malloc(3 * m->ntri * sizeof *m->fn);
  m->en = malloc(9 * m->ntri * sizeof *m->en);
  m->vn = calloc(3 * m->nvert, sizeof *m->vn);
  m->box = malloc(6 * m->ntri * sizeof *m->box);
  m->group = malloc(m->ntri * sizeof *m->group);
  if (!m->fn || !m->en || !m->vn || !m->box || !m->group) return mrn_error("out of memory for a mesh");
  return MRN_OK;
}

static int finite_check(const double *tri, size_t n, const char *source) {
  for (size_t i = 0; i < 9 * n; i++)
    if (!isfinite(tri[i])) return mrn_error("'%s': triangle %zu has a coordinate that is not finite", source, i / 9 + 1);
  return MRN_OK;
}

mrn_trimesh *mrn_trimesh_new(const double *tri, size_t n, double cell, const char *source) {
  if (!source) source = "mesh";
  if (n < 4) return mrn_error("'%s': a closed mesh needs at least 4 triangles, got %zu", source, n), NULL;
  if (finite_check(tri, n, source)) return NULL;
  mrn_trimesh *m = calloc(1, sizeof *m);
  if (!m) return mrn_error("out of memory for a mesh"), NULL;
  m->ntri = n;
  int rc = merge_vertices(m, tri, 3 * n);
  if (!rc) rc = degenerate_check(m, source);
  edge *e = rc ? NULL : edge_list(m);
  if (!rc && !e) rc = mrn_error("out of memory for a mesh");
  if (!rc) rc = edge_check(m, e, source);
  if (!rc) rc = orient(m, source);
  free(e);
  /* turned around, the edges are listed again for their slots */
  e = rc ? NULL : edge_list(m);
  if (!rc && !e) rc = mrn_error("out of memory for a mesh");
  if (!rc) rc = allocate(m);
  if (!rc) face_normals(m), edge_normals(m, e);
  free(e);
  if (!rc) rc = number_groups(m);
  if (!rc) rc = make_buckets(m, cell);
  if (rc) return mrn_trimesh_free(m), NULL;
  return m;
}
