#include "grid/wall.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "grid/boundary.h"
#include "grid/trimesh.h"

static const char *const shape_names[] = {"plane", "box", "cylinder", "polygon", "mesh", NULL};
static const char *const kind_names[] = {"slip", "friction", "fixed", NULL};
const char *const *mrn_wall_shape_names(void) { return shape_names; }
const char *const *mrn_wall_kind_names(void) { return kind_names; }

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* ---- geometry, in the reference placement ------------------------------------------ */

/* Each shape also gives the point of its surface nearest to x in surface
 * coordinates uv = (u, v, patch): lengths along the surface (u only in 2D)
 * and which smooth piece of it (a box's face). Nodes whose nearest points
 * fall in one cell-sized patch of the surface form one contact column. */

/* two unit vectors across the unit vector a (2D: one, in the xy plane) */
static void across(const double a[3], int dim, double e1[3], double e2[3]) {
  e2[0] = e2[1] = e2[2] = 0.0;
  if (dim == 2) {
    e1[0] = -a[1], e1[1] = a[0], e1[2] = 0.0;
    return;
  }
  const double t[3] = {fabs(a[0]) < 0.6 ? 1.0 : 0.0, fabs(a[0]) < 0.6 ? 0.0 : 1.0, 0.0};
  e1[0] = a[1] * t[2] - a[2] * t[1], e1[1] = a[2] * t[0] - a[0] * t[2], e1[2] = a[0] * t[1] - a[1] * t[0];
  const double l = sqrt(dot3(e1, e1));
  for (int d = 0; d < 3; d++) e1[d] /= l;
  e2[0] = a[1] * e1[2] - a[2] * e1[1], e2[1] = a[2] * e1[0] - a[0] * e1[2], e2[2] = a[0] * e1[1] - a[1] * e1[0];
}

static double plane_distance(const mrn_wall_spec *s, int dim, const double x[3], double n[3], double uv[3]) {
  double r[3] = {0, 0, 0}, e1[3], e2[3];
  for (int d = 0; d < dim; d++) r[d] = x[d] - s->point[d];
  memcpy(n, s->normal, 3 * sizeof(double));
  across(s->normal, dim, e1, e2);
  uv[0] = dot3(r, e1), uv[1] = dot3(r, e2), uv[2] = 0.0;
  return dot3(r, s->normal);
}

/* the box: distance to its surface, the normal of the nearest face inside */
static double box_distance(const mrn_wall_spec *s, int dim, const double x[3], double n[3], double uv[3]) {
  double q[3] = {0, 0, 0}, out = 0.0, in = -HUGE_VAL;
  int face = 0;
  for (int d = 0; d < dim; d++) {
    const double r = x[d] - s->point[d];
    q[d] = fabs(r) - s->half[d];
    if (q[d] > 0.0) out += q[d] * q[d];
    if (q[d] > in) in = q[d], face = d;
  }
  const double side = copysign(1.0, x[face] - s->point[face]);
  uv[2] = 2 * face + (side > 0.0);
  for (int d = 0, k = 0; d < dim; d++)
    if (d != face) uv[k++] = x[d] - s->point[d];
  if (out > 0.0) {
    const double len = sqrt(out);
    for (int d = 0; d < dim; d++) n[d] = q[d] > 0.0 ? copysign(q[d], x[d] - s->point[d]) / len : 0.0;
    return len;
  }
  n[face] = side;
  return in;
}

static double cylinder_distance(const mrn_wall_spec *s, int dim, const double x[3], double n[3], double uv[3]) {
  double r[3] = {0, 0, 0}, e1[3], e2[3];
  for (int d = 0; d < dim; d++) r[d] = x[d] - s->point[d];
  uv[1] = uv[2] = 0.0;
  if (dim == 3) { /* the part across the axis */
    const double a = dot3(r, s->normal);
    for (int d = 0; d < 3; d++) r[d] -= a * s->normal[d];
    uv[1] = a;
    across(s->normal, dim, e1, e2);
    uv[0] = s->radius * atan2(dot3(r, e2), dot3(r, e1));
  } else {
    uv[0] = s->radius * atan2(r[1], r[0]);
  }
  const double len = sqrt(dot3(r, r));
  if (len > 0.0)
    for (int d = 0; d < 3; d++) n[d] = r[d] / len;
  else
    n[0] = 1.0; /* the axis itself: any direction across it */
  return len - s->radius;
}

/* The polygon: the distance to the nearest edge, negative inside (an odd
 * number of edges crossed by a ray along +x); the normal points from the
 * nearest point of the boundary to x, or is the edge's own normal on it.
 * u: the length along the boundary to the nearest point. */
static double polygon_distance(const mrn_wall_spec *s, const double x[3], double n[3], double uv[3]) {
  const int nv = s->nvertex;
  const double *v = s->vertex;
  double best = HUGE_VAL, cx = 0.0, cy = 0.0, ex = 1.0, ey = 0.0, along = 0.0, u = 0.0;
  int inside = 0;
  for (int i = 0, j = nv - 1; i < nv; j = i++) {
    const double ax = v[2 * j], ay = v[2 * j + 1], bx = v[2 * i], by = v[2 * i + 1];
    const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    double t = l2 > 0.0 ? ((x[0] - ax) * dx + (x[1] - ay) * dy) / l2 : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    const double px = ax + t * dx, py = ay + t * dy;
    const double dist = hypot(x[0] - px, x[1] - py);
    if (dist < best) best = dist, cx = px, cy = py, ex = dx, ey = dy, u = along + t * sqrt(l2);
    if ((ay > x[1]) != (by > x[1]) && x[0] < ax + (x[1] - ay) * dx / (by - ay)) inside = !inside;
    along += sqrt(l2);
  }
  uv[0] = u, uv[1] = uv[2] = 0.0;
  const double sign = inside ? -1.0 : 1.0;
  if (best > 1e-12 * (fabs(cx) + fabs(cy) + 1.0)) {
    n[0] = sign * (x[0] - cx) / best;
    n[1] = sign * (x[1] - cy) / best;
  } else { /* on an edge: its normal, turned outwards by the orientation */
    const double le = hypot(ex, ey), o = s->normal[2] > 0.0 ? 1.0 : -1.0;
    n[0] = o * ey / le;
    n[1] = -o * ex / le;
  }
  return sign * best;
}

/* The mesh: the distance to the nearest triangle; the patch is its planar
 * group, u and v lengths in that plane from the mesh's `point`. Searched
 * only as far as the caller needs it: in the mesh's terms, `inside` swaps
 * how deep and how far. */
static double mesh_distance(const mrn_wall *w, const double x[3], double n[3], double uv[3], double deep, double far) {
  const mrn_wall_spec *s = &w->spec;
  int group;
  const double d = s->inside ? mrn_trimesh_distance(w->mesh, x, far, deep, n, &group)
                             : mrn_trimesh_distance(w->mesh, x, deep, far, n, &group);
  uv[0] = uv[1] = 0.0, uv[2] = group;
  if (group >= 0) {
    double r[3], e1[3], e2[3];
    for (int d3 = 0; d3 < 3; d3++) r[d3] = x[d3] - s->point[d3];
    across(mrn_trimesh_group_normal(w->mesh, group), 3, e1, e2);
    uv[0] = dot3(r, e1), uv[1] = dot3(r, e2);
  }
  return d;
}

/* signed distance, outward normal and surface coordinates in the reference
 * placement: the one place a new shape is added. Exact when the distance
 * lies in [-deep, far]; beyond, a mesh may stop its search and give a value
 * beyond that bound (with the right sign, a zero normal) */
static double wall_distance_body(const mrn_wall *w, int dim, const double x[3], double n[3], double uv[3], double deep,
                                 double far) {
  const mrn_wall_spec *s = &w->spec;
  double d;
  n[0] = n[1] = n[2] = 0.0;
  switch (s->shape) {
  case MRN_WALL_PLANE: d = plane_distance(s, dim, x, n, uv); break;
  case MRN_WALL_BOX: d = box_distance(s, dim, x, n, uv); break;
  case MRN_WALL_CYLINDER: d = cylinder_distance(s, dim, x, n, uv); break;
  case MRN_WALL_POLYGON: d = polygon_distance(s, x, n, uv); break;
  case MRN_WALL_MESH: d = mesh_distance(w, x, n, uv, deep, far); break;
  default: return HUGE_VAL;
  }
  if (s->inside) {
    for (int k = 0; k < 3; k++) n[k] = -n[k];
    d = -d;
  }
  return d;
}

/* mrn_wall_distance, with the surface coordinates of the nearest point,
 * exact in [-deep, far] (wall_distance_body) */
static double wall_distance_uv(const mrn_wall *w, int dim, const double x[3], double n[3], double uv[3], double deep,
                               double far) {
  /* into the reference placement: x_ref = R^T (x - ref) + center */
  const double *R = w->rot;
  double r[3], xb[3], nb[3];
  for (int d = 0; d < 3; d++) r[d] = x[d] - w->ref[d];
  for (int d = 0; d < 3; d++) xb[d] = R[d] * r[0] + R[3 + d] * r[1] + R[6 + d] * r[2] + w->spec.center[d];
  if (dim == 2) xb[2] = 0.0;
  const double dist = wall_distance_body(w, dim, xb, nb, uv, deep, far);
  for (int d = 0; d < 3; d++) n[d] = R[3 * d] * nb[0] + R[3 * d + 1] * nb[1] + R[3 * d + 2] * nb[2];
  if (dim == 2) n[2] = 0.0;
  return dist;
}

double mrn_wall_distance(const mrn_wall *w, int dim, const double x[3], double n[3]) {
  double uv[3];
  return wall_distance_uv(w, dim, x, n, uv, HUGE_VAL, HUGE_VAL);
}

/* the signed distance where only how it compares with +-cap matters */
static double wall_distance_near(const mrn_wall *w, int dim, const double x[3], double cap) {
  double n[3], uv[3];
  return wall_distance_uv(w, dim, x, n, uv, cap, cap);
}

void mrn_wall_velocity_at(const mrn_wall *w, int dim, const double x[3], double v[3]) {
  const double *o = w->spec.omega, *u = w->spec.velocity;
  double r[3];
  for (int d = 0; d < 3; d++) r[d] = x[d] - w->ref[d];
  v[0] = u[0] + o[1] * r[2] - o[2] * r[1];
  v[1] = u[1] + o[2] * r[0] - o[0] * r[2];
  v[2] = u[2] + o[0] * r[1] - o[1] * r[0];
  if (dim == 2) v[2] = 0.0;
}

/* ---- making walls ------------------------------------------------------------------ */

static int normalise(double v[3], int dim, const char *key) {
  if (dim == 2) v[2] = 0.0;
  const double len = sqrt(dot3(v, v));
  if (!(len > 0.0) || !isfinite(len)) return mrn_error("%s: expected a nonzero finite vector", key);
  for (int d = 0; d < 3; d++) v[d] /= len;
  return MRN_OK;
}

/* the checks of the shape's own keys; the polygon's orientation goes to
 * normal[2] (+1: counter-clockwise) */
static int check_shape(mrn_wall_spec *s, int dim) {
  switch (s->shape) {
  case MRN_WALL_PLANE: return normalise(s->normal, dim, "normal");
  case MRN_WALL_BOX:
    for (int d = 0; d < dim; d++)
      if (!(s->half[d] > 0.0) || !isfinite(s->half[d]))
        return mrn_error("size: expected positive finite sides, got %g along axis %d", 2 * s->half[d], d + 1);
    return MRN_OK;
  case MRN_WALL_CYLINDER:
    if (!(s->radius > 0.0) || !isfinite(s->radius)) return mrn_error("radius: expected > 0, got %g", s->radius);
    return dim == 3 ? normalise(s->normal, dim, "axis") : MRN_OK;
  case MRN_WALL_POLYGON: {
    if (dim != 2) return mrn_error("shape: a polygon wall is 2D only");
    if (s->nvertex < 3 || s->nvertex > MRN_WALL_MAX_VERTICES)
      return mrn_error("vertices: expected 3 to %d points, got %d", MRN_WALL_MAX_VERTICES, s->nvertex);
    double area = 0.0;
    for (int i = 0, j = s->nvertex - 1; i < s->nvertex; j = i++)
      area += s->vertex[2 * j] * s->vertex[2 * i + 1] - s->vertex[2 * i] * s->vertex[2 * j + 1];
    if (!(fabs(area) > 0.0) || !isfinite(area)) return mrn_error("vertices: the polygon encloses no area");
    s->normal[0] = s->normal[1] = 0.0;
    s->normal[2] = area > 0.0 ? 1.0 : -1.0;
    return MRN_OK;
  }
  case MRN_WALL_MESH:
    if (dim != 3) return mrn_error("shape: a mesh wall is 3D only");
    if (s->ntriangle < 1 || s->ntriangle > MRN_WALL_MAX_TRIANGLES)
      return mrn_error("triangles: expected 1 to %d, got %d", MRN_WALL_MAX_TRIANGLES, s->ntriangle);
    return MRN_OK;
  default: return mrn_error("shape: unknown wall shape");
  }
}

/* the length of the closed surface coordinate u: a cylinder's
 * circumference, a polygon's perimeter; 0 where u is open (a plane, a
 * box's faces, a mesh's planar groups) */
static double surface_period(const mrn_wall_spec *s, int dim) {
  if (s->shape == MRN_WALL_MESH) return 0.0;
  if (s->shape == MRN_WALL_CYLINDER) return 2.0 * 3.14159265358979323846 * s->radius;
  if (s->shape != MRN_WALL_POLYGON || dim != 2) return 0.0;
  double len = 0.0;
  for (int i = 0, j = s->nvertex - 1; i < s->nvertex; j = i++)
    len += hypot(s->vertex[2 * i] - s->vertex[2 * j], s->vertex[2 * i + 1] - s->vertex[2 * j + 1]);
  return len;
}

/* 1 when some node of the grid (ghosts included) lies inside the wall or
 * within a cell of it */
static int reaches_grid(const mrn_wall *w, const mrn_grid *g) {
  double x[3];
  for (size_t i = 0; i < g->n; i++) {
    mrn_grid_node_position(g, i, x);
    if (wall_distance_near(w, g->dim, x, g->cell) <= g->cell) return 1;
  }
  return 0;
}

static int outside_error(const char *name, const mrn_grid *g) {
  char box[192] = "";
  for (int d = 0; d < g->dim; d++) {
    const size_t len = strlen(box);
    snprintf(box + len, sizeof box - len, "%s[%g, %g]", d ? " x " : "", g->origin[d], g->origin[d] + g->size[d]);
  }
  return mrn_error("wall '%s' lies entirely outside the grid (no node within a cell of it): the domain is %s", name, box);
}

static int check_spec(mrn_walls *ws, const mrn_wall_spec *s, int dim) {
  if (!s->name[0]) return mrn_error("name: expected a non-empty name");
  if (ws && mrn_walls_find(ws, s->name)) return mrn_error("name: a wall named '%s' exists already", s->name);
  if (s->kind >= MRN_WALL_KIND_COUNT) return mrn_error("kind: unknown wall kind");
  if (!(s->mu >= 0.0) || !isfinite(s->mu)) return mrn_error("mu: expected a finite number >= 0, got %g", s->mu);
  for (int d = 0; d < 3; d++)
    if (!isfinite(s->velocity[d]) || !isfinite(s->omega[d]) || !isfinite(s->point[d]) || !isfinite(s->center[d]))
      return mrn_error("point, center, velocity, omega: expected finite numbers");
  if (dim == 2 && (s->omega[0] != 0.0 || s->omega[1] != 0.0))
    return mrn_error("omega: a 2D wall turns about z only (give one number)");
  return MRN_OK;
}

static void wall_release(mrn_wall *w) {
  if (w->motion_release) w->motion_release(w->motion_ctx);
  free(w->spec.vertex);
  free(w->spec.triangle);
  mrn_trimesh_free(w->mesh);
  free(w->state);
  free(w->outside);
  free(w->node);
  free(w->n);
  free(w->w);
  free(w->key);
  free(w->col_node);
  free(w->col_start);
  free(w->col_n);
  free(w->col_w);
  free(w->col_first);
  free(w->col_state);
  free(w->sums);
}

/* the polygon's corners or the mesh's triangles, copied */
static int copy_shape(mrn_wall *w, const mrn_wall_spec *spec) {
  if (spec->shape == MRN_WALL_POLYGON && spec->nvertex > 0) {
    w->spec.vertex = malloc(2 * (size_t)spec->nvertex * sizeof(double));
    if (!w->spec.vertex) return mrn_error("out of memory for a wall");
    memcpy(w->spec.vertex, spec->vertex, 2 * (size_t)spec->nvertex * sizeof(double));
  }
  if (spec->shape != MRN_WALL_MESH || spec->ntriangle <= 0 || spec->ntriangle > MRN_WALL_MAX_TRIANGLES) return MRN_OK;
  w->spec.triangle = malloc(9 * (size_t)spec->ntriangle * sizeof(double));
  if (!w->spec.triangle) return mrn_error("out of memory for a wall");
  memcpy(w->spec.triangle, spec->triangle, 9 * (size_t)spec->ntriangle * sizeof(double));
  return MRN_OK;
}

int mrn_walls_add(mrn_walls **wsp, const mrn_grid *g, const mrn_wall_spec *spec) {
  mrn_wall w;
  memset(&w, 0, sizeof w);
  w.spec = *spec;
  w.spec.vertex = NULL, w.spec.triangle = NULL, w.spec.source = NULL;
  int rc = check_spec(*wsp, &w.spec, g->dim);
  if (!rc) rc = copy_shape(&w, spec);
  if (!rc) rc = check_shape(&w.spec, g->dim);
  if (!rc) w.period = surface_period(&w.spec, g->dim);
  if (!rc && spec->shape == MRN_WALL_MESH) {
    w.mesh = mrn_trimesh_new(w.spec.triangle, (size_t)w.spec.ntriangle, g->cell, spec->source);
    if (!w.mesh) rc = MRN_ERR;
  }
  if (!rc && w.spec.body) rc = mrn_body_setup(&w, g->dim);
  memcpy(w.ref, w.spec.center, sizeof w.ref);
  w.rot[0] = w.rot[4] = w.rot[8] = 1.0;
  if (!rc && !reaches_grid(&w, g)) rc = outside_error(spec->name, g);
  if (!rc && !(w.state = calloc(g->n, 1))) rc = mrn_error("out of memory for a wall");
  mrn_walls *ws = *wsp;
  if (!rc && !ws && !(ws = *wsp = calloc(1, sizeof *ws))) rc = mrn_error("out of memory for a wall");
  mrn_wall *grown = rc ? NULL : realloc(ws->wall, (size_t)(ws->count + 1) * sizeof *grown);
  if (!rc && !grown) rc = mrn_error("out of memory for a wall");
  if (rc) {
    wall_release(&w);
    return rc;
  }
  ws->wall = grown;
  ws->dim = g->dim;
  ws->wall[ws->count++] = w;
  return MRN_OK;
}

void mrn_walls_free(mrn_walls *ws) {
  if (!ws) return;
  for (int i = 0; i < ws->count; i++) wall_release(&ws->wall[i]);
  free(ws->wall);
  free(ws);
}

mrn_wall *mrn_walls_find(mrn_walls *ws, const char *name) {
  for (int i = 0; ws && i < ws->count; i++)
    if (strcmp(ws->wall[i].spec.name, name) == 0) return &ws->wall[i];
  return NULL;
}

/* ---- touching ---------------------------------------------------------------------- */

/* How far, in initial half sides, a particle's extent may stand off a wall
 * and keep a contact it has; a new contact needs the material on the wall:
 * as for the friction faces (boundary.c), which this rule was chosen for */
#define WALL_TOUCH_SLACK 0.5

/* doubles per column in mrn_wall.sums: 7 + COLUMN_BITS while the columns
 * are built; while they act the impulse J, N, M and P, and the normal
 * momentum the first V held (mrn_contact_bound), from 8 ncol */
enum { COLUMN_BITS = 4, WALL_SUMS = 7 + COLUMN_BITS };

static int grow(void **p, size_t bytes) {
  void *q = realloc(*p, bytes);
  if (!q) return mrn_error("out of memory for a wall's contacts");
  *p = q;
  return MRN_OK;
}

static int touched_push(mrn_wall *w, size_t node, const double n[3], const double v[3], const long long key[3]) {
  if (w->count == w->cap) {
    size_t cap = w->cap ? 2 * w->cap : 256;
    if (grow((void **)&w->node, cap * sizeof *w->node) || grow((void **)&w->n, 3 * cap * sizeof *w->n) ||
        grow((void **)&w->w, 3 * cap * sizeof *w->w) || grow((void **)&w->key, 3 * cap * sizeof *w->key) ||
        grow((void **)&w->col_node, cap * sizeof *w->col_node))
      return MRN_ERR;
    w->cap = cap;
  }
  w->node[w->count] = node;
  for (int d = 0; d < 3; d++) {
    w->n[3 * w->count + d] = n[d];
    w->w[3 * w->count + d] = v[d];
    w->key[3 * w->count + d] = key[d];
  }
  w->count++;
  return MRN_OK;
}

/* a node found outside the wall: not asked again this step (the nodes near
 * the surface lie in the reach of many particles) */
static int outside_push(mrn_wall *w, size_t node) {
  if (w->nout == w->capout) {
    const size_t cap = w->capout ? 2 * w->capout : 256;
    if (grow((void **)&w->outside, cap * sizeof *w->outside)) return MRN_ERR;
    w->capout = cap;
  }
  w->outside[w->nout++] = node;
  w->state[node] |= MRN_WALL_OUTSIDE;
  return MRN_OK;
}

/* 1 when a particle of half side r, whose nearest point of the surface has
 * the coordinates uv, lies over the patch `key` (as the faces'
 * mrn_contact_over_patch; a box's other faces are other patches, a closed
 * coordinate is taken the short way round) */
static int over_patch(const mrn_wall *w, const mrn_grid *g, const long long key[3], const double uv[3], double r) {
  if (key[0] != (long long)uv[2]) return 0;
  for (int d = 0; d < g->dim - 1; d++) {
    const double c = (double)key[1 + d] * g->cell;
    const double x = d == 0 && w->period > 0.0 ? c + remainder(uv[0] - c, w->period) : uv[d];
    if (!mrn_contact_over_patch(x, c, r, g->cell)) return 0;
  }
  return 1;
}

/* the patch of a node: the cell-sized piece of the surface nearest it */
static void patch_key(const mrn_grid *g, const double uv[3], long long key[3]) {
  key[0] = (long long)uv[2];
  key[1] = llround(uv[0] * g->inv_cell);
  key[2] = llround(uv[1] * g->inv_cell);
}

/* Visit the nodes inside the wall (signed distance <= 0) within `reach`
 * cells of a particle at x (the nodes its momentum lands in); uvp: its
 * nearest point of the surface, r its half side. A particle on the wall
 * (`on`) marks them touched (with `held_only`, only those that ended the
 * last step in contact) and OVER those whose patch it lies over; a particle
 * above the wall marks CLEAR the touched ones whose patch it lies over. A
 * node found outside is marked so and not asked again this step. */
static int touch_visit(mrn_wall *w, const mrn_grid *g, const double *x, const double uvp[3], double r, double reach,
                       int on, int held_only) {
  int lo[3], hi[3];
  mrn_grid_reach_box(g, x, reach, lo, hi);
  for (int k = lo[2]; k <= hi[2]; k++)
    for (int j = lo[1]; j <= hi[1]; j++)
      for (int i = lo[0]; i <= hi[0]; i++) {
        const size_t node = mrn_grid_index(g, i, j, k);
        const unsigned char st = w->state[node];
        /* found outside already this step: never touched, in either pass */
        if (st & MRN_WALL_OUTSIDE) continue;
        if (on ? held_only && !(st & MRN_WALL_CONTACT) : !(st & MRN_WALL_TOUCH)) continue;
        if (on && (st & MRN_WALL_TOUCH) && !w->spec.gap_check) continue; /* nothing to learn */
        double xn[3], n[3], v[3], uv[3];
        mrn_grid_node_position(g, node, xn);
        /* on the surface counts as inside: a node of a grid-aligned plane must not
         * drop out by the round-off of its position */
        if (!(wall_distance_uv(w, g->dim, xn, n, uv, HUGE_VAL, 1e-9 * g->cell) <= 1e-9 * g->cell)) {
          if (outside_push(w, node)) return MRN_ERR;
          continue;
        }
        long long key[3];
        patch_key(g, uv, key);
        if (w->spec.gap_check && over_patch(w, g, key, uvp, r)) w->state[node] |= on ? MRN_WALL_OVER : MRN_WALL_CLEAR;
        if (!on || (st & MRN_WALL_TOUCH)) continue;
        mrn_wall_velocity_at(w, g->dim, xn, v);
        w->state[node] |= MRN_WALL_TOUCH;
        if (touched_push(w, node, n, v, key)) return MRN_ERR;
      }
  return MRN_OK;
}

/* a node a neighbouring process's material touched (mrn_walls_share.band_or) */
typedef struct fresh_ctx {
  mrn_wall *w;
  const mrn_grid *g;
} fresh_ctx;

static int touch_fresh(void *arg, size_t node) {
  const fresh_ctx *f = arg;
  double xn[3], n[3], v[3], uv[3];
  long long key[3];
  mrn_grid_node_position(f->g, node, xn);
  wall_distance_uv(f->w, f->g->dim, xn, n, uv, HUGE_VAL, 1e-9 * f->g->cell);
  patch_key(f->g, uv, key);
  mrn_wall_velocity_at(f->w, f->g->dim, xn, v);
  return touched_push(f->w, node, n, v, key);
}

/* a touched node as the sort sees it: its patch, its node, its place */
typedef struct patch_entry {
  long long key[3];
  size_t node, k;
} patch_entry;

/* the touched nodes in order of patch, then of node */
static int by_patch(const void *a, const void *b) {
  const patch_entry *p = a, *q = b;
  for (int d = 0; d < 3; d++)
    if (p->key[d] != q->key[d]) return p->key[d] < q->key[d] ? -1 : 1;
  return p->node < q->node ? -1 : p->node > q->node;
}

/* room for n columns */
static int columns_reserve(mrn_wall *w, size_t n) {
  if (n <= w->col_cap) return MRN_OK;
  const size_t cap = n > 2 * w->col_cap ? n : 2 * w->col_cap;
  if (grow((void **)&w->col_start, (cap + 1) * sizeof *w->col_start) ||
      grow((void **)&w->col_first, cap * sizeof *w->col_first) || grow((void **)&w->col_n, 3 * cap * sizeof *w->col_n) ||
      grow((void **)&w->col_w, 3 * cap * sizeof *w->col_w) || grow((void **)&w->col_state, cap) ||
      grow((void **)&w->sums, WALL_SUMS * cap * sizeof *w->sums))
    return MRN_ERR;
  w->col_cap = cap;
  return MRN_OK;
}

/* The touched nodes sorted by patch, then node (e), and the patches' keys
 * (3 each, *nkeys of them, in that order) */
static int local_patches(const mrn_wall *w, patch_entry **e, long long **keys, size_t *nkeys) {
  *nkeys = 0;
  *e = malloc((w->count + 1) * sizeof **e);
  *keys = malloc((3 * w->count + 1) * sizeof **keys);
  if (!*e || !*keys) return mrn_error("out of memory for a wall's contacts");
  for (size_t k = 0; k < w->count; k++) {
    memcpy((*e)[k].key, w->key + 3 * k, sizeof (*e)[k].key);
    (*e)[k].node = w->node[k], (*e)[k].k = k;
  }
  qsort(*e, w->count, sizeof **e, by_patch);
  for (size_t k = 0; k < w->count; k++)
    if (k == 0 || memcmp((*e)[k].key, (*e)[k - 1].key, sizeof (*e)[k].key) != 0)
      memcpy(*keys + 3 * (*nkeys)++, (*e)[k].key, sizeof (*e)[k].key);
  return MRN_OK;
}

/* the state bits a column takes from the union of its nodes', one number each */
static const unsigned char column_bit[COLUMN_BITS - 1] = {MRN_WALL_CONTACT, MRN_WALL_OVER, MRN_WALL_CLEAR};

/* A column's sums over its nodes here, e[lo .. hi - 1]: sums[0 .. 7) the
 * normals (into the wall) and velocities of the nodes this process books
 * and their count, to be summed over the processes; bits[0 .. 3) 1 where
 * one of them has the bit column_bit[k], bits[3] minus the first node's
 * index, to be maximised */
static void column_sums(const mrn_wall *w, const mrn_grid *g, const patch_entry *e, size_t lo, size_t hi, double *sums,
                        double *bits) {
  unsigned seen = 0;
  for (size_t q = lo; q < hi; q++) {
    const size_t k = e[q].k;
    seen |= w->state[e[q].node];
    if (!mrn_grid_owns(g, (long)e[q].node)) continue;
    for (int d = 0; d < 3; d++) sums[d] -= w->n[3 * k + d], sums[3 + d] += w->w[3 * k + d];
    sums[6] += 1.0;
  }
  for (int k = 0; k < COLUMN_BITS - 1; k++) bits[k] = (seen & column_bit[k]) != 0;
  if (hi > lo) bits[COLUMN_BITS - 1] = -(double)e[lo].node; /* the lowest index: the nodes are sorted */
}

/* Column c from its summed sums: its mean normal and velocity, its contact
 * bit and first node; 0 when the material over its patch stands clear of the
 * wall (gap_check): then it is no column, and its nodes lose their contact */
static int column_close(mrn_wall *w, size_t c, const double *sums, const double *bits) {
  unsigned char seen = 0;
  for (int k = 0; k < COLUMN_BITS - 1; k++) seen |= bits[k] > 0.0 ? column_bit[k] : 0;
  if ((seen & MRN_WALL_CLEAR) && !(seen & MRN_WALL_OVER)) return 0;
  double *n = w->col_n + 3 * c, *v = w->col_w + 3 * c;
  const double len = sqrt(dot3(sums, sums));
  for (int d = 0; d < 3; d++) {
    n[d] = len > 0.0 ? sums[d] / len : 0.0;
    v[d] = sums[3 + d] / sums[6];
  }
  w->col_state[c] = seen & MRN_WALL_CONTACT;
  w->col_first[c] = (size_t)-bits[COLUMN_BITS - 1];
  return 1;
}

/* The columns of the patches all[0 .. total) (3 numbers each, in the order
 * of e's), from the touched nodes e here; sums and bits combined over the
 * processes when shared */
static void fill_columns(mrn_wall *w, const mrn_grid *g, const mrn_walls_share *share, const patch_entry *e,
                         const long long *all, size_t total) {
  double *sums = w->sums, *bits = w->sums + 7 * total; /* COLUMN_BITS per column */
  size_t *from = w->col_start; /* where each patch's nodes start in e, until overwritten below */
  memset(sums, 0, 7 * total * sizeof *sums);
  for (size_t c = 0, q = 0; c <= total; c++) {
    from[c] = q;
    while (c < total && q < w->count && memcmp(e[q].key, all + 3 * c, sizeof e[q].key) == 0) q++;
  }
  for (size_t c = 0; c < total; c++) {
    double *b = bits + COLUMN_BITS * c;
    for (int k = 0; k < COLUMN_BITS - 1; k++) b[k] = 0.0;
    b[COLUMN_BITS - 1] = -HUGE_VAL;
    column_sums(w, g, e, from[c], from[c + 1], sums + 7 * c, b);
  }
  if (share) {
    share->reduce(share->ctx, sums, 7 * total, MRN_COMM_SUM);
    share->reduce(share->ctx, bits, COLUMN_BITS * total, MRN_COMM_MAX);
  }
  w->ncol = 0;
  size_t m = 0;
  for (size_t c = 0; c < total; c++) {
    const size_t lo = from[c], hi = from[c + 1]; /* read before column ncol <= c overwrites them */
    if (!column_close(w, w->ncol, sums + 7 * c, bits + COLUMN_BITS * c)) {
      for (size_t q = lo; q < hi; q++) w->state[e[q].node] &= (unsigned char)~(MRN_WALL_TOUCH | MRN_WALL_CONTACT);
      continue;
    }
    w->col_start[w->ncol++] = m;
    for (size_t q = lo; q < hi; q++) w->col_node[m++] = e[q].node;
  }
  w->col_start[w->ncol] = m;
}

/* Group the touched nodes into columns, one per surface patch: in a
 * distributed run, the patches of every process, each with its sums over
 * all (rc: the outcome so far, agreed first) */
static int build_columns(mrn_wall *w, const mrn_grid *g, const mrn_walls_share *share, int rc) {
  patch_entry *e = NULL;
  long long *keys = NULL, *all = NULL;
  size_t nkeys = 0, total = 0;
  if (rc == MRN_OK) rc = local_patches(w, &e, &keys, &nkeys);
  if (share) rc = share->agree(share->ctx, rc);
  if (rc == MRN_OK && share) all = share->union_keys(share->ctx, keys, nkeys, &total);
  else if (rc == MRN_OK) all = keys, total = nkeys;
  if (rc == MRN_OK && (!all || columns_reserve(w, total + 1))) rc = MRN_ERR; /* message set */
  if (share) rc = share->agree(share->ctx, rc);
  if (rc == MRN_OK) fill_columns(w, g, share, e, all, total);
  if (all != keys) free(all);
  free(keys);
  free(e);
  return rc;
}

/* One pass over the particles: the material on the wall (pass 0), or the
 * material above it (pass 1, gap_check only); the distance exact where the
 * passes compare it (a mesh stops beyond) */
static int touch_pass(mrn_wall *w, const mrn_grid *g, double reach, const double *x, const double *vol0, size_t np,
                      int pass) {
  const int passes = w->spec.gap_check ? 2 : 1;
  int rc = MRN_OK;
  for (size_t p = 0; p < np && !rc; p++) {
    const double r = 0.5 * (g->dim == 2 ? sqrt(vol0[p]) : cbrt(vol0[p]));
    const double deep = passes > 1 ? HUGE_VAL : 1.5 * r, far = passes > 1 ? fmax(1.5 * r, reach * g->cell) : 1.5 * r;
    double n[3], uv[3];
    const double gap = wall_distance_uv(w, g->dim, x + 3 * p, n, uv, deep, far) - r;
    if (pass == 0 && gap <= WALL_TOUCH_SLACK * r) rc = touch_visit(w, g, x + 3 * p, uv, r, reach, 1, gap > 0.0);
    else if (pass == 1 && gap > 0.0 && gap + r < reach * g->cell) rc = touch_visit(w, g, x + 3 * p, uv, r, reach, 0, 0);
  }
  return rc;
}

/* One wall: the nodes of the last step lose their touch bit; those no
 * longer touched lose their contact too (as a face's untouched column). In
 * a distributed run the nodes of the bands a neighbour's material touched
 * are touched here too, before the material above the wall is looked at. */
static int wall_touch(mrn_wall *w, const mrn_grid *g, double reach, const double *x, const double *vol0, size_t np,
                      const mrn_walls_share *share) {
  const size_t old = w->count;
  for (size_t k = 0; k < old; k++)
    w->state[w->node[k]] &= (unsigned char)~(MRN_WALL_TOUCH | MRN_WALL_OVER | MRN_WALL_CLEAR);
  for (size_t k = 0; k < w->nout; k++) w->state[w->outside[k]] &= (unsigned char)~MRN_WALL_OUTSIDE;
  w->nout = 0;
  w->count = 0;
  /* the old list is read again below: keep it aside while the new one grows */
  size_t *prev = old ? malloc(old * sizeof *prev) : NULL;
  int rc = old && !prev ? mrn_error("out of memory for a wall's contacts") : MRN_OK;
  if (prev) memcpy(prev, w->node, old * sizeof *prev);
  if (rc == MRN_OK) rc = touch_pass(w, g, reach, x, vol0, np, 0);
  if (share && (rc = share->agree(share->ctx, rc)) == MRN_OK) {
    fresh_ctx f = {w, g};
    rc = share->band_or(share->ctx, w->state, MRN_WALL_TOUCH, touch_fresh, &f);
  }
  if (rc == MRN_OK && w->spec.gap_check) rc = touch_pass(w, g, reach, x, vol0, np, 1);
  for (size_t k = 0; rc == MRN_OK && k < old; k++)
    if (!(w->state[prev[k]] & MRN_WALL_TOUCH)) w->state[prev[k]] &= (unsigned char)~MRN_WALL_CONTACT;
  free(prev);
  if (rc && !share) return rc;
  return build_columns(w, g, share, rc);
}

/* the motion function's velocities, checked */
static int wall_motion(mrn_wall *w, int dim, double t) {
  double v[3] = {0, 0, 0}, o[3] = {0, 0, 0};
  int rc = w->motion(w->motion_ctx, t, v, o);
  if (rc) return rc;
  if (dim == 2) v[2] = o[0] = o[1] = 0.0;
  for (int d = 0; d < 3; d++)
    if (!isfinite(v[d]) || !isfinite(o[d]))
      return mrn_error("wall '%s': its motion function gave a non-finite velocity at t = %g s", w->spec.name, t);
  memcpy(w->spec.velocity, v, sizeof v);
  memcpy(w->spec.omega, o, sizeof o);
  return MRN_OK;
}

int mrn_wall_reset_contacts(mrn_wall *w, const size_t *contact, size_t n) {
  for (size_t k = 0; k < w->count; k++)
    w->state[w->node[k]] &= (unsigned char)~(MRN_WALL_TOUCH | MRN_WALL_CONTACT | MRN_WALL_OVER | MRN_WALL_CLEAR);
  w->count = w->ncol = 0;
  return mrn_wall_restore(w, contact, n);
}

int mrn_wall_restore(mrn_wall *w, const size_t *contact, size_t n) {
  const double zero[3] = {0, 0, 0};
  const long long key[3] = {0, 0, 0};
  for (size_t k = 0; k < n; k++) {
    w->state[contact[k]] |= MRN_WALL_TOUCH | MRN_WALL_CONTACT;
    if (touched_push(w, contact[k], zero, zero, key)) return MRN_ERR;
  }
  return MRN_OK;
}

int mrn_walls_touch(mrn_walls *ws, const mrn_grid *g, double t_mid, double reach, const double *x, const double *vol0,
                    size_t n) {
  if (!ws) return MRN_OK;
  int rc = MRN_OK;
  for (int i = 0; rc == MRN_OK && i < ws->count; i++)
    if (ws->wall[i].motion) rc = wall_motion(&ws->wall[i], g->dim, t_mid);
  if (ws->share) rc = ws->share->agree(ws->share->ctx, rc);
  for (int i = 0; rc == MRN_OK && i < ws->count; i++) {
    mrn_wall *w = &ws->wall[i];
    memset(w->impulse, 0, sizeof w->impulse);
    memset(w->angular, 0, sizeof w->angular);
    memset(w->hold_impulse, 0, sizeof w->hold_impulse);
    memset(w->hold_angular, 0, sizeof w->hold_angular);
    w->step_work = w->hold_work = w->step_friction = 0.0;
    w->v_done = 0;
    w->contacts = 0;
    rc = wall_touch(w, g, reach, x, vol0, n, ws->share);
    if (rc == MRN_OK && w->ncol) memset(w->sums + 8 * w->ncol, 0, w->ncol * sizeof *w->sums); /* nothing held yet */
  }
  return rc;
}

/* ---- the contact ------------------------------------------------------------------- */

/* a fixed wall: the node moves with the wall; the impulse goes to J where
 * this process books it (mrn_grid_owns) */
static void wall_fix(const mrn_grid *g, double mass_floor, double *v, size_t node, const double w[3], double J[3]) {
  if (!(g->mass[node] > mass_floor)) return;
  const int books = mrn_grid_owns(g, (long)node);
  for (int d = 0; d < 3; d++) {
    if (books) J[d] += g->mass[node] * (w[d] - v[d]);
    v[d] = w[d];
  }
}

/* column c as the contact of grid/boundary.h sees it */
static mrn_contact_column column_of(const mrn_wall *w, size_t c) {
  const size_t lo = w->col_start[c], hi = w->col_start[c + 1];
  mrn_contact_column col = {.count = (int)(hi - lo), .nodes = w->col_node + lo, .axis = -1, .shared = 1};
  memcpy(col.n, w->col_n + 3 * c, sizeof col.n);
  memcpy(col.w, w->col_w + 3 * c, sizeof col.w);
  return col;
}

/* The contact of grid/boundary.h on every column, in sweeps with the sums
 * over the processes between them (share): each column's N; the holds, and
 * M and P of the columns held; friction. The column's contact bit is its
 * own (the union of its nodes', kept on them for the next step's touch).
 * J: 3 per column. The holds of a field without friction are added to the
 * columns' memory with `weight` (their weight in what reaches the
 * particles), which bounds the friction of V~ (mrn_contact_bound, with
 * hold_share). Returns the frictional work. */
static double contact_columns(mrn_wall *w, mrn_grid *g, double mass_floor, double *vel, int with_friction, double *J,
                              const mrn_walls_share *share, double weight, double hold_share) {
  const size_t nc = w->ncol;
  double *N = w->sums + 3 * nc, *MP = N + nc, *held = MP + 4 * nc, work = 0.0;
  const double mu = w->spec.kind == MRN_WALL_FRICTION ? w->spec.mu : 0.0;
  for (size_t c = 0; c < nc; c++) {
    const mrn_contact_column col = column_of(w, c);
    N[c] = mrn_contact_push(&col, g, mass_floor, vel);
  }
  if (share) share->reduce(share->ctx, N, nc, MRN_COMM_SUM);
  for (size_t c = 0; c < nc; c++) {
    const mrn_contact_column col = column_of(w, c);
    for (int k = 0; k < 4; k++) MP[4 * c + k] = 0.0; /* a column not held slides by nothing */
    const int in_contact = mrn_contact_held(N[c], with_friction, 1, &w->col_state[c], MRN_WALL_CONTACT);
    if (in_contact && !with_friction) held[c] += weight * N[c];
    if (in_contact) {
      mrn_contact_hold(&col, g, mass_floor, vel, J + 3 * c);
      if (with_friction) mrn_contact_slide_sums(&col, g, mass_floor, vel, MP + 4 * c);
    }
    if (!with_friction) continue;
    for (int k = 0; k < col.count; k++)
      w->state[col.nodes[k]] = (unsigned char)((w->state[col.nodes[k]] & ~MRN_WALL_CONTACT) | w->col_state[c]);
    w->contacts += w->col_state[c] != 0;
  }
  if (!with_friction) return 0.0;
  if (share) share->reduce(share->ctx, MP, 4 * nc, MRN_COMM_SUM);
  for (size_t c = 0; c < nc; c++) {
    const mrn_contact_column col = column_of(w, c);
    const double bound = mrn_contact_bound(N[c], held[c], hold_share);
    work += mrn_contact_slide(&col, g, mass_floor, vel, mu, bound, MP + 4 * c, J + 3 * c);
  }
  return work;
}

/* add the impulse J of column c and its moment about ref to imp, ang; the
 * wall's work J . w to *work */
static void book(const mrn_wall *w, const mrn_grid *g, size_t c, const double J[3], double imp[3], double ang[3],
                 double *work) {
  double pos[3], r[3];
  mrn_grid_node_position(g, w->col_first[c], pos);
  for (int d = 0; d < 3; d++) {
    imp[d] += J[d];
    r[d] = pos[d] - w->ref[d];
  }
  ang[0] += r[1] * J[2] - r[2] * J[1];
  ang[1] += r[2] * J[0] - r[0] * J[2];
  ang[2] += r[0] * J[1] - r[1] * J[0];
  *work += dot3(J, w->col_w + 3 * c);
}

static double wall_apply(mrn_wall *w, mrn_grid *g, double mass_floor, double *vel, int with_friction,
                         const mrn_walls_share *share, double pass_weight, double hold_share) {
  double work = 0.0, *J = w->sums;
  if (w->ncol) memset(J, 0, 3 * w->ncol * sizeof *J);
  /* the weight of this field's holds in what reaches the particles: 1 for
   * the step's first V, pass_weight for XPIC's smoothed fields, none for V~
   * (whose impulse is booked as it acts) or a re-map's V */
  const double hold = with_friction ? 0.0 : vel == g->vel ? (w->v_done ? 0.0 : 1.0) : pass_weight;
  if (w->spec.kind != MRN_WALL_FIXED)
    work = contact_columns(w, g, mass_floor, vel, with_friction, J, share, hold, hold_share);
  else
    for (size_t c = 0; c < w->ncol; c++)
      for (size_t k = w->col_start[c]; k < w->col_start[c + 1]; k++)
        wall_fix(g, mass_floor, vel + 3 * w->col_node[k], w->col_node[k], w->col_w + 3 * c, J + 3 * c);
  /* the reaction: the impulses of V~, of the step's first V and of XPIC's
   * smoothed fields, each of these with its weight in V* (xpic.h), acting
   * at the column's first node */
  for (size_t c = 0; c < w->ncol; c++) {
    if (with_friction) book(w, g, c, J + 3 * c, w->impulse, w->angular, &w->step_work);
    else if (hold != 0.0) {
      for (int d = 0; d < 3; d++) J[3 * c + d] *= hold;
      book(w, g, c, J + 3 * c, w->hold_impulse, w->hold_angular, &w->hold_work);
    }
  }
  if (with_friction) w->step_friction += work, w->v_done = 1;
  return work;
}

double mrn_walls_apply(mrn_walls *ws, mrn_grid *g, double mass_floor, double *vel, int with_friction,
                       double hold_share, double pass_weight) {
  double work = 0.0;
  for (int i = 0; ws && i < ws->count; i++)
    work += wall_apply(&ws->wall[i], g, mass_floor, vel, with_friction, ws->share, pass_weight, hold_share);
  return work;
}

/* R <- exp([omega dt]x) R (Rodrigues' formula) */
static void rotate(double R[9], const double omega[3], double dt) {
  const double th = sqrt(dot3(omega, omega)) * dt;
  if (!(th > 0.0)) return;
  double k[3], Q[9], out[9];
  for (int d = 0; d < 3; d++) k[d] = omega[d] * dt / th;
  const double c = cos(th), s = sin(th), t = 1.0 - c;
  Q[0] = c + t * k[0] * k[0], Q[1] = t * k[0] * k[1] - s * k[2], Q[2] = t * k[0] * k[2] + s * k[1];
  Q[3] = t * k[1] * k[0] + s * k[2], Q[4] = c + t * k[1] * k[1], Q[5] = t * k[1] * k[2] - s * k[0];
  Q[6] = t * k[2] * k[0] - s * k[1], Q[7] = t * k[2] * k[1] + s * k[0], Q[8] = c + t * k[2] * k[2];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) out[3 * i + j] = Q[3 * i] * R[j] + Q[3 * i + 1] * R[3 + j] + Q[3 * i + 2] * R[6 + j];
  memcpy(R, out, sizeof out);
}

/* the step's impulses and works, booked by each process on its rows,
 * summed over the processes (one exchange for all the walls) */
enum { STEP_SUMS = 15 };
static void step_pack(mrn_wall *w, double *v, int back) {
  double *f[] = {w->impulse, w->angular, w->hold_impulse, w->hold_angular};
  for (int a = 0; a < 4; a++)
    for (int d = 0; d < 3; d++) {
      if (back) f[a][d] = v[3 * a + d];
      else v[3 * a + d] = f[a][d];
    }
  double *one[] = {&w->hold_work, &w->step_work, &w->step_friction};
  for (int k = 0; k < 3; k++) {
    if (back) *one[k] = v[12 + k];
    else v[12 + k] = *one[k];
  }
}

static int step_sums(mrn_walls *ws) {
  if (!ws->share || !ws->count) return MRN_OK;
  double *v = malloc((size_t)ws->count * STEP_SUMS * sizeof *v);
  const int rc = ws->share->agree(ws->share->ctx, v ? MRN_OK : mrn_error("out of memory for the walls' reactions"));
  if (rc == MRN_OK) {
    for (int i = 0; i < ws->count; i++) step_pack(&ws->wall[i], v + STEP_SUMS * i, 0);
    ws->share->reduce(ws->share->ctx, v, (size_t)ws->count * STEP_SUMS, MRN_COMM_SUM);
    for (int i = 0; i < ws->count; i++) step_pack(&ws->wall[i], v + STEP_SUMS * i, 1);
  }
  free(v);
  return rc;
}

int mrn_walls_step_end(mrn_walls *ws, double dt, double hold_share, const double gravity[3], double *work_done) {
  double work = 0.0;
  *work_done = 0.0;
  if (!ws) return MRN_OK;
  ws->damping_work = 0.0;
  int rc = step_sums(ws);
  if (rc) return rc;
  for (int i = 0; i < ws->count; i++) {
    mrn_wall *w = &ws->wall[i];
    w->work_friction += w->step_friction;
    for (int d = 0; d < 3; d++) {
      w->impulse[d] += hold_share * w->hold_impulse[d];
      w->angular[d] += hold_share * w->hold_angular[d];
    }
    w->step_work += hold_share * w->hold_work;
    for (int d = 0; d < 3; d++) {
      w->force[d] = -w->impulse[d] / dt;
      w->moment[d] = -w->angular[d] / dt;
      w->total_impulse[d] -= w->impulse[d];
    }
    w->work += w->step_work;
    if (w->spec.body) ws->damping_work += mrn_body_advance(w, ws->dim, dt, gravity, ws->cundall);
    else work += w->step_work;
    for (int d = 0; d < 3; d++) w->ref[d] += w->spec.velocity[d] * dt;
    rotate(w->rot, w->spec.omega, dt);
    if (w->spec.body) mrn_body_respin(w, ws->dim);
  }
  *work_done = work;
  return MRN_OK;
}
