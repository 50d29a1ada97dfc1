/* moraine: the nodes a particle talks to, with weights and gradients.
 *
 * Included by the dimension-specialised kernel files with DIM defined to 2
 * or 3, so every loop bound below is a compile-time constant. The kernel is
 * the tensor product of 1D functions (002, Eq. 52), adjusted at the faces of
 * the grid as mrn_kernel_boundary says, and optionally with the MLS gradient
 * (002 Remark 4; Hu et al. 2018) in place of the kernel's own gradient. */
#ifndef DIM
#error "stencil.h needs DIM"
#endif

#include <stdint.h>
#include <string.h>

#include "grid/grid.h"
#include "shape/shape.h"
#include "transfer/wls.h"

#undef STENCIL_MAX
#define STENCIL_MAX (MRN_SHAPE_MAX_SUPPORT * MRN_SHAPE_MAX_SUPPORT * (DIM == 3 ? MRN_SHAPE_MAX_SUPPORT : 1))

typedef struct KNAME(stencil) {
  int count;
  size_t node[STENCIL_MAX];
  double N[STENCIL_MAX];
  double dN[STENCIL_MAX][DIM];     /* d N / d x (1/m) */
  double offset[STENCIL_MAX][DIM]; /* x_i - x_p, the branch vector (000, Eq. 21) */
} KNAME(stencil);


/* Fold the weight of exterior node `ext` (domain index) onto the face node
 * and its neighbour by linear extrapolation: u_ext = (1 + k) u_face - k u_next
 * with k the distance in cells from the face. */
static inline void KNAME(fold_exterior)(int base, int sup, int ext, int face, int next, double *w, double *dw) {
  int ke = ext - base, kf = face - base, kn = next - base;
  if (kf < 0 || kf >= sup || kn < 0 || kn >= sup) return;
  double k = fabs((double)(ext - face));
  w[kf] += (1 + k) * w[ke];
  dw[kf] += (1 + k) * dw[ke];
  w[kn] -= k * w[ke];
  dw[kn] -= k * dw[ke];
  w[ke] = dw[ke] = 0.0;
}

/* Apply the face treatment along one axis; returns 1 when the support
 * crossed a face (so the WLS correction is needed). */
static inline int KNAME(axis_boundary)(mrn_kernel_boundary mode, int base, int sup, int ncell, double *w,
                                       double *dw) {
  int crossed = 0;
  for (int k = 0; k < sup; k++) {
    int node = base + k;
    if (node >= 0 && node <= ncell) continue;
    if (w[k] != 0.0 || dw[k] != 0.0) crossed = 1;
    if (mode == MRN_KERNEL_MODIFIED) {
      if (node < 0) KNAME(fold_exterior)(base, sup, node, 0, 1, w, dw);
      else KNAME(fold_exterior)(base, sup, node, ncell, ncell - 1, w, dw);
    } else {
      w[k] = dw[k] = 0.0;
    }
  }
  return crossed;
}

/* fill the stencil of a particle at x (inside the domain); vol0 is its
 * initial volume (uGIMP uses it for the particle size) */
static inline void KNAME(stencil_build)(const mrn_grid *g, const mrn_kernel_options *opt, const double *x,
                                        double vol0, KNAME(stencil) *s) {
  double w[DIM][MRN_SHAPE_MAX_SUPPORT], dw[DIM][MRN_SHAPE_MAX_SUPPORT];
  int base[DIM], node[DIM][MRN_SHAPE_MAX_SUPPORT];
  const int sup = mrn_shape_support(opt->shape);
  double lp = 0.0;
  if (opt->shape == MRN_SHAPE_GIMP || opt->shape == MRN_SHAPE_CPGIMP) { /* cpGIMP at a point: F = I */
    /* half the particle's initial side, in cells; at most half a cell so the
     * support stays within 3 nodes (one particle per cell) */
    lp = 0.5 * (DIM == 2 ? sqrt(vol0) : cbrt(vol0)) * g->inv_cell;
    if (lp > 0.5) lp = 0.5;
  }
  int crossed = 0;
  for (int d = 0; d < DIM; d++) {
    double xi = (x[d] - g->origin[d]) * g->inv_cell;
    base[d] = mrn_shape_weights_1d(opt->shape, xi, lp, w[d], dw[d]);
    if (sup == 2 && base[d] == g->ncell[d]) { /* linear, or CPDI's grid basis at a point */
      /* a particle exactly on the upper face belongs to the last cell, not to
       * one beyond the domain (same values, gradient from inside) */
      base[d] = g->ncell[d] - 1;
      w[d][0] = 0.0, w[d][1] = 1.0;
      dw[d][0] = -1.0, dw[d][1] = 1.0;
    }
    if (opt->periodic & (1u << d)) {
      /* node numbers wrap around; offsets keep the unwrapped positions */
      for (int k = 0; k < sup; k++) node[d][k] = ((base[d] + k) % g->ncell[d] + g->ncell[d]) % g->ncell[d];
    } else {
      if (opt->boundary != MRN_KERNEL_EXTENDED)
        crossed |= KNAME(axis_boundary)(opt->boundary, base[d], sup, g->ncell[d], w[d], dw[d]);
      for (int k = 0; k < sup; k++) node[d][k] = base[d] + k;
    }
  }
  int c = 0;
#if DIM == 3
  for (int k = 0; k < sup; k++)
#endif
    for (int j = 0; j < sup; j++)
      for (int i = 0; i < sup; i++) {
#if DIM == 3
        const int idx[3] = {i, j, k};
#else
        const int idx[2] = {i, j};
#endif
        double N = 1.0;
        for (int d = 0; d < DIM; d++) N *= w[d][idx[d]];
        for (int d = 0; d < DIM; d++) {
          double g_d = dw[d][idx[d]] * g->inv_cell;
          for (int e = 0; e < DIM; e++)
            if (e != d) g_d *= w[e][idx[e]];
          s->dN[c][d] = g_d;
          s->offset[c][d] = g->origin[d] + (base[d] + idx[d]) * g->cell - x[d];
        }
        s->N[c] = N;
#if DIM == 3
        s->node[c] = mrn_grid_index(g, node[0][i], node[1][j], node[2][k]);
#else
        s->node[c] = mrn_grid_index(g, node[0][i], node[1][j], 0);
#endif
        c++;
      }
  s->count = c;
  int correct_values = opt->boundary == MRN_KERNEL_WLS && crossed;
  if (correct_values || opt->mls_gradient)
    mrn_wls_correct(DIM, c, s->N, &s->dN[0][0], &s->offset[0][0], correct_values, 1);
}

/* ---- plain B-splines one axis at a time (the fast path of the kernels) ---- */
#ifndef MRN_STENCIL_BSPLINE_AXIS
#define MRN_STENCIL_BSPLINE_AXIS
/* 4 doubles at any 8-byte aligned address (GCC vector extension; without
 * AVX it becomes two 2-wide halves) */
typedef double mrn_axis_v4 __attribute__((vector_size(32), aligned(8), may_alias));

/* Cubic B-spline along one axis for the 4 nodes from floor(xi) - 1, as
 * 4-wide vectors: with f = xi - floor(xi) and g = 1 - f the node distances
 * are 1 + f, f, g, 1 + g, and (the branches of mrn_shape_cubic_1d, in
 * factored form; the two agree to round-off)
 *   w  = (g^3/6, f^3/2 - f^2 + 2/3, g^3/2 - g^2 + 2/3, f^3/6)
 *      = t^2 (a t + b) + c,      t = (g, f, g, f),
 *   dw/dxi = (-g^2/2, 3f^2/2 - 2f, -(3g^2/2 - 2g), f^2/2) = t (d t + e).
 * Stores the weights, dw/dx = dw/dxi / cell and the branch components
 * origin + (base + k) cell - x; returns base. Not inlined: compiled once,
 * so every kernel gets the same bits (inlined, the compiler fused the
 * products into multiply-adds differently from one kernel to another). */
static __attribute__((noinline, unused)) int mrn_bspline_cubic_axis(double xi, double inv_cell, double origin,
                                                                     double cell, double x, double *w, double *dw,
                                                                     double *off) {
  const double fl = floor(xi);
  const double f = xi - fl, g = 1.0 - f; /* f is exact for xi >= 0 */
  const mrn_axis_v4 t = {g, f, g, f}, t2 = t * t;
  const mrn_axis_v4 a = {1.0 / 6.0, 0.5, 0.5, 1.0 / 6.0}, b = {0.0, -1.0, -1.0, 0.0};
  const mrn_axis_v4 c = {0.0, 2.0 / 3.0, 2.0 / 3.0, 0.0};
  const mrn_axis_v4 d = {-0.5, 1.5, -1.5, 0.5}, e = {0.0, -2.0, 2.0, 0.0};
  const mrn_axis_v4 k = {-1.0, 0.0, 1.0, 2.0};
  *(mrn_axis_v4 *)w = t2 * (a * t + b) + c;
  *(mrn_axis_v4 *)dw = t * (d * t + e) * inv_cell;
  *(mrn_axis_v4 *)off = origin + (fl + k) * cell - x; /* fl + k: (double)(base + k) exactly */
  return (int)fl - 1;
}

#endif

/* The shapes with a fast stencil, by the code the kernels are specialised
 * for: the support (nodes per axis), except uGIMP's, whose support is 3. */
#ifndef MRN_FAST_KINDS
#define MRN_FAST_KINDS
enum { MRN_FAST_LINEAR = 2, MRN_FAST_QUADRATIC = 3, MRN_FAST_CUBIC = 4, MRN_FAST_GIMP = 5 };
#define MRN_FAST_SUPPORT(kind) ((kind) == MRN_FAST_GIMP ? 3 : (kind))
#endif

/* A fast stencil (linear, quadratic B-spline, cubic B-spline, uGIMP) kept as
 * its factors: the node of the first corner and, per axis, the weights,
 * their derivatives d/dx (1/m) and the branch components x_i - x_p; in 2D
 * the lanes beyond the support hold zeros. The weights of every shape but
 * the cubic are those of stencil_build (the same functions, the same bits);
 * the cubic's are formed in factored form (mrn_bspline_cubic_axis) and
 * agree with stencil_build's to round-off. */
typedef struct KNAME(axes) {
  size_t node0;
  double w[DIM][4];
  double dw[DIM][4];
  double off[DIM][4];
} KNAME(axes);

/* uGIMP's particle half-width in cells, from its initial volume vol0, as
 * stencil_build forms it, and its reciprocal into *inv_lp. The last pair is
 * kept per thread, keyed by the bits of vol0 and of the grid's 1/cell: the
 * particles that follow one another mostly share vol0, and the root and the
 * division cost more than the rest of the axes (the engine is built with
 * TLS descriptors, -mtls-dialect=gnu2, so that a look-up is no call to
 * __tls_get_addr). */
static inline double KNAME(gimp_half_width)(const mrn_grid *g, double vol0, double *inv_lp) {
  static _Thread_local uint64_t memo_vol0 = 0, memo_inv = 0; /* 1/cell is never +0: no hit at first */
  static _Thread_local double memo_lp = 0.0, memo_inv_lp = 0.0;
  uint64_t bv, bi;
  memcpy(&bv, &vol0, sizeof bv);
  memcpy(&bi, &g->inv_cell, sizeof bi);
  if (bv == memo_vol0 && bi == memo_inv) {
    *inv_lp = memo_inv_lp;
    return memo_lp;
  }
  double lp = 0.5 * (DIM == 2 ? sqrt(vol0) : cbrt(vol0)) * g->inv_cell;
  lp = lp > 0.5 ? 0.5 : lp;
  memo_vol0 = bv, memo_inv = bi, memo_lp = lp, memo_inv_lp = *inv_lp = 1.0 / lp;
  return lp;
}

/* Returns 0 when the particle needs the general stencil: its support crosses
 * a face and the kernel is adjusted there. `sup` is a constant at every call. */
#if DIM == 2
#ifndef MRN_AXIS_V2
#define MRN_AXIS_V2
typedef double mrn_axis_v2 __attribute__((vector_size(16)));
typedef long long mrn_axis_m2 __attribute__((vector_size(16)));
#endif
/* The end of a 3-node 2D axes build (quadratic B-spline, uGIMP): the
 * derivatives per cell scaled by 1/cell, the branch components, the stores
 * with zeros in each axis's fourth lane (group_sum, kernels_impl.h, reads
 * the x factors as 4-wide vectors), and the first node; 0 when the support
 * crosses a face whose kernel is adjusted. b0 is (double)base, exactly. */
static inline __attribute__((always_inline)) int KNAME(axes_store3_2d)(
    const mrn_grid *g, const mrn_kernel_boundary mode, mrn_axis_v2 xd, mrn_axis_v2 origin, mrn_axis_v2 b0,
    const mrn_axis_v2 w[3], const mrn_axis_v2 dw[3], KNAME(axes) *a) {
  const double inv_cell = g->inv_cell, cell = g->cell;
  const int base[2] = {(int)b0[0], (int)b0[1]};
  const mrn_axis_v2 dw0 = dw[0] * inv_cell, dw1 = dw[1] * inv_cell, dw2 = dw[2] * inv_cell;
  const mrn_axis_v2 o0 = origin + b0 * cell - xd, o1 = origin + (b0 + 1.0) * cell - xd,
                    o2 = origin + (b0 + 2.0) * cell - xd;
  for (int d = 0; d < 2; d++) { /* lane by lane: fewer shuffles than building 4-wide vectors */
    a->w[d][0] = w[0][d];
    a->w[d][1] = w[1][d];
    a->w[d][2] = w[2][d];
    a->w[d][3] = 0.0;
    a->dw[d][0] = dw0[d];
    a->dw[d][1] = dw1[d];
    a->dw[d][2] = dw2[d];
    a->dw[d][3] = 0.0;
    a->off[d][0] = o0[d];
    a->off[d][1] = o1[d];
    a->off[d][2] = o2[d];
    a->off[d][3] = 0.0;
  }
  if (mode != MRN_KERNEL_EXTENDED &&
      ((base[0] < 0) | (base[1] < 0) | (base[0] + 2 > g->ncell[0]) | (base[1] + 2 > g->ncell[1])))
    return 0;
  a->node0 = (size_t)(base[0] + g->pad) * (size_t)g->stride[0] + (size_t)(base[1] + g->pad) * (size_t)g->stride[1];
  return 1;
}

/* The quadratic B-spline's axes of a 2D particle, both axes at once as the
 * lanes of 2-wide vectors: the same operations as the loop of axes_build
 * (MRN_QUADRATIC_BSPLINE, as mrn_shape_quadratic_1d per axis), so the same
 * bits; stored by axes_store3_2d. */
static inline __attribute__((always_inline)) int KNAME(axes_quadratic_2d)(const mrn_grid *g,
                                                                          const mrn_kernel_boundary mode,
                                                                          const double *x, KNAME(axes) *a) {
  const mrn_axis_v2 xd = {x[0], x[1]}, origin = {g->origin[0], g->origin[1]};
  const mrn_axis_v2 xi = (xd - origin) * g->inv_cell, h = xi - 0.5;
  const mrn_axis_v2 b0 = {floor(h[0]), floor(h[1])}; /* (double)base, exactly */
  const mrn_axis_v2 d0 = xi - b0;
  mrn_axis_v2 w[3], dw[3];
  MRN_QUADRATIC_BSPLINE(d0, w[0], w[1], w[2], dw[0], dw[1], dw[2]);
  return KNAME(axes_store3_2d)(g, mode, xd, origin, b0, w, dw, a);
}

/* The linear stencil's axes of a 2D particle, both axes at once: the
 * operations of stencil_build (mrn_shape_linear_1d, and a particle exactly
 * on the upper face in the last cell, whose weights (0, 1) the same formula
 * gives there), so the same bits. Lanes 2 and 3 hold zeros. */
static inline __attribute__((always_inline)) int KNAME(axes_linear_2d)(const mrn_grid *g,
                                                                       const mrn_kernel_boundary mode,
                                                                       const double *x, KNAME(axes) *a) {
  /* the grid's values in locals before the stores into `a`, which could
   * alias them */
  const double inv_cell = g->inv_cell, cell = g->cell;
  const mrn_axis_v2 nc = {(double)g->ncell[0], (double)g->ncell[1]};
  const size_t pad = (size_t)g->pad, st0 = (size_t)g->stride[0], st1 = (size_t)g->stride[1];
  const mrn_axis_v2 xd = {x[0], x[1]}, origin = {g->origin[0], g->origin[1]};
  const mrn_axis_v2 xi = (xd - origin) * inv_cell, one = {1.0, 1.0};
  mrn_axis_v2 b0 = {floor(xi[0]), floor(xi[1])};
  /* on the upper face: the last cell (b0 - 1 exactly where b0 == ncell) */
  b0 -= (mrn_axis_v2)((mrn_axis_m2)(b0 == nc) & (mrn_axis_m2)one);
  const mrn_axis_v2 t = xi - b0, w0 = 1.0 - t;
  const mrn_axis_v2 o0 = origin + b0 * cell - xd, o1 = origin + (b0 + 1.0) * cell - xd;
  for (int d = 0; d < 2; d++) {
    *(mrn_axis_v4 *)a->w[d] = (mrn_axis_v4){w0[d], t[d], 0.0, 0.0};
    *(mrn_axis_v4 *)a->dw[d] = (mrn_axis_v4){-inv_cell, inv_cell, 0.0, 0.0};
    *(mrn_axis_v4 *)a->off[d] = (mrn_axis_v4){o0[d], o1[d], 0.0, 0.0};
  }
  const mrn_axis_m2 out = (b0 < 0.0) | (b0 + 1.0 > nc);
  if (mode != MRN_KERNEL_EXTENDED && (out[0] | out[1])) return 0;
  a->node0 = ((size_t)(long)b0[0] + pad) * st0 + ((size_t)(long)b0[1] + pad) * st1;
  return 1;
}

/* uGIMP's axes of a 2D particle, both axes at once as the lanes of 2-wide
 * vectors: the operations of mrn_shape_gimp_1d per axis (MRN_GIMP_FACTORED),
 * so the same bits; stored by axes_store3_2d. */
#define MRN_MIN_V2(a, b) ((mrn_axis_v2)(((mrn_axis_m2)(a) & ((a) < (b))) | ((mrn_axis_m2)(b) & ~((a) < (b)))))
static inline __attribute__((always_inline)) int KNAME(axes_gimp_2d)(const mrn_grid *g, const mrn_kernel_boundary mode,
                                                                     const double *x, double vol0, KNAME(axes) *a) {
  double inv_lp;
  const double lp = KNAME(gimp_half_width)(g, vol0, &inv_lp);
  const mrn_axis_v2 lpv = {lp, lp};
  const mrn_axis_v2 xd = {x[0], x[1]}, origin = {g->origin[0], g->origin[1]};
  const mrn_axis_v2 xi = (xd - origin) * g->inv_cell, h = xi - lp;
  const mrn_axis_v2 b0 = {floor(h[0]), floor(h[1])}; /* (double)base, exactly */
  const mrn_axis_v2 c = (b0 + 1.0) - h;
  mrn_axis_v2 w[3], dw[3];
  MRN_GIMP_FACTORED(MRN_MIN_V2, c, lpv, inv_lp, w[0], w[1], w[2], dw[0], dw[1], dw[2]);
  return KNAME(axes_store3_2d)(g, mode, xd, origin, b0, w, dw, a);
}
#endif


static inline __attribute__((always_inline)) int KNAME(axes_build)(const mrn_grid *g, const int kind,
                                                                   const mrn_kernel_boundary mode, const double *x,
                                                                   double vol0, KNAME(axes) *a) {
#if DIM == 2
  if (kind == MRN_FAST_QUADRATIC) return KNAME(axes_quadratic_2d)(g, mode, x, a);
  if (kind == MRN_FAST_LINEAR) return KNAME(axes_linear_2d)(g, mode, x, a);
  if (kind == MRN_FAST_GIMP) return KNAME(axes_gimp_2d)(g, mode, x, vol0, a);
#endif
  const int sup = MRN_FAST_SUPPORT(kind);
  double inv_lp = 0.0;
  const double lp = kind == MRN_FAST_GIMP ? KNAME(gimp_half_width)(g, vol0, &inv_lp) : 0.0;
  /* the grid's values in locals: the stores into `a` could alias them, and
   * the compiler would load them again for every node */
  const double inv_cell = g->inv_cell, cell = g->cell;
  const int pad = g->pad;
  size_t node0 = 0;
  for (int d = 0; d < DIM; d++) {
    const double origin = g->origin[d], xd = x[d];
    const double xi = (xd - origin) * inv_cell;
    int base;
    if (kind == MRN_FAST_CUBIC) {
      base = mrn_bspline_cubic_axis(xi, inv_cell, origin, cell, xd, a->w[d], a->dw[d], a->off[d]);
    } else {
      double w[3], dw[3];
      if (kind == MRN_FAST_GIMP) {
        base = mrn_shape_gimp_1d_k(xi, lp, inv_lp, w, dw);
      } else if (kind == MRN_FAST_QUADRATIC) {
        base = mrn_shape_quadratic_1d(xi, w, dw);
      } else { /* linear; a particle exactly on the upper face in the last cell, as stencil_build */
        base = mrn_shape_linear_1d(xi, w, dw);
        if (base == g->ncell[d]) base--, w[0] = 0.0, w[1] = 1.0;
      }
      const double b0 = (double)base;
      for (int k = 0; k < sup; k++) {
        a->w[d][k] = w[k];
        a->dw[d][k] = dw[k] * inv_cell;
        a->off[d][k] = origin + (b0 + k) * cell - xd; /* b0 + k: (double)(base + k) exactly */
      }
    }
    if (mode != MRN_KERNEL_EXTENDED && (base < 0 || base + sup - 1 > g->ncell[d])) return 0;
    node0 += (size_t)(base + pad) * (size_t)g->stride[d];
  }
  a->node0 = node0;
  return 1;
}
