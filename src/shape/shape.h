/* moraine: shape functions.
 *
 * Every shape function is a tensor product of a 1D kernel. The 1D kernels are
 * inline so the transfer kernels can be specialised for each of them; the
 * registry below maps deck names to kinds and carries their documentation.
 *
 * For a particle at grid coordinate xi = (x - origin) / h along one axis,
 * mrn_shape_weights_1d() gives the first supporting node (domain numbering)
 * and the weights w[k] and derivatives dw[k] (per unit of xi, divide by h for
 * d/dx) of the `support` consecutive nodes base .. base + support - 1. */
#ifndef MRN_SHAPE_SHAPE_H
#define MRN_SHAPE_SHAPE_H

#include <math.h>

typedef enum { MRN_SHAPE_LINEAR = 0, MRN_SHAPE_QUADRATIC_BSPLINE, MRN_SHAPE_KIND_COUNT } mrn_shape_kind;

#define MRN_SHAPE_MAX_SUPPORT 4

typedef struct mrn_shape_info {
  mrn_shape_kind kind;
  const char *name;
  int support; /* nodes per axis */
  const char *doc;
} mrn_shape_info;

const mrn_shape_info *mrn_shape_info_of(mrn_shape_kind k);
int mrn_shape_from_name(const char *name, mrn_shape_kind *out);
/* NULL-terminated list of names */
const char *const *mrn_shape_names(void);

static inline int mrn_shape_support(mrn_shape_kind k) { return k == MRN_SHAPE_LINEAR ? 2 : 3; }

/* linear hat functions, support 2 */
static inline int mrn_shape_linear_1d(double xi, double *w, double *dw) {
  int base = (int)floor(xi);
  double t = xi - base;
  w[0] = 1.0 - t;
  w[1] = t;
  dw[0] = -1.0;
  dw[1] = 1.0;
  return base;
}

/* quadratic B-spline (002, Eq. 6 with the cell size h), support 3 */
static inline int mrn_shape_quadratic_1d(double xi, double *w, double *dw) {
  int base = (int)floor(xi - 0.5);
  double d0 = xi - base; /* in [0.5, 1.5) : distance to the first node */
  double d1 = d0 - 1.0;  /* in [-0.5, 0.5) */
  double d2 = d0 - 2.0;  /* in [-1.5, -0.5) */
  w[0] = 0.5 * (1.5 - d0) * (1.5 - d0);
  w[1] = 0.75 - d1 * d1;
  w[2] = 0.5 * (1.5 + d2) * (1.5 + d2);
  dw[0] = -(1.5 - d0);
  dw[1] = -2.0 * d1;
  dw[2] = (1.5 + d2);
  return base;
}

static inline int mrn_shape_weights_1d(mrn_shape_kind k, double xi, double *w, double *dw) {
  switch (k) {
  case MRN_SHAPE_LINEAR: return mrn_shape_linear_1d(xi, w, dw);
  default: return mrn_shape_quadratic_1d(xi, w, dw);
  }
}

#endif
