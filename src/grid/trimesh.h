/* moraine: a closed triangle mesh as a signed distance (the `mesh` wall).
 *
 * Made from a triangle soup (an STL file's facets): corners closer than a
 * millionth of the mesh's size merge into shared vertices; the mesh must be
 * closed and consistently oriented (every edge shared by exactly two
 * triangles that run along it in opposite directions), its triangles not
 * degenerate, and it must enclose a volume. A mesh wound clockwise
 * throughout (its normals inward) is turned around.
 *
 * The signed distance of a point is its distance to the nearest triangle,
 * negative inside; the sign is that of (x - q) . N, with q the nearest point
 * and N the angle-weighted pseudo-normal of the face, edge or vertex q lies
 * on (Baerentzen and Aanaes 2005), exact for a closed, oriented mesh and
 * needing no more than the nearest triangle. The nearest triangle is found
 * in a uniform grid of buckets over the mesh's bounding box, searched in
 * rings of buckets around the point until no bucket left can hold anything
 * nearer. Points far from the surface take the sign stored at their
 * bucket's centre, so a query can stop at a distance `cap`.
 *
 * Triangles of one plane joined across edges form a planar group: the
 * piece of surface a node's contact column belongs to (grid/wall.c). */
#ifndef MRN_GRID_TRIMESH_H
#define MRN_GRID_TRIMESH_H

#include <stddef.h>

typedef struct mrn_trimesh mrn_trimesh;

/* The mesh of n triangles tri (9 numbers each: corners a, b, c), buckets
 * about `cell` wide; NULL with a message naming `source` (the file) and the
 * first edge or triangle at fault. */
mrn_trimesh *mrn_trimesh_new(const double *tri, size_t n, double cell, const char *source);
void mrn_trimesh_free(mrn_trimesh *m);

/* The signed distance of x from the surface (negative inside), the outward
 * unit normal at the nearest point and its planar group. Exact when the
 * distance lies in [-cap_in, cap_out]; beyond, a value beyond that bound
 * with the right sign, n zero and group -1 (caps may be HUGE_VAL). */
double mrn_trimesh_distance(const mrn_trimesh *m, const double x[3], double cap_in, double cap_out, double n[3],
                            int *group);
/* the unit normal of a planar group */
const double *mrn_trimesh_group_normal(const mrn_trimesh *m, int group);

#endif
