#include "grid/boundary.h"

#include <math.h>
#include <string.h>

#include "core/error.h"

static const char *const kind_names[] = {"free", "fixed", "slip", "friction", "velocity", "periodic", NULL};

const char *mrn_bc_kind_name(mrn_bc_kind k) { return k < MRN_BC_KIND_COUNT ? kind_names[k] : "?"; }
const char *const *mrn_bc_kind_names(void) { return kind_names; }

int mrn_bc_kind_from_name(const char *name, mrn_bc_kind *out) {
  for (int i = 0; kind_names[i]; i++)
    if (strcmp(kind_names[i], name) == 0) {
      *out = (mrn_bc_kind)i;
      return 1;
    }
  return 0;
}

const char *mrn_face_name(int face) {
  static const char *names[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  return face >= 0 && face < MRN_FACE_COUNT ? names[face] : "?";
}

/* Apply one face condition to the node velocity v (3 components).
 * `axis` is the face normal axis, `outward` is -1 for a min face, +1 for max. */
static double apply_face(const mrn_face_bc *f, double *v, double mass, int axis, double outward,
                         int with_friction) {
  switch (f->kind) {
  case MRN_BC_FREE:
  case MRN_BC_PERIODIC:
    return 0.0;
  case MRN_BC_VELOCITY:
    v[0] = f->velocity[0];
    v[1] = f->velocity[1];
    v[2] = f->velocity[2];
    return 0.0;
  case MRN_BC_FIXED:
    v[0] = v[1] = v[2] = 0.0;
    return 0.0;
  case MRN_BC_SLIP:
    v[axis] = 0.0;
    return 0.0;
  case MRN_BC_FRICTION: {
    double vn = v[axis] * outward; /* > 0: moving into the face */
    v[axis] = 0.0;
    if (!with_friction || vn <= 0.0 || f->mu <= 0.0) return 0.0;
    double vt2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (vt2 <= 0.0) return 0.0;
    double vt = sqrt(vt2);
    double reduced = vt - f->mu * vn;
    double scale = reduced > 0.0 ? reduced / vt : 0.0;
    double work = 0.0;
    for (int d = 0; d < 3; d++) {
      double before = v[d];
      v[d] *= scale;
      /* (000, Eq. 66): dW = F . V dt with F dt = m (V_after - V_before) */
      work += mass * (v[d] - before) * v[d];
    }
    return work;
  }
  default:
    return 0.0;
  }
}

double mrn_boundary_apply(const mrn_boundary *bc, const mrn_grid *g, double *vel, int with_friction) {
  double work = 0.0;
  for (int axis = 0; axis < g->dim; axis++) {
    for (int side = 0; side < 2; side++) {
      const mrn_face_bc *f = &bc->face[2 * axis + side];
      if (f->kind == MRN_BC_FREE || f->kind == MRN_BC_PERIODIC) continue;
      /* node layers on and beyond the face, in domain numbering */
      int first = side == 0 ? -g->pad : g->ncell[axis];
      int last = side == 0 ? 0 : g->ncell[axis] + g->pad;
      double outward = side == 0 ? -1.0 : 1.0;
      int lo[3], hi[3];
      for (int d = 0; d < 3; d++) {
        if (d >= g->dim) { lo[d] = hi[d] = 0; continue; }
        lo[d] = -g->pad;
        hi[d] = g->ncell[d] + g->pad;
      }
      lo[axis] = first;
      hi[axis] = last;
      for (int k = lo[2]; k <= hi[2]; k++)
        for (int j = lo[1]; j <= hi[1]; j++)
          for (int i = lo[0]; i <= hi[0]; i++) {
            size_t n = mrn_grid_index(g, i, j, k);
            if (g->mass[n] <= 0.0) continue;
            work += apply_face(f, vel + 3 * n, g->mass[n], axis, outward, with_friction);
          }
    }
  }
  return work;
}

int mrn_boundary_validate(const mrn_boundary *bc, int dim) {
  for (int axis = 0; axis < dim; axis++) {
    int lo = bc->face[2 * axis].kind == MRN_BC_PERIODIC, hi = bc->face[2 * axis + 1].kind == MRN_BC_PERIODIC;
    if (lo != hi)
      return mrn_error("face %s is periodic but %s is not: both faces of an axis must be periodic",
                       mrn_face_name(lo ? 2 * axis : 2 * axis + 1), mrn_face_name(lo ? 2 * axis + 1 : 2 * axis));
  }
  return MRN_OK;
}
