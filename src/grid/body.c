/* moraine: rigid bodies — walls moved by their forces (grid/wall.h).
 *
 * A body is a wall of finite extent with a mass and an inertia from its
 * shape and density. Its contact with the material is the wall's; at the
 * end of each step the reaction of the material, gravity and its external
 * load change its velocity and angular velocity (Newton-Euler, semi-implicit
 * Euler), with which the wall then moves. doc/numerics.md, "Rigid bodies". */
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "grid/wall.h"

static const char *const dof_names[] = {"x", "y", "z", "rx", "ry", "rz", NULL};
const char *const *mrn_body_dof_names(void) { return dof_names; }

enum { DOF_RZ = 5 };

static int is_fixed(const mrn_wall *w, int dof) { return (w->spec.fix >> dof) & 1u; }

/* ---- mass and inertia -------------------------------------------------------------- */

/* A polygon of unit density: its area, centroid, and polar moment about the
 * centroid, from the sum over its edges (Green's theorem), the vertices
 * taken from their mean to keep the round-off small */
static double polygon_inertia(const mrn_wall_spec *s, double c[3], double *izz) {
  double a = 0.0, cx = 0.0, cy = 0.0, io = 0.0;
  for (int i = 0, j = s->nvertex - 1; i < s->nvertex; j = i++) {
    const double x0 = s->vertex[2 * j] - s->point[0], y0 = s->vertex[2 * j + 1] - s->point[1];
    const double x1 = s->vertex[2 * i] - s->point[0], y1 = s->vertex[2 * i + 1] - s->point[1];
    const double cr = x0 * y1 - x1 * y0;
    a += 0.5 * cr;
    cx += (x0 + x1) * cr / 6.0, cy += (y0 + y1) * cr / 6.0;
    io += cr * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) / 12.0;
  }
  if (!(fabs(a) > 0.0)) return 0.0;
  cx /= a, cy /= a;
  c[0] = s->point[0] + cx, c[1] = s->point[1] + cy, c[2] = 0.0;
  *izz = fabs(io) - fabs(a) * (cx * cx + cy * cy); /* io has the sign of a: clockwise polygons too */
  return fabs(a);
}

/* A closed triangle mesh of unit density: its volume, centroid and inertia
 * about the centroid, summed over the tetrahedra each triangle makes with an
 * origin o (a corner of the mesh, to keep the round-off small): a tetrahedron
 * o, a, b, c adds det/6 to the volume and det A C0 A^T to the second moment
 * S = int x x^T dV, with A = [a b c] - o, det = det A and C0 the canonical
 * tetrahedron's (entries 1/60 on the diagonal, 1/120 off it). Then
 * I = tr(S_c) 1 - S_c for S_c = S - V c c^T about the centroid. The sums have
 * the orientation's sign, so a mesh wound either way gives the same body. */
static double mesh_inertia(const mrn_wall_spec *s, double c[3], double I1[9]) {
  const double *o = s->triangle;
  double v = 0.0, m1[3] = {0.0, 0.0, 0.0}, S[9] = {0.0};
  for (int t = 0; t < s->ntriangle; t++) {
    double A[9]; /* A[3 * i + k]: coordinate i of corner k, from o */
    for (int k = 0; k < 3; k++)
      for (int i = 0; i < 3; i++) A[3 * i + k] = s->triangle[9 * t + 3 * k + i] - o[i];
    const double det = A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
                       A[2] * (A[3] * A[7] - A[4] * A[6]);
    v += det / 6.0;
    for (int i = 0; i < 3; i++) m1[i] += det / 24.0 * (A[3 * i] + A[3 * i + 1] + A[3 * i + 2]);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        const double *ai = A + 3 * i, *aj = A + 3 * j;
        const double sum = (ai[0] + ai[1] + ai[2]) * (aj[0] + aj[1] + aj[2]);
        const double diag = ai[0] * aj[0] + ai[1] * aj[1] + ai[2] * aj[2];
        S[3 * i + j] += det * (sum + diag) / 120.0; /* A C0 A^T, C0 = (1 1^T + 1) / 120 */
      }
  }
  if (!(fabs(v) > 0.0)) return 0.0;
  double cc[3];
  for (int i = 0; i < 3; i++) cc[i] = m1[i] / v, c[i] = o[i] + cc[i];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) S[3 * i + j] = (S[3 * i + j] - v * cc[i] * cc[j]) * (v > 0.0 ? 1.0 : -1.0);
  const double tr = S[0] + S[4] + S[8];
  for (int k = 0; k < 9; k++) I1[k] = (k % 4 == 0 ? tr : 0.0) - S[k];
  return fabs(v);
}

/* The volume (area in 2D) of the shape, its centroid c and its inertia of
 * unit density about c (I1, row-major); 0 for a shape of no finite extent */
static double unit_inertia(const mrn_wall_spec *s, int dim, double c[3], double I1[9]) {
  const double *h = s->half;
  memset(I1, 0, 9 * sizeof *I1);
  memcpy(c, s->point, 3 * sizeof *c);
  if (s->inside) return 0.0;
  double v = 0.0;
  switch (s->shape) {
  case MRN_WALL_BOX:
    if (dim == 2) {
      v = 4.0 * h[0] * h[1];
      I1[8] = v * (h[0] * h[0] + h[1] * h[1]) / 3.0;
    } else {
      v = 8.0 * h[0] * h[1] * h[2];
      I1[0] = v * (h[1] * h[1] + h[2] * h[2]) / 3.0;
      I1[4] = v * (h[0] * h[0] + h[2] * h[2]) / 3.0;
      I1[8] = v * (h[0] * h[0] + h[1] * h[1]) / 3.0;
    }
    return v;
  case MRN_WALL_CYLINDER:
    if (dim == 3) return 0.0; /* infinite along its axis */
    v = M_PI * s->radius * s->radius;
    I1[8] = 0.5 * v * s->radius * s->radius;
    return v;
  case MRN_WALL_POLYGON: return polygon_inertia(s, c, &I1[8]);
  case MRN_WALL_MESH: return mesh_inertia(s, c, I1);
  default: return 0.0;
  }
}

/* the checks of a body's own keys */
static int check_body(const mrn_wall_spec *s, int dim) {
  const char *key = s->mass > 0.0 ? "mass" : "density";
  if (!(s->density >= 0.0) || !(s->mass >= 0.0) || !isfinite(s->density) || !isfinite(s->mass) ||
      !(s->density > 0.0 || s->mass > 0.0))
    return mrn_error("%s: a rigid body needs a finite density > 0 (kg/m^3) or mass > 0 (kg%s), got %g", key,
                     dim == 2 ? "/m" : "", s->mass != 0.0 ? s->mass : s->density);
  if (s->density > 0.0 && s->mass > 0.0) return mrn_error("mass: give a rigid body's density or its mass, not both");
  for (int k = 0; dof_names[k]; k++)
    if (dim == 2 && ((s->fix >> k) & 1u) && k != 0 && k != 1 && k != DOF_RZ)
      return mrn_error("fix: '%s' is not a degree of freedom of a 2D body (x, y, rz)", dof_names[k]);
  if (s->fix >> 6) return mrn_error("fix: unknown degree of freedom");
  for (int d = 0; d < 3; d++)
    if (!isfinite(s->load[d]) || !isfinite(s->load_moment[d]))
      return mrn_error("external_force, external_moment: expected finite numbers");
  if (dim == 2 && (s->load[2] != 0.0 || s->load_moment[0] != 0.0 || s->load_moment[1] != 0.0))
    return mrn_error("external_moment: a 2D body turns about z only (give one number)");
  return MRN_OK;
}

int mrn_body_setup(mrn_wall *w, int dim) {
  mrn_wall_spec *s = &w->spec;
  int rc = check_body(s, dim);
  if (rc) return rc;
  double c[3], I1[9];
  const double v = unit_inertia(s, dim, c, I1);
  if (!(v > 0.0))
    return mrn_error("%s: wall '%s' is unbounded (infinite mass): a rigid body is a box, a disk (a 2D cylinder), "
                     "a polygon or a mesh, with the material outside it",
                     s->mass > 0.0 ? "mass" : "density", s->name);
  w->mass = s->mass > 0.0 ? s->mass : s->density * v;
  for (int k = 0; k < 9; k++) w->inertia[k] = w->mass / v * I1[k];
  memcpy(s->center, c, sizeof s->center); /* a body turns about its centre of mass */
  return MRN_OK;
}

/* ---- motion ------------------------------------------------------------------------ */

void mrn_body_inertia(const mrn_wall *w, double I[9]) {
  const double *R = w->rot, *J = w->inertia;
  double RJ[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) RJ[3 * i + j] = R[3 * i] * J[j] + R[3 * i + 1] * J[3 + j] + R[3 * i + 2] * J[6 + j];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) I[3 * i + j] = RJ[3 * i] * R[3 * j] + RJ[3 * i + 1] * R[3 * j + 1] + RJ[3 * i + 2] * R[3 * j + 2];
}

static void mat_vec(const double A[9], const double x[3], double y[3]) {
  for (int i = 0; i < 3; i++) y[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2];
}

double mrn_body_kinetic(const mrn_wall *w, int dim) {
  const double *v = w->spec.velocity, *o = w->spec.omega;
  double e = 0.5 * w->mass * (v[0] * v[0] + v[1] * v[1] + (dim == 3 ? v[2] * v[2] : 0.0));
  if (dim == 2) return e + 0.5 * w->inertia[8] * o[2] * o[2];
  double I[9], Io[3];
  mrn_body_inertia(w, I);
  mat_vec(I, o, Io);
  return e + 0.5 * (o[0] * Io[0] + o[1] * Io[1] + o[2] * Io[2]);
}

/* solve A x = b (3 x 3) by Cramer's rule (A an inertia, some rows unit
 * rows: never singular) */
static void solve3(const double A[9], const double b[3], double x[3]) {
  const double det = A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
                     A[2] * (A[3] * A[7] - A[4] * A[6]);
  for (int k = 0; k < 3; k++) {
    double M[9];
    memcpy(M, A, sizeof M);
    for (int i = 0; i < 3; i++) M[3 * i + k] = b[i];
    x[k] = (M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) +
            M[2] * (M[3] * M[7] - M[4] * M[6])) / det;
  }
}

/* The angular velocity whose angular momentum in the current placement is
 * L: I omega = L on the free axes, the fixed ones kept (their rows of I
 * made unit rows, so the free axes still see a non-diagonal I) */
static void spin_from(const mrn_wall *w, const double L[3], double omega[3]) {
  double I[9], b[3];
  mrn_body_inertia(w, I);
  memcpy(b, L, sizeof b);
  for (int a = 0; a < 3; a++)
    if (is_fixed(w, 3 + a)) {
      for (int j = 0; j < 3; j++) I[3 * a + j] = a == j;
      b[a] = w->spec.omega[a];
    }
  solve3(I, b, omega);
}

/* The angular velocity after a step of dt under the moment M. 3D: the
 * angular momentum I omega gains M dt, and the new omega follows from it
 * (mrn_body_respin again once the body has turned), which keeps the
 * gyroscopic coupling and conserves L without a moment */
static void spin_step(mrn_wall *w, int dim, double dt, const double M[3], double on[3]) {
  memcpy(on, w->spec.omega, 3 * sizeof *on);
  if (dim == 2) {
    if (!is_fixed(w, DOF_RZ)) on[2] += dt * M[2] / w->inertia[8];
    return;
  }
  double I[9];
  mrn_body_inertia(w, I);
  mat_vec(I, w->spec.omega, w->spin);
  for (int a = 0; a < 3; a++) w->spin[a] += dt * M[a];
  spin_from(w, w->spin, on);
}

void mrn_body_respin(mrn_wall *w, int dim) {
  if (dim == 3) spin_from(w, w->spin, w->spec.omega);
}

/* The work of gravity and the load over the step, at the mean of the old
 * and new velocities (which makes a free body's kinetic energy balance
 * exact); along a fixed degree of freedom the fixing cancels all the other
 * forces, so gravity, load and fixing together do minus the reaction's work */
static double body_work(const mrn_wall *w, int dim, double dt, const double F[3], const double vn[3],
                        const double on[3]) {
  const double *v = w->spec.velocity, *o = w->spec.omega;
  double work = 0.0;
  for (int d = 0; d < dim; d++)
    work += is_fixed(w, d) ? -w->force[d] * v[d] * dt : F[d] * 0.5 * (v[d] + vn[d]) * dt;
  for (int a = dim == 2 ? 2 : 0; a < 3; a++)
    work += is_fixed(w, 3 + a) ? -w->moment[a] * o[a] * dt : w->spec.load_moment[a] * 0.5 * (o[a] + on[a]) * dt;
  return work;
}

/* Cundall's local damping of a body's net force f moving at v, as a node's
 * (000, Eqs. 61-62) */
static double cundall(double D, double f, double v) {
  return D > 0.0 && v != 0.0 ? -D * fabs(f) * (v > 0.0 ? 1.0 : -1.0) : 0.0;
}

double mrn_body_advance(mrn_wall *w, int dim, double dt, const double gravity[3], double D) {
  const double *v = w->spec.velocity, *o = w->spec.omega;
  double F[3], fd[3], vn[3], on[3], M[3], md[3];
  for (int d = 0; d < 3; d++) {
    F[d] = w->mass * gravity[d] + w->spec.load[d]; /* all but the reaction */
    fd[d] = cundall(D, F[d] + w->force[d], v[d]);
    M[d] = w->moment[d] + w->spec.load_moment[d];
    md[d] = cundall(D, M[d], o[d]);
    M[d] += md[d];
  }
  for (int d = 0; d < 3; d++)
    vn[d] = d < dim && !is_fixed(w, d) ? v[d] + dt * (F[d] + fd[d] + w->force[d]) / w->mass : v[d];
  spin_step(w, dim, dt, M, on);
  w->body_work += body_work(w, dim, dt, F, vn, on);
  double damping = 0.0; /* as the nodes': f_damp . (v + v_new) / 2 dt */
  for (int d = 0; d < 3; d++) {
    if (d < dim && !is_fixed(w, d)) damping += fd[d] * 0.5 * (v[d] + vn[d]) * dt;
    if ((dim == 3 || d == 2) && !is_fixed(w, 3 + d)) damping += md[d] * 0.5 * (o[d] + on[d]) * dt;
  }
  memcpy(w->spec.velocity, vn, sizeof vn);
  memcpy(w->spec.omega, on, sizeof on);
  return damping;
}

void mrn_walls_body_energy(const mrn_walls *ws, double *kinetic, double *work) {
  *kinetic = *work = 0.0;
  for (int i = 0; ws && i < ws->count; i++) {
    if (!ws->wall[i].spec.body) continue;
    *kinetic += mrn_body_kinetic(&ws->wall[i], ws->dim);
    *work += ws->wall[i].body_work;
  }
}

int mrn_walls_have_bodies(const mrn_walls *ws) {
  for (int i = 0; ws && i < ws->count; i++)
    if (ws->wall[i].spec.body) return 1;
  return 0;
}

int mrn_walls_body_holds(const mrn_walls *ws, size_t node) {
  for (int i = 0; i < ws->count; i++)
    if (ws->wall[i].spec.body && (ws->wall[i].state[node] & MRN_WALL_TOUCH)) return 1;
  return 0;
}
