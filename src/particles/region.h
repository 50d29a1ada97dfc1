/* moraine: geometric regions that particles are seeded from.
 *
 * A region answers "is this point inside?" and knows a bounding box. Regions
 * are immutable and reference counted so that Lua userdata and composite
 * regions (union, difference, intersection) can share children safely.
 * Points are 3-vectors; 2D regions ignore z. */
#ifndef MRN_PARTICLES_REGION_H
#define MRN_PARTICLES_REGION_H

/* The deepest nesting of combinations a region may have. Point tests and
 * the release of a region recurse once per level, a C stack frame each (a
 * few dozen bytes, a few hundred under the sanitizers): 1000 levels stay far
 * inside any thread's stack, while a chain of a million overflowed it. A
 * region that deep already costs 1000 tests per seeded point; combining n
 * regions in one call nests them about log2(n) deep (lua_region.c). */
#define MRN_REGION_MAX_DEPTH 1000

typedef enum {
  MRN_REGION_BOX,          /* axis-aligned box min..max */
  MRN_REGION_SPHERE,       /* disk in 2D, sphere in 3D: center, radius */
  MRN_REGION_CYLINDER,     /* 3D: axis from p0 to p1 with radius; 2D: the same as a rectangle swept
                              along the segment (a capsule without caps) */
  MRN_REGION_POLYGON,      /* 2D polygon (x, y vertices, either orientation, even-odd rule) */
  MRN_REGION_UNION,        /* a or b */
  MRN_REGION_INTERSECTION, /* a and b */
  MRN_REGION_DIFFERENCE,   /* a and not b */
  MRN_REGION_PREDICATE     /* a user callback (e.g. a Lua function) */
} mrn_region_kind;

/* returns 1 inside, 0 outside, -1 on error (message set by the callback) */
typedef int (*mrn_region_predicate)(void *ctx, const double x[3]);

typedef struct mrn_region {
  mrn_region_kind kind;
  int refcount;
  int dim;             /* 2, 3, or 0 when valid in both */
  int depth;           /* 1 for a shape or predicate; 1 + the deeper operand's for a combination */
  double lo[3], hi[3]; /* bounding box; +-HUGE_VAL when unbounded (predicates) */
  double p0[3], p1[3]; /* box: min, max; sphere: center; cylinder: axis end points */
  double radius;
  double *vertices;    /* polygon: 2 * nvert values */
  int nvert;
  struct mrn_region *a, *b;
  mrn_region_predicate predicate;
  void *ctx;
  void (*release)(void *ctx); /* called once when the region is destroyed */
} mrn_region;

/* constructors return a region with refcount 1, or NULL with a message set */
mrn_region *mrn_region_box(const double lo[3], const double hi[3]);
mrn_region *mrn_region_sphere(const double center[3], double radius);
mrn_region *mrn_region_cylinder(const double p0[3], const double p1[3], double radius);
mrn_region *mrn_region_polygon(const double *xy, int nvert);
/* composites take new references to a and b; refused (NULL, message set)
 * when they would nest deeper than MRN_REGION_MAX_DEPTH */
mrn_region *mrn_region_combine(mrn_region_kind kind, mrn_region *a, mrn_region *b);
mrn_region *mrn_region_predicate_new(mrn_region_predicate fn, void *ctx, void (*release)(void *));

void mrn_region_ref(mrn_region *r);
void mrn_region_unref(mrn_region *r);

/* 1 inside, 0 outside, -1 error from a predicate */
int mrn_region_contains(const mrn_region *r, const double x[3]);
/* 1 when the bounding box is finite along the first `dim` axes */
int mrn_region_bounded(const mrn_region *r, int dim);

#endif
