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

typedef enum {
  MRN_SHAPE_LINEAR = 0,
  MRN_SHAPE_GIMP,
  MRN_SHAPE_QUADRATIC_BSPLINE,
  MRN_SHAPE_CUBIC_BSPLINE,
  MRN_SHAPE_CPDI, /* CPDI: linear hat functions averaged over the particle's domain (transfer/cpdi.h) */
  MRN_SHAPE_CPDI2, /* CPDI2 (2D): as CPDI over a quadrilateral with tracked corners (transfer/cpdi2.h) */
  MRN_SHAPE_CPGIMP, /* cpGIMP: uGIMP with the particle's box sized from its tracked domain (transfer/cpgimp.h) */
  MRN_SHAPE_KIND_COUNT
} mrn_shape_kind;

/* How kernels meet the faces of the grid:
 *   EXTENDED   ghost nodes beyond each face keep the full kernel (face
 *              conditions act on the ghost nodes too);
 *   TRUNCATED  nodes outside the domain are dropped; the partition of unity
 *              fails next to the faces (for comparison and tests);
 *   MODIFIED   boundary-modified B-splines: each exterior node's function is
 *              folded onto the two nearest interior nodes by linear
 *              extrapolation (u_-1 = 2 u_0 - u_1), which restores the partition
 *              of unity and linear reproduction with nodes in the domain only
 *              (the purpose of 000 §2.3);
 *   WLS        truncated kernels corrected by weighted least squares
 *              (002, Eqs. 53-63), only for particles whose support crosses a
 *              face (002, Eqs. 61 and 63). */
typedef enum {
  MRN_KERNEL_EXTENDED = 0,
  MRN_KERNEL_TRUNCATED,
  MRN_KERNEL_MODIFIED,
  MRN_KERNEL_WLS,
  MRN_KERNEL_BOUNDARY_COUNT
} mrn_kernel_boundary;

/* everything the transfer kernels need to know about the kernel */
typedef struct mrn_kernel_options {
  mrn_shape_kind shape;
  mrn_kernel_boundary boundary;
  int mls_gradient; /* 1: grad N_i = (C2 + C3 (x_i - x_p)) N_i everywhere (002, Eq. 62) */
  unsigned periodic; /* bit d set: axis d is periodic, kernels wrap around */
} mrn_kernel_options;

const char *const *mrn_kernel_boundary_names(void);
int mrn_kernel_boundary_from_name(const char *name, mrn_kernel_boundary *out);

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

/* CPDI or CPDI2: the domain-averaged kernels, all run by transfer/cpdi.c */
static inline int mrn_shape_is_cpdi(mrn_shape_kind k) { return k == MRN_SHAPE_CPDI || k == MRN_SHAPE_CPDI2; }

/* whether shape k works in dimension dim: CPDI2's quadrilaterals are 2D only */
static inline int mrn_shape_takes_dim(mrn_shape_kind k, int dim) { return k != MRN_SHAPE_CPDI2 || dim == 2; }

/* nodes per axis around a point; CPDI's grid basis is the linear one,
 * cpGIMP's at a point is uGIMP's, and their particles reach further, as far
 * as their domains (transfer/cpdi.h, transfer/cpgimp.h) */
static inline int mrn_shape_support(mrn_shape_kind k) {
  return k == MRN_SHAPE_LINEAR || mrn_shape_is_cpdi(k) ? 2 : k == MRN_SHAPE_CUBIC_BSPLINE ? 4 : 3;
}

/* whether the shape follows each particle's domain A = F U0
 * (particles/domain.h): its support grows with the domain, so its kernels
 * run through the reference stencil with the domains the step froze
 * (transfer/cpdi.h) */
static inline int mrn_shape_tracks_domain(mrn_shape_kind k) {
  return mrn_shape_is_cpdi(k) || k == MRN_SHAPE_CPGIMP;
}

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

/* quadratic B-spline (002 §4, the kernel of Eq. 52), support 3: the weights
 * W0..W2 and their derivatives DW0..DW2 (per cell) at the three nodes from
 * base, given D0 = xi - base in [0.5, 1.5), the distance to the first node.
 * A macro so that the same operations serve a double and a GCC vector of
 * doubles (the 2D fast stencil forms both axes at once, transfer/stencil.h),
 * with the same bits. */
#define MRN_QUADRATIC_BSPLINE(D0, W0, W1, W2, DW0, DW1, DW2)     \
  do {                                                           \
    const __typeof__(D0) d1_ = (D0) - 1.0; /* in [-0.5, 0.5) */  \
    const __typeof__(D0) d2_ = (D0) - 2.0; /* in [-1.5, -0.5) */ \
    (W0) = 0.5 * (1.5 - (D0)) * (1.5 - (D0));                    \
    (W1) = 0.75 - d1_ * d1_;                                     \
    (W2) = 0.5 * (1.5 + d2_) * (1.5 + d2_);                      \
    (DW0) = -(1.5 - (D0));                                       \
    (DW1) = -2.0 * d1_;                                          \
    (DW2) = (1.5 + d2_);                                         \
  } while (0)

static inline int mrn_shape_quadratic_1d(double xi, double *w, double *dw) {
  int base = (int)floor(xi - 0.5);
  double d0 = xi - base; /* in [0.5, 1.5) : distance to the first node */
  MRN_QUADRATIC_BSPLINE(d0, w[0], w[1], w[2], dw[0], dw[1], dw[2]);
  return base;
}

/* cubic B-spline, support 4: N(r) = r^3/2 - r^2 + 2/3 for |r| < 1,
 * (2 - |r|)^3 / 6 for 1 <= |r| < 2 (r in cells) */
static inline int mrn_shape_cubic_1d(double xi, double *w, double *dw) {
  int base = (int)floor(xi) - 1;
  for (int k = 0; k < 4; k++) {
    double r = xi - (base + k);
    double a = fabs(r), sgn = r < 0 ? -1.0 : 1.0;
    if (a < 1.0) {
      w[k] = 0.5 * a * a * a - a * a + 2.0 / 3.0;
      dw[k] = sgn * (1.5 * a * a - 2.0 * a);
    } else if (a < 2.0) {
      double t = 2.0 - a;
      w[k] = t * t * t / 6.0;
      dw[k] = -sgn * 0.5 * t * t;
    } else {
      w[k] = dw[k] = 0.0;
    }
  }
  return base;
}

/* uGIMP (Bardenhagen & Kober): the hat function convolved with a particle of
 * half-width lp (in cells, fixed at its initial size), support 3 for lp <= 1/2:
 * 1 - (r^2 + lp^2) / (2 lp) for |r| < lp, 1 - |r| up to 1 - lp, then
 * (1 + lp - |r|)^2 / (4 lp) up to 1 + lp. dw is d/dxi of the weight,
 * r = xi - node. The plain form, branch by branch: the reference the
 * factored form below is tested against (tests/unit/test_kernels.c). */
static inline int mrn_shape_gimp_1d_piecewise(double xi, double lp, double *w, double *dw) {
  int base = (int)floor(xi - lp);
  for (int k = 0; k < 3; k++) {
    double r = xi - (base + k);
    double a = fabs(r), sgn = r < 0 ? -1.0 : 1.0;
    if (a < lp) {
      w[k] = 1.0 - (r * r + lp * lp) / (2.0 * lp);
      dw[k] = -r / lp;
    } else if (a < 1.0 - lp) {
      w[k] = 1.0 - a;
      dw[k] = -sgn;
    } else if (a < 1.0 + lp) {
      double t = 1.0 + lp - a;
      w[k] = t * t / (4.0 * lp);
      dw[k] = -sgn * t / (2.0 * lp);
    } else {
      w[k] = dw[k] = 0.0;
    }
  }
  return base;
}

/* uGIMP in factored form. With base = floor(xi - lp), the particle's box
 * [xi - lp, xi + lp] starts in the cell [base, base + 1]; C = base + 1 -
 * (xi - lp) is how much of the box that cell holds (in (0, 1]). Either the
 * box stays in the cell (C >= 2 lp) and the weights are the hat function's,
 * or it reaches past node base + 1 by t = 2 lp - C, and the piecewise form
 * above reduces to
 *   w0 = C^2 / (4 lp), w2 = t^2 / (4 lp), w1 = 1 - w0 - w2,
 *   dw0 = -C / (2 lp), dw2 = t / (2 lp), dw1 = -(dw0 + dw2);
 * with m = min(C, 2 lp) one set of formulas serves both cases
 * (w0 = m^2 / (4 lp) + (C - m), t = 2 lp - m), with no branch per node and
 * no cancellation in a small weight. K = 1 / lp. A macro so that the same
 * operations serve a double and a GCC vector of doubles (the 2D fast
 * stencil forms both axes at once), with the same bits; MIN is the minimum
 * for the type. */
#define MRN_GIMP_FACTORED(MIN, C, LP, K, W0, W1, W2, DW0, DW1, DW2)                         \
  do {                                                                                      \
    const __typeof__(C) m_ = MIN((C), 2.0 * (LP));                                          \
    const __typeof__(C) t_ = 2.0 * (LP)-m_; /* the box past node base + 1, or 0 */         \
    (W0) = 0.25 * (K) * m_ * m_ + ((C)-m_);                                                 \
    (W2) = 0.25 * (K) * t_ * t_;                                                            \
    (W1) = 1.0 - (W0) - (W2);                                                               \
    (DW0) = -0.5 * (K) * m_;                                                                \
    (DW2) = 0.5 * (K) * t_;                                                                 \
    (DW1) = -((DW0) + (DW2));                                                               \
  } while (0)
#define MRN_MIN_SCALAR(a, b) ((a) < (b) ? (a) : (b))

/* uGIMP's weights as every stencil forms them (MRN_GIMP_FACTORED), given
 * inv_lp = 1 / lp */
static inline int mrn_shape_gimp_1d_k(double xi, double lp, double inv_lp, double *w, double *dw) {
  const double h = xi - lp, b = floor(h);
  const double c = (b + 1.0) - h;
  MRN_GIMP_FACTORED(MRN_MIN_SCALAR, c, lp, inv_lp, w[0], w[1], w[2], dw[0], dw[1], dw[2]);
  return (int)b;
}

static inline int mrn_shape_gimp_1d(double xi, double lp, double *w, double *dw) {
  return mrn_shape_gimp_1d_k(xi, lp, 1.0 / lp, w, dw);
}

/* lp: particle half-width in cells (uGIMP, and cpGIMP at a point) */
static inline int mrn_shape_weights_1d(mrn_shape_kind k, double xi, double lp, double *w, double *dw) {
  switch (k) {
  case MRN_SHAPE_LINEAR:
  case MRN_SHAPE_CPDI:
  case MRN_SHAPE_CPDI2: return mrn_shape_linear_1d(xi, w, dw);
  case MRN_SHAPE_GIMP:
  case MRN_SHAPE_CPGIMP: return mrn_shape_gimp_1d(xi, lp, w, dw);
  case MRN_SHAPE_CUBIC_BSPLINE: return mrn_shape_cubic_1d(xi, w, dw);
  default: return mrn_shape_quadratic_1d(xi, w, dw);
  }
}

#endif
