/* moraine: body of the transfer kernels; included with DIM = 2 or 3 and
 * KNAME(x) naming the specialised functions. See kernels.h.
 *
 * Each kernel exists in a general form, which builds a particle's full
 * stencil (stencil_build: any shape, face treatment, periodic axes, MLS
 * gradient), and in fast forms for linear, uGIMP and plain quadratic and
 * cubic B-spline kernels away from adjusted faces, without the MLS gradient
 * or periodic axes (MRN_FAST_*, stencil.h), which keep the stencil as its
 * per-axis factors and sum factor by factor.
 *
 * Instances: the work on one block's particles (P2G, USF's fused pass) or on
 * one particle (the velocity gradient, G2P) is an always-inline
 * function whose choices (support, scheme, what to form) are constant
 * arguments; each kernel has one X-macro list of the combinations it is
 * specialised for (MRN_P2G_VARIANTS, ...), from which follow one small
 * function per combination, which the compiler specialises (every loop
 * bound and branch in the node loops a compile-time constant), and the table
 * the kernel picks from by the options. P2G's parallel region
 * (for_own_blocks) is shared and calls the instance per block; the chunked
 * kernels (gradient, G2P) keep theirs in each instance (MRN_CHUNKED_LOOP).
 *
 * P2G runs over the particles binned by blocks of cells (transfer/blocks.h):
 * colour by colour, the blocks of one colour in parallel; in 2D the
 * particles that follow one another with stencils starting at the same node
 * are summed before they are added to the nodes (group_sum), so a node adds
 * up per-group sums. The other kernels run over the particles in index
 * order, in parallel, each particle on its own. Neither depends on the
 * number of threads for its result. */
#include <string.h>

#include "core/parallel.h"
#include "core/tensor.h"
#include "transfer/affine_fit.h"
#include "transfer/blocks.h"
#include "transfer/cpdi.h"
#include "transfer/kernels.h"
#include "transfer/profile.h"
#include "transfer/stencil.h"

#define MRN_INLINE static inline __attribute__((always_inline))

/* the initial volume axes_build reads (uGIMP's only: the other kernels do
 * not load it, so their code is what it was without uGIMP) */
#define MRN_FAST_VOL0(kind, ps, p) ((kind) == MRN_FAST_GIMP ? (ps)->vol0[p] : 0.0)

/* values stored per particle for F and the affine matrix (particles.h) */
#define TSTRIDE ((size_t)(DIM * DIM))

/* the fast stencil for these options (MRN_FAST_*, stencil.h), or 0 for
 * the general one */
static inline int KNAME(fast_kind)(const mrn_kernel_options *o) {
  if (o->periodic || o->mls_gradient) return 0;
  switch (o->shape) {
  case MRN_SHAPE_LINEAR: return MRN_FAST_LINEAR;
  case MRN_SHAPE_QUADRATIC_BSPLINE: return MRN_FAST_QUADRATIC;
  case MRN_SHAPE_CUBIC_BSPLINE: return MRN_FAST_CUBIC;
  case MRN_SHAPE_GIMP: return MRN_FAST_GIMP;
  default: return 0;
  }
}

/* ---- P2G -------------------------------------------------------------------- */

typedef struct KNAME(p2g_args) {
  mrn_grid *g;
  const mrn_particles *ps;
  mrn_kernel_options ko;
} KNAME(p2g_args);

/* Work on the particles order[from .. to) of one block: `args` says what
 * (P2G, USF's fused pass); keeps the lowest index a gradient sink rejected
 * in *first_bad and the time spent there in *spent. */
typedef void (*KNAME(range_fn))(const void *args, const uint32_t *order, size_t from, size_t to, long *first_bad,
                                double *spent);

/* `run` on each non-empty block of b, in parallel when `parallel`: each
 * thread the blocks it owns (mrn_block_owner: the thread that moves the
 * block's particles in G2P), colour by colour, all threads meeting after
 * each colour (blocks of one colour touch disjoint nodes). Returns the
 * lowest index any range rejected, or n; *spent sums the ranges' time. */
static long KNAME(for_own_blocks)(const mrn_blocks *b, int parallel, KNAME(range_fn) run, const void *args, long n,
                                  double *spent) {
  long first_bad = n;
  double sp = 0.0;
  (void)parallel; /* unused without OpenMP */
#pragma omp parallel if (parallel) reduction(min : first_bad) reduction(+ : sp)
  {
    int t, team;
    mrn_team(&t, &team);
    const size_t nchunks = mrn_particle_chunks(b->np);
    for (int c = 0; c < b->colours; c++) {
      for (size_t k = b->colour_first[c]; k < b->colour_first[c + 1]; k++) {
        const uint32_t blk = b->list[k];
        if (mrn_block_owner(b, blk, nchunks, team) == t)
          run(args, b->order, b->start[blk], b->start[blk + 1], &first_bad, &sp);
      }
#pragma omp barrier
    }
  }
  *spent = sp;
  return first_bad;
}

/* one particle, general stencil */
static void KNAME(p2g_general)(const KNAME(p2g_args) *ar, size_t p, int momentum, int force, int affine) {
  mrn_grid *g = ar->g;
  const mrn_particles *ps = ar->ps;
  KNAME(stencil) s;
  KNAME(stencil_build)(g, &ar->ko, ps->x + 3 * p, ps->vol0[p], &s);
  const double m = ps->mass[p];
  const double *v = ps->v + 3 * p;
  const double *A = ps->affine + TSTRIDE * p;
  const double *sig = ps->stress + 6 * p;
  const double vol = mrn_particle_volume_dim(ps, p, DIM);
  for (int c = 0; c < s.count; c++) {
    const size_t n = s.node[c];
    if (momentum) {
      const double wm = s.N[c] * m;
      g->mass[n] += wm;
      for (int a = 0; a < DIM; a++) {
        double va = v[a];
        /* (000, Eqs. 19-20 and 23-24): v_p + A_p (x_i - x_p), A = grad v or C */
        if (affine)
          for (int b = 0; b < DIM; b++) va += A[DIM * a + b] * s.offset[c][b];
        g->mom[3 * n + a] += wm * va;
      }
    }
    if (force) {
      /* f_a = -V sigma_ab dN/dx_b */
      for (int a = 0; a < DIM; a++) {
        double f = 0.0;
        for (int b = 0; b < DIM; b++) f += sig[sym_index(a, b)] * s.dN[c][b];
        g->force[3 * n + a] -= vol * f;
      }
    }
  }
}

/* The per-particle factors both fast P2G forms start from: m v, m A (APIC's
 * affine matrix, zero when off) and V sigma; components beyond DIM stay 0. */
MRN_INLINE void KNAME(p2g_particle_terms)(const mrn_particles *ps, size_t p, int affine, double mv[3],
                                          double MA[3][3], double VS[3][3]) {
  const double m = ps->mass[p], vol = mrn_particle_volume_dim(ps, p, DIM);
  const double *v = ps->v + 3 * p, *A = ps->affine + TSTRIDE * p, *sig = ps->stress + 6 * p;
  for (int a = 0; a < 3; a++) {
    mv[a] = a < DIM ? m * v[a] : 0.0;
    for (int b = 0; b < 3; b++) {
      MA[a][b] = (affine && a < DIM && b < DIM) ? m * A[DIM * a + b] : 0.0;
      VS[a][b] = (a < DIM && b < DIM) ? vol * sig[sym_index(a, b)] : 0.0;
    }
  }
}

#if DIM == 3
/* Short vectors for the rows of nodes: a row holds 3 sup contiguous values
 * (9 or 12), handled as 4-wide vectors plus a scalar tail; never a value
 * beyond the row (the next node may belong to another thread's block). */
#ifndef MRN_KERNEL_V4
#define MRN_KERNEL_V4
/* 4 doubles at any 8-byte aligned address, aliasing plain doubles (macros,
 * so no function passes a vector by value: the ABI then does not depend on
 * the instruction set) */
typedef double mrn_v4 __attribute__((vector_size(32), aligned(8), may_alias));
#define mrn_v4_load(p) (*(const mrn_v4 *)(p))
#define mrn_v4_store(p, v) (*(mrn_v4 *)(p) = (v))
#endif

/* One particle, plain B-spline factors. The nodes are visited by rows (the
 * `sup` nodes along x at one y, z), whose 3 sup nodal values are contiguous
 * in memory; each row gets a combination of per-particle vectors set up
 * once. With N = w_x w_y w_z, the branch x_i - x_p = (o_x, o_y, o_z) and A_b
 * the column b of A:
 *   m N (v + A (x_i - x_p)) = w_y w_z Q + w_y o_y w_z MY + w_y w_z o_z MZ,
 *        Q = w_x m (v + A_x o_x), MY = w_x m A_y, MZ = w_x m A_z;
 *   -V sigma grad N = -(w_y w_z FX + dw_y w_z FY + w_y dw_z FZ),
 *        FX = dw_x V sigma_x, FY = w_x V sigma_y, FZ = w_x V sigma_z.
 * Components beyond DIM are zero. */
MRN_INLINE void KNAME(p2g_fast)(const KNAME(p2g_args) *ar, const KNAME(axes) *ax, size_t p, const int sup,
                                const int momentum, const int force, const int affine) {
  mrn_grid *g = ar->g;
  const mrn_particles *ps = ar->ps;
  const double m = ps->mass[p];
  const int T = 3 * sup, NV = T / 4;
  double Q[12] __attribute__((aligned(32))), MY[12] __attribute__((aligned(32))), MZ[12] __attribute__((aligned(32)));
  double FX[12] __attribute__((aligned(32))), FY[12] __attribute__((aligned(32))), FZ[12] __attribute__((aligned(32)));
  double MW[4];
  double mv[3], MA[3][3], VS[3][3];
  KNAME(p2g_particle_terms)(ps, p, affine, mv, MA, VS);
#pragma GCC unroll 4
  for (int i = 0; i < sup; i++) {
    const double wx = ax->w[0][i], dwx = ax->dw[0][i], ox = ax->off[0][i];
    MW[i] = m * wx;
#pragma GCC unroll 3
    for (int a = 0; a < 3; a++) {
      const int t = 3 * i + a;
      if (momentum) {
        Q[t] = wx * (mv[a] + MA[a][0] * ox);
        MY[t] = wx * MA[a][1];
        MZ[t] = wx * MA[a][2];
      }
      if (force) {
        FX[t] = dwx * VS[a][0];
        FY[t] = wx * VS[a][1];
        FZ[t] = wx * VS[a][2];
      }
    }
  }
  double *restrict mass = g->mass, *restrict mom = g->mom, *restrict frc = g->force;
  const long s1 = g->stride[1];
  const long s2 = g->stride[2];
  for (int k = 0; k < sup; k++)
    for (int j = 0; j < sup; j++) {
      const double wy = ax->w[1][j];
      const double wz = ax->w[2][k], wr = wy * wz, cy = wy * ax->off[1][j] * wz, cz = wr * ax->off[2][k];
      const double fy = ax->dw[1][j] * wz, fz = wy * ax->dw[2][k];
      const size_t row = ax->node0 + (size_t)(j * s1) + (size_t)(k * s2);
      if (momentum) {
        for (int i = 0; i < sup; i++) mass[row + (size_t)i] += wr * MW[i];
        double *mr = mom + 3 * row;
        for (int c = 0; c < NV; c++) {
          mrn_v4 add = wr * mrn_v4_load(Q + 4 * c);
          if (affine) add += cy * mrn_v4_load(MY + 4 * c);
          if (affine) add += cz * mrn_v4_load(MZ + 4 * c);
          mrn_v4_store(mr + 4 * c, mrn_v4_load(mr + 4 * c) + add);
        }
        for (int t = 4 * NV; t < T; t++) {
          double add = wr * Q[t];
          if (affine) add += cy * MY[t];
          if (affine) add += cz * MZ[t];
          mr[t] += add;
        }
      }
      if (force) {
        double *fr = frc + 3 * row;
        for (int c = 0; c < NV; c++) {
          mrn_v4 f = wr * mrn_v4_load(FX + 4 * c) + fy * mrn_v4_load(FY + 4 * c);
          f += fz * mrn_v4_load(FZ + 4 * c);
          mrn_v4_store(fr + 4 * c, mrn_v4_load(fr + 4 * c) - f);
        }
        for (int t = 4 * NV; t < T; t++) {
          double f = wr * FX[t] + fy * FY[t];
          f += fz * FZ[t];
          fr[t] -= f;
        }
      }
    }
}

#else
#ifndef MRN_KERNEL_V2
#define MRN_KERNEL_V2
/* the x, y components of a node, at any 8-byte aligned address (see mrn_v4) */
typedef double mrn_v2 __attribute__((vector_size(16), aligned(8), may_alias));
#define mrn_v2_load(p) (*(const mrn_v2 *)(p))
#define mrn_v2_store(p, v) (*(mrn_v2 *)(p) = (v))
#endif

/* One particle, plain B-spline factors, in 2D. The node values are formed
 * row by row (a row: the nodes along x at one y): with N = w_x w_y, the
 * branch x_i - x_p = (o_x, o_y) and A_x, A_y the columns of A,
 *   m N (v + A (x_i - x_p)) = w_x (c + s o_x),  c = m w_y (v + A_y o_y), s = m w_y A_x
 *   -V sigma grad N         = -(r dw_x + q w_x), r = V sigma_x w_y,      q = V sigma_y dw_y
 * so a node costs two multiply-adds per term, on the node's (x, y) pair as
 * one 2-wide vector. (Short vectors over a whole row, as in 3D, waste a
 * third of every vector on the z components in 2D.) */
MRN_INLINE void KNAME(p2g_fast)(const KNAME(p2g_args) *ar, const KNAME(axes) *ax, size_t p, const int sup,
                                const int momentum, const int force, const int affine) {
  mrn_grid *g = ar->g;
  const mrn_particles *ps = ar->ps;
  const double m = ps->mass[p];
  double mv[3], MA[3][3], VS[3][3];
  KNAME(p2g_particle_terms)(ps, p, affine, mv, MA, VS);
  double *restrict mass = g->mass, *restrict mom = g->mom, *restrict frc = g->force;
  const long s1 = g->stride[1];
  for (int j = 0; j < sup; j++) {
    const double wr = ax->w[1][j];
    const size_t row = ax->node0 + (size_t)(j * s1);
    const double mr = m * wr;
    /* the x, y components of a node are contiguous: one 2-wide vector */
    mrn_v2 c = {0, 0}, sl = {0, 0}, r = {0, 0}, q = {0, 0};
    for (int a = 0; a < DIM; a++) {
      if (momentum) {
        c[a] = wr * (affine ? mv[a] + MA[a][1] * ax->off[1][j] : mv[a]);
        sl[a] = affine ? wr * MA[a][0] : 0.0;
      }
      if (force) {
        r[a] = VS[a][0] * wr;
        q[a] = VS[a][1] * ax->dw[1][j];
      }
    }
    for (int i = 0; i < sup; i++) {
      const size_t n = row + (size_t)i;
      const double wx = ax->w[0][i];
      if (momentum) {
        mass[n] += wx * mr;
        mrn_v2 t = c;
        if (affine) t += sl * ax->off[0][i];
        mrn_v2_store(mom + 3 * n, mrn_v2_load(mom + 3 * n) + wx * t);
      }
      if (force) mrn_v2_store(frc + 3 * n, mrn_v2_load(frc + 3 * n) - (r * ax->dw[0][i] + q * wx));
    }
  }
}

#endif

/* ---- batches and groups of particles ----------------------------------------------
 *
 * P2G and USF's fused pass go through a block's particles in batches: up to
 * MRN_BATCH particles of consecutive indices (in block order) whose
 * stencils are all fast, built together (batch_build). Within a batch, in
 * 2D, a group of particles that follow one another with stencils starting
 * at the same node (as seeded or sorted: for a linear, uGIMP or cubic
 * kernel mostly the particles of one cell, for a quadratic one those
 * between the same cell centres) is summed in registers, row by row of the
 * stencil, and the sums are added to the nodes once (group_sum); a particle
 * alone is added to the nodes directly (p2g_fast), as is every particle in
 * 3D. Both passes form the same
 * batches from the same block order, so the force they scatter is the same
 * bit for bit, whatever the thread count. */

/* particles per batch (their stencils are kept; the fused pass hands their
 * velocity gradients to the material update together) */
enum { MRN_BATCH = 64 };

/* The stencils of the batch that starts at order position q with particle
 * p0, into ax; returns its length (0: p0 needs the general stencil). With
 * gvel, each particle's velocity gradient is gathered from it into
 * L + 9 j as its stencil is built. */
MRN_INLINE size_t KNAME(batch_build)(const KNAME(p2g_args) *ar, const uint32_t *order, size_t q, size_t to,
                                     size_t p0, KNAME(axes) *ax, const double *gvel, double *L, const int kind,
                                     const int momentum, const int force, const int affine);

#if DIM == 2
#ifndef MRN_ACC4
#define MRN_ACC4
/* four nodes of a row of the stencil as the lanes of one vector */
typedef double mrn_acc4 __attribute__((vector_size(32)));
#endif

/* The sums of a group, row by row of the stencil (lanes i: the nodes along
 * x). Every index into them is a constant once the row functions below are
 * inlined with a literal row: the compiler keeps the sums in registers only
 * then. */
typedef struct KNAME(group_acc) {
  mrn_acc4 m[4], px[4], py[4], fx[4], fy[4]; /* mass, momentum, internal force */
} KNAME(group_acc);

/* A particle's x factors of a group (see group_sum), on the group's lanes */
typedef struct KNAME(group_x) {
  mrn_acc4 mw, qx, qy, yx, yy, rx, ry, sx, sy;
} KNAME(group_x);

MRN_INLINE void KNAME(group_x_factors)(const mrn_particles *ps, const KNAME(axes) *a, size_t p, int shifted,
                                       const int affine, KNAME(group_x) *f) {
  const double m = ps->mass[p];
  double mv[3], MA[3][3], VS[3][3];
  KNAME(p2g_particle_terms)(ps, p, affine, mv, MA, VS);
  /* lanes beyond the support hold zeros (axes_build); a stencil of
   * fewer than 4 nodes starting one node further along x takes the lanes
   * from 1 */
  mrn_acc4 wx = {a->w[0][0], a->w[0][1], a->w[0][2], a->w[0][3]};
  mrn_acc4 dwx = {a->dw[0][0], a->dw[0][1], a->dw[0][2], a->dw[0][3]};
  mrn_acc4 ox = {a->off[0][0], a->off[0][1], a->off[0][2], a->off[0][3]};
  if (shifted) {
    wx = __builtin_shufflevector(wx, wx, 3, 0, 1, 2);
    dwx = __builtin_shufflevector(dwx, dwx, 3, 0, 1, 2);
    ox = __builtin_shufflevector(ox, ox, 3, 0, 1, 2);
  }
  f->mw = m * wx;
  f->qx = affine ? wx * (mv[0] + MA[0][0] * ox) : wx * mv[0];
  f->qy = affine ? wx * (mv[1] + MA[1][0] * ox) : wx * mv[1];
  f->yx = wx * MA[0][1], f->yy = wx * MA[1][1];
  f->rx = dwx * VS[0][0], f->ry = dwx * VS[1][0], f->sx = wx * VS[0][1], f->sy = wx * VS[1][1];
}

/* a particle's terms added to row J of the sums */
MRN_INLINE void KNAME(group_add_row)(KNAME(group_acc) *s, const KNAME(axes) *a, const KNAME(group_x) *f, const int J,
                                     const int momentum, const int force, const int affine) {
  const double wr = a->w[1][J];
  if (momentum) {
    s->m[J] += wr * f->mw;
    s->px[J] += wr * f->qx;
    s->py[J] += wr * f->qy;
    if (affine) {
      const double wo = wr * a->off[1][J];
      s->px[J] += wo * f->yx;
      s->py[J] += wo * f->yy;
    }
  }
  if (force) {
    const double dwr = a->dw[1][J];
    s->fx[J] -= wr * f->rx;
    s->fx[J] -= dwr * f->sx;
    s->fy[J] -= wr * f->ry;
    s->fy[J] -= dwr * f->sy;
  }
}

/* row J of the sums into the nodes: `width` nodes from the row's first,
 * never a node beyond the stencils (it may belong to another thread's block) */
MRN_INLINE void KNAME(group_flush_row)(const KNAME(p2g_args) *ar, size_t node0, const KNAME(group_acc) *s, const int J,
                                       const int width, const int momentum, const int force) {
  mrn_grid *g = ar->g;
  double *restrict mass = g->mass, *restrict mom = g->mom, *restrict frc = g->force;
  const size_t row = node0 + (size_t)(J * g->stride[1]);
  for (int i = 0; i < width; i++) {
    const size_t nd = row + (size_t)i;
    if (momentum) {
      mass[nd] += s->m[J][i];
      const mrn_v2 add = {s->px[J][i], s->py[J][i]};
      mrn_v2_store(mom + 3 * nd, mrn_v2_load(mom + 3 * nd) + add);
    }
    if (force) {
      const mrn_v2 add = {s->fx[J][i], s->fy[J][i]};
      mrn_v2_store(frc + 3 * nd, mrn_v2_load(frc + 3 * nd) + add);
    }
  }
}

MRN_INLINE void KNAME(group_flush)(const KNAME(p2g_args) *ar, size_t node0, const KNAME(group_acc) *s, const int sup,
                                   const int width, const int momentum, const int force) {
  KNAME(group_flush_row)(ar, node0, s, 0, width, momentum, force);
  KNAME(group_flush_row)(ar, node0, s, 1, width, momentum, force);
  if (sup >= 3) KNAME(group_flush_row)(ar, node0, s, 2, width, momentum, force);
  if (sup == 4) KNAME(group_flush_row)(ar, node0, s, 3, width, momentum, force);
}

/* The particles p0 .. p0 + n - 1 (n >= 2), whose stencils ax[0 .. n) all
 * start at ax[0].node0 or, when `wide` (supports of 2 or 3 nodes along x),
 * some at the node after it along x, summed and added to the nodes: the
 * lanes of a row are then its sup + 1 nodes from ax[0].node0, and a stencil
 * starting at the next node has its x factors moved up one lane (its lanes
 * beyond the support are zeros, axes_build). With N = w_x w_y, the
 * branch x_i - x_p = (o_x, o_y) and A_x, A_y the columns of A, row j of the
 * nodes (lanes i, along x) receives from each particle
 *   m N                      = w_y (m w_x)
 *   m N (v + A (x_i - x_p))  = w_y Q + w_y o_y Y,  Q = w_x m (v + A_x o_x), Y = w_x m A_y
 *   -V sigma grad N          = -(w_y R + dw_y S),  R = dw_x V sigma_x,     S = w_x V sigma_y
 * with the x factors Q, Y, R, S formed once per particle (group_x_factors). */
MRN_INLINE void KNAME(group_sum)(const KNAME(p2g_args) *ar, const KNAME(axes) *ax, size_t p0, size_t n,
                                 const int sup, const int wide, const int momentum, const int force,
                                 const int affine) {
  KNAME(group_acc) s = {0};
  for (size_t k = 0; k < n; k++) {
    const KNAME(axes) *a = ax + k;
    KNAME(group_x) f;
    KNAME(group_x_factors)(ar->ps, a, p0 + k, wide && a->node0 != ax->node0, affine, &f);
    KNAME(group_add_row)(&s, a, &f, 0, momentum, force, affine);
    KNAME(group_add_row)(&s, a, &f, 1, momentum, force, affine);
    if (sup >= 3) KNAME(group_add_row)(&s, a, &f, 2, momentum, force, affine);
    if (sup == 4) KNAME(group_add_row)(&s, a, &f, 3, momentum, force, affine);
  }
  /* `sup` nodes per row, one more for a wide group (sup < 4) */
  if (wide) KNAME(group_flush)(ar, ax->node0, &s, sup, sup < 4 ? sup + 1 : 4, momentum, force);
  else KNAME(group_flush)(ar, ax->node0, &s, sup, sup, momentum, force);
}
#endif

/* A batch's particles p0 .. p0 + n - 1, stencils ax[0 .. n), to the grid */
MRN_INLINE void KNAME(batch_scatter)(const KNAME(p2g_args) *ar, const KNAME(axes) *ax, size_t p0, size_t n,
                                     const int kind, const int momentum, const int force, const int affine) {
  const int sup = MRN_FAST_SUPPORT(kind);
  size_t j = 0;
  while (j < n) {
    size_t e = j + 1;
#if DIM == 2
    int wide = 0;
    for (; e < n; e++) {
      if (ax[e].node0 == ax[j].node0) continue;
      if (sup <= 3 && ax[e].node0 == ax[j].node0 + 1) {
        wide = 1;
        continue;
      }
      break;
    }
    if (e - j > 1) {
      if (wide) KNAME(group_sum)(ar, ax + j, p0 + j, e - j, sup, 1, momentum, force, affine);
      else KNAME(group_sum)(ar, ax + j, p0 + j, e - j, sup, 0, momentum, force, affine);
      j = e;
      continue;
    }
#endif
    KNAME(p2g_fast)(ar, &ax[j], p0 + j, sup, momentum, force, affine);
    j = e;
  }
}

/* the particles order[from .. to) (or from .. to when order is NULL) */
MRN_INLINE void KNAME(p2g_range)(const KNAME(p2g_args) *ar, const uint32_t *order, size_t from, size_t to,
                                 const int kind, const int momentum, const int force, const int affine) {
  KNAME(axes) ax[MRN_BATCH];
  size_t q = from;
  while (q < to) {
    const size_t p0 = order ? order[q] : q;
    const size_t n =
        kind ? KNAME(batch_build)(ar, order, q, to, p0, ax, NULL, NULL, kind, momentum, force, affine) : 0;
    if (!n) {
      KNAME(p2g_general)(ar, p0, momentum, force, affine);
      q++;
      continue;
    }
    KNAME(batch_scatter)(ar, ax, p0, n, kind, momentum, force, affine);
    q += n;
  }
}

/* Every P2G instance: fast stencil (0: the general one), mass and momentum,
 * internal force, affine term; one specialised range function each
 * (p2g_range with these constants), named and tabled from this list. */
#define MRN_P2G_VARIANTS_OF(X, KIND) \
  X(KIND, 1, 0, 0) X(KIND, 1, 0, 1) X(KIND, 0, 1, 0) X(KIND, 1, 1, 0) X(KIND, 1, 1, 1)
#define MRN_P2G_VARIANTS(X)                                                           \
  MRN_P2G_VARIANTS_OF(X, 0) MRN_P2G_VARIANTS_OF(X, 2) MRN_P2G_VARIANTS_OF(X, 3) \
  MRN_P2G_VARIANTS_OF(X, 4) MRN_P2G_VARIANTS_OF(X, 5)

#define MRN_P2G_INSTANCE(KIND, MOM, FRC, AFF)                                                                  \
  static void KNAME(p2g_##KIND##_##MOM##FRC##AFF)(const void *ar, const uint32_t *order, size_t from, size_t to, \
                                                  long *first_bad, double *spent) {                            \
    (void)first_bad, (void)spent;                                                                              \
    KNAME(p2g_range)(ar, order, from, to, KIND, MOM, FRC, AFF);                                                \
  }
MRN_P2G_VARIANTS(MRN_P2G_INSTANCE)
#undef MRN_P2G_INSTANCE

typedef struct KNAME(p2g_variant) {
  int kind, momentum, force, affine;
  KNAME(range_fn) run;
} KNAME(p2g_variant);

#define MRN_P2G_ENTRY(KIND, MOM, FRC, AFF) {KIND, MOM, FRC, AFF, KNAME(p2g_##KIND##_##MOM##FRC##AFF)},
static const KNAME(p2g_variant) KNAME(p2g_variants)[] = {MRN_P2G_VARIANTS(MRN_P2G_ENTRY)};
#undef MRN_P2G_ENTRY

static KNAME(range_fn) KNAME(p2g_pick)(int kind, int momentum, int force, int affine) {
  affine = affine && momentum;
  const size_t count = sizeof KNAME(p2g_variants) / sizeof KNAME(p2g_variants)[0];
  for (size_t k = 0; k < count; k++) {
    const KNAME(p2g_variant) *v = &KNAME(p2g_variants)[k];
    if (v->kind == kind && v->momentum == momentum && v->force == force && v->affine == affine) return v->run;
  }
  return NULL;
}

/* time spent sorting inside a P2G, which the profile books apart */
static inline double KNAME(sort_seconds)(void) { return mrn_profile_seconds ? mrn_profile_seconds[MRN_PHASE_SORT] : 0.0; }

void KNAME(mrn_p2g)(mrn_transfer *tr, int momentum, int force) {
  if (mrn_shape_tracks_domain(tr->kernel.shape)) { /* no fast form (cpdi.h) */
    mrn_cpdi_p2g(tr, momentum, force);
    return;
  }
  const double t0 = mrn_phase_begin(), sort0 = KNAME(sort_seconds)();
  if (!momentum && !force) return;
  const unsigned clear = (momentum ? MRN_CLEAR_MASS_MOM : 0u) | (force ? MRN_CLEAR_FORCE : 0u);
  mrn_blocks *b = mrn_blocks_prepare(tr, clear); /* may reorder the particles */
  KNAME(p2g_args) ar = {tr->grid, tr->particles, tr->kernel};
  const int affine = tr->scheme->grid_velocity != MRN_VGRID_PLAIN;
  const KNAME(range_fn) run = KNAME(p2g_pick)(KNAME(fast_kind)(&ar.ko), momentum, force, affine);
  double unused = 0.0;
  if (!b) {
    run(&ar, NULL, 0, tr->particles->n, NULL, &unused);
  } else {
    KNAME(for_own_blocks)(b, !b->dense && tr->particles->n > MRN_OMP_MIN_ITEMS, run, &ar, 0, &unused);
  }
  if (mrn_profile_seconds) mrn_phase_end(MRN_PHASE_P2G, t0 + (KNAME(sort_seconds)() - sort0));
}

/* ---- gathers ------------------------------------------------------------------ */

#if DIM == 3
/* Sums over a fast stencil, factor by factor: the rows of nodes (the `sup`
 * nodes along x at one y, z; 3 sup contiguous values) are added up with the
 * weights of y and z as whole vectors, and the x factors applied once at
 * the end:
 *   vpic = sum N v                         (000, Eq. 31) when want_pic
 *   vold = sum N v_old                     (the velocity before the update) when want_old
 *   B    = sum N v (x) (x_i - x_p)         (000, Eq. 26) when want_b
 *   L    = sum v (x) grad N                (000, Eqs. 44-45) when want_l
 * Every output is added to. */
MRN_INLINE void KNAME(gather_fast)(const KNAME(axes) *ax, const double *restrict gvel, const double *restrict gold,
                                   long s1, long s2, const int sup, const int want_pic, const int want_old,
                                   const int want_b, const int want_l, double vpic[DIM], double vold[DIM],
                                   double B[DIM][DIM], double L[DIM][DIM]) {
  const int T = 3 * sup, NV = T / 4;
  mrn_v4 R[3] = {{0}}, RA[3] = {{0}}, RY[3] = {{0}}, RZ[3] = {{0}}, RDY[3] = {{0}}, RDZ[3] = {{0}};
  double r[12] = {0}, ra[12] = {0}, ry[12] = {0}, rz[12] = {0}, rdy[12] = {0}, rdz[12] = {0}; /* tails */
  for (int k = 0; k < sup; k++)
    for (int j = 0; j < sup; j++) {
      const double wy = ax->w[1][j];
      const double wz = ax->w[2][k], wr = wy * wz, cy = wy * ax->off[1][j] * wz, cz = wr * ax->off[2][k];
      const double dy = ax->dw[1][j] * wz, dz = wy * ax->dw[2][k];
      const size_t row = ax->node0 + (size_t)(j * s1) + (size_t)(k * s2);
      const double *vr = gvel + 3 * row;
      const double *orow = want_old ? gold + 3 * row : NULL;
      for (int c = 0; c < NV; c++) {
        const mrn_v4 vv = mrn_v4_load(vr + 4 * c);
        R[c] += wr * vv;
        if (want_old) RA[c] += wr * mrn_v4_load(orow + 4 * c);
        if (want_b) {
          RY[c] += cy * vv;
          RZ[c] += cz * vv;
        }
        if (want_l) {
          RDY[c] += dy * vv;
          RDZ[c] += dz * vv;
        }
      }
      for (int t = 4 * NV; t < T; t++) {
        r[t] += wr * vr[t];
        if (want_old) ra[t] += wr * orow[t];
        if (want_b) {
          ry[t] += cy * vr[t];
          rz[t] += cz * vr[t];
        }
        if (want_l) {
          rdy[t] += dy * vr[t];
          rdz[t] += dz * vr[t];
        }
      }
    }
  for (int c = 0; c < NV; c++) {
    mrn_v4_store(r + 4 * c, R[c]);
    if (want_old) mrn_v4_store(ra + 4 * c, RA[c]);
    if (want_b) {
      mrn_v4_store(ry + 4 * c, RY[c]);
      mrn_v4_store(rz + 4 * c, RZ[c]);
    }
    if (want_l) {
      mrn_v4_store(rdy + 4 * c, RDY[c]);
      mrn_v4_store(rdz + 4 * c, RDZ[c]);
    }
  }
  for (int a = 0; a < DIM; a++)
    for (int i = 0; i < sup; i++) {
      const int t = 3 * i + a;
      const double wx = ax->w[0][i];
      if (want_pic) vpic[a] += wx * r[t];
      if (want_old) vold[a] += wx * ra[t];
      if (want_b) {
        B[a][0] += wx * ax->off[0][i] * r[t];
        B[a][1] += wx * ry[t];
        B[a][2] += wx * rz[t];
      }
      if (want_l) {
        L[a][0] += ax->dw[0][i] * r[t];
        L[a][1] += wx * rdy[t];
        L[a][2] += wx * rdz[t];
      }
    }
}

#else
/* Sums over a fast stencil, factor by factor, in 2D: along each row of nodes
 * the sums of w_x v, w_x v_old, w_x o_x v and dw_x v, then those of the
 * rows weighted by w_y, w_y o_y or dw_y, on (x, y) pairs as 2-wide vectors:
 *   vpic = sum N v                         (000, Eq. 31) when want_pic
 *   vold = sum N v_old                     (the velocity before the update) when want_old
 *   B    = sum N v (x) (x_i - x_p)         (000, Eq. 26) when want_b
 *   L    = sum v (x) grad N                (000, Eqs. 44-45) when want_l
 * Every output is added to. */
MRN_INLINE void KNAME(gather_fast)(const KNAME(axes) *ax, const double *restrict gvel, const double *restrict gold,
                                   long s1, long s2, const int sup, const int want_pic, const int want_old,
                                   const int want_b, const int want_l, double vpic[DIM], double vold[DIM],
                                   double B[DIM][DIM], double L[DIM][DIM]) {
  (void)s2;
  double wox[4];
  for (int i = 0; i < sup; i++) wox[i] = ax->w[0][i] * ax->off[0][i];
  /* (x, y) pairs as 2-wide vectors; Bx, By, Lx, Ly the columns of B and L */
  mrn_v2 sv = {vpic[0], vpic[1]}, sa = {vold[0], vold[1]}, Bx = {B[0][0], B[1][0]}, By = {B[0][1], B[1][1]};
  mrn_v2 Lx = {L[0][0], L[1][0]}, Ly = {L[0][1], L[1][1]};
  for (int j = 0; j < sup; j++) {
    const size_t row = ax->node0 + (size_t)(j * s1);
    mrn_v2 rv = {0, 0}, ra = {0, 0}, rvx = {0, 0}, rdv = {0, 0};
    for (int i = 0; i < sup; i++) {
      const mrn_v2 vi = mrn_v2_load(gvel + 3 * (row + (size_t)i));
      rv += ax->w[0][i] * vi;
      if (want_old) ra += ax->w[0][i] * mrn_v2_load(gold + 3 * (row + (size_t)i));
      if (want_b) rvx += wox[i] * vi;
      if (want_l) rdv += ax->dw[0][i] * vi;
    }
    const double wy = ax->w[1][j], woy = wy * ax->off[1][j], dwy = ax->dw[1][j];
    if (want_pic) sv += wy * rv;
    if (want_old) sa += wy * ra;
    if (want_b) {
      Bx += wy * rvx;
      By += woy * rv;
    }
    if (want_l) {
      Lx += wy * rdv;
      Ly += dwy * rv;
    }
  }
  for (int a = 0; a < DIM; a++) {
    vpic[a] = sv[a];
    vold[a] = sa[a];
    B[a][0] = Bx[a];
    B[a][1] = By[a];
    L[a][0] = Lx[a];
    L[a][1] = Ly[a];
  }
}
#endif

/* the same sums over a general stencil; vold when gold is given */
static inline void KNAME(gather_general)(const KNAME(stencil) *s, const double *gvel, const double *gold,
                                         const double *gstar, int want_pic, int want_bd, int want_l, double vpic[DIM],
                                         double vold[DIM], double vstar[DIM], double B[DIM][DIM], double D[DIM][DIM],
                                         double L[DIM][DIM]) {
  for (int c = 0; c < s->count; c++) {
    const size_t node = s->node[c];
    const double *vi = gvel + 3 * node;
    if (want_pic)
      for (int d = 0; d < DIM; d++) {
        vpic[d] += s->N[c] * vi[d];
        if (gold) vold[d] += s->N[c] * gold[3 * node + d];
        if (gstar) vstar[d] += s->N[c] * gstar[3 * node + d];
      }
    if (want_bd)
      for (int a = 0; a < DIM; a++)
        for (int b = 0; b < DIM; b++) {
          B[a][b] += s->N[c] * vi[a] * s->offset[c][b];
          D[a][b] += s->N[c] * s->offset[c][a] * s->offset[c][b];
        }
    if (want_l)
      for (int a = 0; a < DIM; a++)
        for (int b = 0; b < DIM; b++) L[a][b] += vi[a] * s->dN[c][b];
  }
}

/* a velocity gradient as a full row-major 3 x 3 (what the material update takes) */
static inline void KNAME(store_matrix)(const double M[DIM][DIM], double *out) {
  memset(out, 0, 9 * sizeof(double));
  for (int a = 0; a < DIM; a++)
    for (int b = 0; b < DIM; b++) out[3 * a + b] = M[a][b];
}

/* a particle tensor as stored (TSTRIDE values: particles.h) */
static inline void KNAME(store_tensor)(const double M[DIM][DIM], double *out) {
  for (int a = 0; a < DIM; a++)
    for (int b = 0; b < DIM; b++) out[DIM * a + b] = M[a][b];
}

/* Hands the gradients L of particles [lo, hi) to the sink; keeps the lowest
 * rejected index and, when the phases are timed, the time spent there. */
MRN_INLINE void KNAME(hand_over)(const mrn_gradient_sink *sink, long lo, long hi, const double *L, long *first_bad,
                                 double *spent) {
  const double t0 = mrn_phase_begin();
  const long bad = sink->chunk(sink->ctx, (size_t)lo, (size_t)hi, L);
  if (mrn_profile_seconds) *spent += mrn_profile_now() - t0;
  if (bad >= 0 && bad < *first_bad) *first_bad = bad;
}

/* The body of a chunked kernel instance (the velocity gradient, G2P): the
 * particles in chunks of MRN_GRADIENT_CHUNK, each thread its own chunks
 * (mrn_team_chunks: the particles it scattered in P2G); EACH handles
 * particle p of the chunk [lo, hi), writing its gradient to L + 9 (p - lo)
 * when HAND_OVER, and the chunk's gradients then go to `sink`; then, when
 * `after` is not NULL, the chunk goes to it (mrn_particle_pass). Returns the
 * lowest index the sink rejected, or -1, sets *sink_seconds and, with
 * `after`, *after_bad (the lowest index it rejected, or -1). The parallel
 * region sits in each instance, not in a shared function: GCC outlines a
 * parallel region before it inlines, so only there does the outlined loop
 * see the instance's constants (and contract and vectorise its sums as the
 * reference results were formed). */
#define MRN_CHUNKED_LOOP(N, HAND_OVER, EACH)                                                                  \
  const long n_ = (N), nchunks_ = (n_ + MRN_GRADIENT_CHUNK - 1) / MRN_GRADIENT_CHUNK;                        \
  long first_bad = n_, first_after = n_;                                                                     \
  double spent = 0.0;                                                                                        \
  _Pragma("omp parallel if (n_ > MRN_OMP_MIN_ITEMS) reduction(min : first_bad, first_after) reduction(+ : spent)") { \
    size_t c0_, c1_;                                                                                         \
    mrn_team_chunks((size_t)nchunks_, &c0_, &c1_);                                                           \
    for (long c = (long)c0_; c < (long)c1_; c++) {                                                           \
      const long lo = c * MRN_GRADIENT_CHUNK, hi = lo + MRN_GRADIENT_CHUNK < n_ ? lo + MRN_GRADIENT_CHUNK : n_; \
      double L[(HAND_OVER) ? 9 * MRN_GRADIENT_CHUNK : 1];                                                     \
      for (long p = lo; p < hi; p++) EACH;                                                                   \
      if (HAND_OVER) KNAME(hand_over)(sink, lo, hi, L, &first_bad, &spent);                                  \
      if (after) {                                                                                           \
        const long bad_ = after->chunk(after->ctx, (size_t)lo, (size_t)hi);                                  \
        if (bad_ >= 0 && bad_ < first_after) first_after = bad_;                                             \
      }                                                                                                      \
    }                                                                                                        \
  }                                                                                                          \
  *sink_seconds = spent;                                                                                     \
  if (after) *after_bad = first_after < n_ ? first_after : -1;                                               \
  return first_bad < n_ ? first_bad : -1;

/* ---- velocity gradient ---------------------------------------------------------- */

/* L of a particle with a fast stencil into out (9 values) */
MRN_INLINE void KNAME(gradient_fast)(const mrn_grid *g, const KNAME(axes) *ax, const double *gvel, double *out,
                                     const int sup) {
  double L[DIM][DIM] = {{0}}, none[DIM][DIM] = {{0}}, nv[DIM] = {0};
  KNAME(gather_fast)(ax, gvel, NULL, g->stride[1], g->stride[2], sup, 0, 0, 0, 1, nv, nv, none, L);
  KNAME(store_matrix)(L, out);
}

/* one particle's L into out (9 values); `kind` (MRN_FAST_*, 0: the general
 * stencil) is a constant at every call */
MRN_INLINE void KNAME(gradient_particle)(const mrn_grid *g, const mrn_particles *ps, const mrn_kernel_options *ko,
                                         const double *gvel, size_t p, double *out, const int kind) {
  KNAME(axes) ax;
  if (kind && KNAME(axes_build)(g, kind, ko->boundary, ps->x + 3 * p, MRN_FAST_VOL0(kind, ps, p), &ax)) {
    KNAME(gradient_fast)(g, &ax, gvel, out, MRN_FAST_SUPPORT(kind));
    return;
  }
  double L[DIM][DIM] = {{0}}, none[DIM][DIM] = {{0}}, nv[DIM] = {0};
  KNAME(stencil) s;
  KNAME(stencil_build)(g, ko, ps->x + 3 * p, ps->vol0[p], &s);
  KNAME(gather_general)(&s, gvel, NULL, NULL, 0, 0, 1, nv, nv, nv, none, none, L);
  KNAME(store_matrix)(L, out);
}


/* every velocity gradient instance, by fast stencil (0: the general one) */
#define MRN_GRADIENT_VARIANTS(X) X(0) X(2) X(3) X(4) X(5)

typedef long (*KNAME(gradient_fn))(const mrn_transfer *, const mrn_kernel_options *, const double *,
                                   const mrn_gradient_sink *, double *);

#define MRN_GRADIENT_INSTANCE(KIND)                                                                   \
  static long KNAME(gradient_##KIND)(const mrn_transfer *tr, const mrn_kernel_options *ko, const double *gvel, \
                                    const mrn_gradient_sink *sink, double *sink_seconds) {            \
    const mrn_grid *g = tr->grid;                                                                     \
    const mrn_particles *ps = tr->particles;                                                          \
    const mrn_particle_pass *after = NULL;                                                            \
    long *after_bad = NULL;                                                                           \
    (void)after_bad;                                                                                  \
    MRN_CHUNKED_LOOP((long)ps->n, 1,                                                                  \
                     KNAME(gradient_particle)(g, ps, ko, gvel, (size_t)p, L + 9 * (p - lo), KIND))    \
  }
MRN_GRADIENT_VARIANTS(MRN_GRADIENT_INSTANCE)
#undef MRN_GRADIENT_INSTANCE

typedef struct KNAME(gradient_variant) {
  int kind;
  KNAME(gradient_fn) run;
} KNAME(gradient_variant);

#define MRN_GRADIENT_ENTRY(KIND) {KIND, KNAME(gradient_##KIND)},
static const KNAME(gradient_variant) KNAME(gradient_variants)[] = {MRN_GRADIENT_VARIANTS(MRN_GRADIENT_ENTRY)};
#undef MRN_GRADIENT_ENTRY

static KNAME(gradient_fn) KNAME(gradient_pick)(int kind) {
  const size_t count = sizeof KNAME(gradient_variants) / sizeof KNAME(gradient_variants)[0];
  for (size_t k = 0; k < count; k++)
    if (KNAME(gradient_variants)[k].kind == kind) return KNAME(gradient_variants)[k].run;
  return KNAME(gradient_0);
}

long KNAME(mrn_gradient)(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink) {
  if (mrn_shape_tracks_domain(tr->kernel.shape)) return mrn_cpdi_gradient(tr, gvel, sink);
  const double t0 = mrn_phase_begin();
  const mrn_kernel_options ko = tr->kernel;
  double spent = 0.0;
  const long bad = KNAME(gradient_pick)(KNAME(fast_kind)(&ko))(tr, &ko, gvel, sink, &spent);
  mrn_phase_end_split(MRN_PHASE_G2P, sink->phase, t0, spent, tr->particles->n > MRN_OMP_MIN_ITEMS);
  return bad;
}

MRN_INLINE size_t KNAME(batch_build)(const KNAME(p2g_args) *ar, const uint32_t *order, size_t q, size_t to,
                                     size_t p0, KNAME(axes) *ax, const double *gvel, double *L, const int kind,
                                     const int momentum, const int force, const int affine) {
  size_t n = 0;
  while (q + n < to && n < MRN_BATCH && (order ? order[q + n] : q + n) == p0 + n &&
         KNAME(axes_build)(ar->g, kind, ar->ko.boundary, ar->ps->x + 3 * (p0 + n), MRN_FAST_VOL0(kind, ar->ps, p0 + n),
                           &ax[n])) {
    const size_t p = p0 + n;
    if (gvel) {
      KNAME(gradient_fast)(ar->g, &ax[n], gvel, L + 9 * n, MRN_FAST_SUPPORT(kind));
      /* what the material update reads once the batch's gradients are formed */
      __builtin_prefetch(ar->ps->F + TSTRIDE * p, 1);
      __builtin_prefetch(ar->ps->stress + 6 * p, 1);
      __builtin_prefetch(ar->ps->strain + 6 * p, 1);
      if (ar->ps->state_stride) __builtin_prefetch(ar->ps->state + (size_t)ar->ps->state_stride * p, 1);
    }
    /* what the scatter reads of the particle, asked for while the batch's
     * stencils are built */
    if (momentum) __builtin_prefetch(ar->ps->v + 3 * p);
    if (affine) __builtin_prefetch(ar->ps->affine + TSTRIDE * p);
    if (force) {
      __builtin_prefetch(ar->ps->stress + 6 * p);
      __builtin_prefetch(ar->ps->F + TSTRIDE * p);
    }
    n++;
  }
  return n;
}

/* ---- USF: material update and internal force in one pass ---------------------- */

/* The particles order[from .. to) of one block (or from .. to when order is
 * NULL), batch by batch (batch_build): each particle's stencil is built
 * once, its L gathered from gvel, the batch's L handed to the sink (the
 * material update), and then the internal force of the updated stress
 * scattered with the same stencils, as P2G would. A particle that needs the
 * general stencil is handled on its own. `kind` (MRN_FAST_*) is a constant. */
MRN_INLINE void KNAME(update_force_range)(const KNAME(p2g_args) *ar, const double *gvel, const uint32_t *order,
                                          size_t from, size_t to, const mrn_gradient_sink *sink, long *first_bad,
                                          double *spent, const int kind) {
  const mrn_grid *g = ar->g;
  const mrn_particles *ps = ar->ps;
  KNAME(axes) ax[MRN_BATCH];
  double L[9 * MRN_BATCH];
  size_t q = from;
  while (q < to) {
    const size_t p0 = order ? order[q] : q;
    const size_t n = KNAME(batch_build)(ar, order, q, to, p0, ax, gvel, L, kind, 0, 0, 0);
    if (!n) { /* the general stencil, for this particle alone */
      KNAME(gradient_particle)(g, ps, &ar->ko, gvel, p0, L, 0);
      KNAME(hand_over)(sink, (long)p0, (long)p0 + 1, L, first_bad, spent);
      KNAME(p2g_general)(ar, p0, 0, 1, 0);
      q++;
      continue;
    }
    KNAME(hand_over)(sink, (long)p0, (long)(p0 + n), L, first_bad, spent);
    KNAME(batch_scatter)(ar, ax, p0, n, kind, 0, 1, 0);
    q += n;
  }
}

/* what USF's fused pass needs */
typedef struct KNAME(update_force_args) {
  KNAME(p2g_args) p2g;
  const double *gvel;
  const mrn_gradient_sink *sink;
} KNAME(update_force_args);

/* every instance of the fused pass, by fast stencil */
#define MRN_UPDATE_FORCE_VARIANTS(X) X(2) X(3) X(4) X(5)

#define MRN_UPDATE_FORCE_INSTANCE(KIND)                                                                         \
  static void KNAME(update_force_##KIND)(const void *args, const uint32_t *order, size_t from, size_t to,       \
                                        long *first_bad, double *spent) {                                      \
    const KNAME(update_force_args) *a = args;                                                                  \
    KNAME(update_force_range)(&a->p2g, a->gvel, order, from, to, a->sink, first_bad, spent, KIND);              \
  }
MRN_UPDATE_FORCE_VARIANTS(MRN_UPDATE_FORCE_INSTANCE)
#undef MRN_UPDATE_FORCE_INSTANCE

typedef struct KNAME(update_force_variant) {
  int kind;
  KNAME(range_fn) run;
} KNAME(update_force_variant);

#define MRN_UPDATE_FORCE_ENTRY(KIND) {KIND, KNAME(update_force_##KIND)},
static const KNAME(update_force_variant) KNAME(update_force_variants)[] = {
    MRN_UPDATE_FORCE_VARIANTS(MRN_UPDATE_FORCE_ENTRY)};
#undef MRN_UPDATE_FORCE_ENTRY

static KNAME(range_fn) KNAME(update_force_pick)(int kind) {
  const size_t count = sizeof KNAME(update_force_variants) / sizeof KNAME(update_force_variants)[0];
  for (size_t k = 0; k < count; k++)
    if (KNAME(update_force_variants)[k].kind == kind) return KNAME(update_force_variants)[k].run;
  return NULL;
}

int KNAME(mrn_update_force_fused)(const mrn_transfer *tr) {
  const mrn_kernel_options ko = tr->kernel;
  if (!KNAME(fast_kind)(&ko)) return 0;
  /* In block order the material update reaches F, stress and strain run by
   * run: worth it when the runs are long (particles as seeded, or sorted),
   * not when they are scattered (after a long flow, unsorted: runs of one
   * or two, where the separate passes, in index order, are twice as fast) */
  const mrn_blocks *b = tr->blocks;
  return b->np != tr->particles->n || !b->runs || b->np >= MRN_FUSED_MIN_RUN * b->runs;
}

long KNAME(mrn_update_force)(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink) {
  if (mrn_shape_tracks_domain(tr->kernel.shape)) { /* the two passes (cpdi.h) */
    const long bad = mrn_cpdi_gradient(tr, gvel, sink);
    mrn_cpdi_p2g(tr, 0, 1);
    return bad;
  }
  const double t0 = mrn_phase_begin(), sort0 = KNAME(sort_seconds)();
  mrn_blocks_reuse(tr->blocks); /* the particles have not moved since the first P2G */
  const mrn_blocks *b = mrn_blocks_prepare(tr, MRN_CLEAR_FORCE);
  const KNAME(update_force_args) ar = {{tr->grid, tr->particles, tr->kernel}, gvel, sink};
  const KNAME(range_fn) run = KNAME(update_force_pick)(KNAME(fast_kind)(&tr->kernel));
  const long n = (long)tr->particles->n;
  double spent = 0.0;
  long first_bad = n;
  if (!b) run(&ar, NULL, 0, (size_t)n, &first_bad, &spent);
  else first_bad = KNAME(for_own_blocks)(b, !b->dense && n > MRN_OMP_MIN_ITEMS, run, &ar, n, &spent);
  const long bad = first_bad < n ? first_bad : -1;
  mrn_phase_end_split(MRN_PHASE_P2G, sink->phase, t0 + (KNAME(sort_seconds)() - sort0), spent,
                      b && !b->dense && tr->particles->n > MRN_OMP_MIN_ITEMS);
  return bad;
}

/* ---- G2P ------------------------------------------------------------------------ */

/* C = B D^-1 (000, Eqs. 25-27), stored (TSTRIDE values) */
static inline void KNAME(apic_matrix)(const double B[DIM][DIM], const double D[DIM][DIM], double *C) {
  double Di[DIM][DIM];
#if DIM == 2
  double det = D[0][0] * D[1][1] - D[0][1] * D[1][0];
  Di[0][0] = D[1][1] / det;
  Di[1][1] = D[0][0] / det;
  Di[0][1] = -D[0][1] / det;
  Di[1][0] = -D[1][0] / det;
#else
  double det = D[0][0] * (D[1][1] * D[2][2] - D[1][2] * D[2][1]) - D[0][1] * (D[1][0] * D[2][2] - D[1][2] * D[2][0]) +
               D[0][2] * (D[1][0] * D[2][1] - D[1][1] * D[2][0]);
  Di[0][0] = (D[1][1] * D[2][2] - D[1][2] * D[2][1]) / det;
  Di[0][1] = (D[0][2] * D[2][1] - D[0][1] * D[2][2]) / det;
  Di[0][2] = (D[0][1] * D[1][2] - D[0][2] * D[1][1]) / det;
  Di[1][0] = (D[1][2] * D[2][0] - D[1][0] * D[2][2]) / det;
  Di[1][1] = (D[0][0] * D[2][2] - D[0][2] * D[2][0]) / det;
  Di[1][2] = (D[0][2] * D[1][0] - D[0][0] * D[1][2]) / det;
  Di[2][0] = (D[1][0] * D[2][1] - D[1][1] * D[2][0]) / det;
  Di[2][1] = (D[0][1] * D[2][0] - D[0][0] * D[2][1]) / det;
  Di[2][2] = (D[0][0] * D[1][1] - D[0][1] * D[1][0]) / det;
#endif
  for (int a = 0; a < DIM; a++)
    for (int b = 0; b < DIM; b++) {
      double v = 0.0;
      for (int k = 0; k < DIM; k++) v += B[a][k] * Di[k][b];
      C[DIM * a + b] = v;
    }
}

/* the G2P "stencil" of the multilinear kernel with an affine or Taylor grid
 * velocity where it has no fast one: the general stencil, and the affine
 * matrix fitted from the grid (transfer/affine_fit.h: the kernel's own
 * B D^-1 vanishes on grid lines); the fast linear stencil fits it too */
#ifndef MRN_SUP_LINEAR_FIT
#define MRN_SUP_LINEAR_FIT 1
#endif

/* what G2P needs that does not change from particle to particle */
typedef struct KNAME(g2p_args) {
  const mrn_grid *g;
  mrn_particles *ps;
  const mrn_kernel_options *ko;
  double dt, X;
  double *dx;
  const double *gstar;
  mrn_velocity_update_kind vu;
  mrn_position_update_kind xu;
  double mass_floor;
} KNAME(g2p_args);

/* G2P of one particle; with `fused` the velocity gradient from the updated
 * grid velocity is written to Lout on the way (the same stencil). With
 * `want_dv` the grid velocity before the update V is gathered too, for the
 * change dv = sum N (V~ - V) = a_p dt of FLIP's and XPIC's updates (000,
 * Eq. 33; the grid keeps no acceleration); PIC and APIC (X = 0) do without
 * it. `kind` (MRN_FAST_*, 0: the general stencil, MRN_SUP_LINEAR_FIT), `gvk`,
 * `fused` and `want_dv` are constants at every call; uGIMP's fast form
 * takes no affine grid velocity (its D is not a constant). */
MRN_INLINE void KNAME(g2p_particle)(const KNAME(g2p_args) *ar, size_t p, double *Lout, const int kind, const int gvk,
                                    const int fused, const int want_dv) {
  const mrn_grid *g = ar->g;
  mrn_particles *ps = ar->ps;
  const double dt = ar->dt, X = ar->X;
  const mrn_velocity_update_kind vu = ar->vu;
  /* the linear kernel's affine matrix is fitted: no B, D or L for it */
  const int linear = (kind == MRN_SUP_LINEAR_FIT || kind == MRN_FAST_LINEAR) && gvk != MRN_VGRID_PLAIN;
  const int want_bd = gvk == MRN_VGRID_AFFINE, want_l = gvk == MRN_VGRID_TAYLOR || fused;
  double *x = ps->x + 3 * p;
  double *v = ps->v + 3 * p;
  double v_pic[3] = {0, 0, 0}, v_old[3] = {0, 0, 0}, v_star[3] = {0, 0, 0};
  double B[DIM][DIM] = {{0}}, D[DIM][DIM] = {{0}}, L[DIM][DIM] = {{0}};
  if (fused) {
    /* the material update reads these once the chunk's gradients are
     * formed: ask for them now, into the second-level cache */
    __builtin_prefetch(ps->F + TSTRIDE * p, 1, 2);
    __builtin_prefetch(ps->stress + 6 * p, 1, 2);
    __builtin_prefetch(ps->strain + 6 * p, 1, 2);
    if (ps->state_stride) __builtin_prefetch(ps->state + (size_t)ps->state_stride * p, 1, 2);
  }
  if (gvk == MRN_VGRID_AFFINE) __builtin_prefetch(ps->affine + TSTRIDE * p, 1);
  KNAME(axes) ax;
  if (kind >= MRN_FAST_LINEAR && KNAME(axes_build)(g, kind, ar->ko->boundary, x, MRN_FAST_VOL0(kind, ps, p), &ax)) {
    KNAME(gather_fast)(&ax, g->vel_new, g->vel, g->stride[1], g->stride[2], MRN_FAST_SUPPORT(kind), 1, want_dv,
                       want_bd && !linear, fused || (want_l && !linear), v_pic, v_old, B, L);
    if (gvk == MRN_VGRID_AFFINE && !linear) {
      /* the full B-spline's D = sum N (x_i - x_p) (x)(x_i - x_p) is h^2/4 I
       * (quadratic) or h^2/3 I (cubic) wherever the particle is */
      const double dinv = (kind == MRN_FAST_QUADRATIC ? 4.0 : 3.0) * g->inv_cell * g->inv_cell;
      double *C = ps->affine + TSTRIDE * p;
      for (int a = 0; a < DIM; a++)
        for (int b = 0; b < DIM; b++) C[DIM * a + b] = B[a][b] * dinv;
    }
  } else {
    KNAME(stencil) s;
    KNAME(stencil_build)(g, ar->ko, x, ps->vol0[p], &s);
    KNAME(gather_general)(&s, g->vel_new, want_dv ? g->vel : NULL, ar->gstar, 1, want_bd && !linear,
                          fused || (want_l && !linear), v_pic, v_old, v_star, B, D, L);
    if (gvk == MRN_VGRID_AFFINE && !linear) KNAME(apic_matrix)(B, D, ps->affine + TSTRIDE * p);
  }
  if (fused) KNAME(store_matrix)(L, Lout);
  if (linear) /* its D vanishes on grid lines: transfer/affine_fit.h */
    mrn_affine_fit(g, ar->ko, DIM, ar->mass_floor, x, ps->affine + TSTRIDE * p);
  else if (gvk == MRN_VGRID_TAYLOR) KNAME(store_tensor)(L, ps->affine + TSTRIDE * p); /* (000, Eq. 22), updated V */
  double step[3] = {0, 0, 0};
  for (int d = 0; d < DIM; d++) {
    if (!want_dv) {
      /* PIC and APIC (X = 0, no XPIC): v = v_pic, and both the grid and the
       * particle position updates move by v_pic dt */
      v[d] = v_pic[d];
      step[d] = v_pic[d] * dt;
      continue;
    }
    const double dv = v_pic[d] - v_old[d]; /* a_p dt */
    double v_new;
    if (vu == MRN_VUPDATE_XPIC) {
      v_new = v_star[d] + dv; /* (000, Eq. 40): V - (I - G P)^m V = G V* */
    } else {
      double v_flip = v[d] + dv;                 /* (000, Eq. 33) */
      v_new = X * v_flip + (1.0 - X) * v_pic[d]; /* (000, Eqs. 31, 37) */
    }
    switch (ar->xu) {
    case MRN_XUPDATE_GRID: step[d] = v_pic[d] * dt; break;  /* (000, Eq. 32) */
    case MRN_XUPDATE_PARTICLE: step[d] = v_new * dt; break; /* (000, Eqs. 36, 38) */
    case MRN_XUPDATE_XPIC:                                  /* (000, Eq. 41) */
      step[d] = dt * (v_pic[d] - 0.5 * dv - 0.5 * (v[d] - v_star[d]));
      break;
    }
    v[d] = v_new;
  }
  if (ar->dx) {
    for (int d = 0; d < 3; d++) ar->dx[3 * p + d] = step[d];
  } else {
    for (int d = 0; d < DIM; d++) x[d] += step[d];
  }
}

/* Every G2P instance: stencil (0: the general one; MRN_SUP_LINEAR_FIT: the
 * general one with the fitted affine matrix; MRN_FAST_*), grid velocity
 * (mrn_grid_velocity_kind), gradient handed on (fused), change of the grid
 * velocity gathered (dv); one instance each (g2p_particle with these
 * constants in a chunked loop), named and tabled from this list. */
#define MRN_G2P_VARIANTS_GV(X, KIND, GV) X(KIND, GV, 0, 0) X(KIND, GV, 1, 0) X(KIND, GV, 0, 1) X(KIND, GV, 1, 1)
#define MRN_G2P_VARIANTS_OF(X, KIND) \
  MRN_G2P_VARIANTS_GV(X, KIND, PLAIN) MRN_G2P_VARIANTS_GV(X, KIND, AFFINE) MRN_G2P_VARIANTS_GV(X, KIND, TAYLOR)
#define MRN_G2P_VARIANTS(X)                                                                                   \
  MRN_G2P_VARIANTS_OF(X, 0) MRN_G2P_VARIANTS_GV(X, 1, AFFINE) MRN_G2P_VARIANTS_GV(X, 1, TAYLOR)              \
  MRN_G2P_VARIANTS_OF(X, 2) MRN_G2P_VARIANTS_OF(X, 3) MRN_G2P_VARIANTS_OF(X, 4) MRN_G2P_VARIANTS_GV(X, 5, PLAIN) \
  MRN_G2P_VARIANTS_GV(X, 5, TAYLOR)

typedef long (*KNAME(g2p_fn))(const KNAME(g2p_args) *, const mrn_gradient_sink *, double *,
                              const mrn_particle_pass *, long *);

#define MRN_G2P_INSTANCE(KIND, GV, FUSED, DV)                                                                      \
  static long KNAME(g2p_##KIND##_##GV##_##FUSED##DV)(const KNAME(g2p_args) * ar, const mrn_gradient_sink *sink,     \
                                                    double *sink_seconds, const mrn_particle_pass *after,           \
                                                    long *after_bad) {                                              \
    MRN_CHUNKED_LOOP((long)ar->ps->n, FUSED,                                                                       \
                     KNAME(g2p_particle)(ar, (size_t)p, L + (FUSED ? 9 * (p - lo) : 0), KIND, MRN_VGRID_##GV, FUSED, \
                                         DV))                                                                       \
  }
MRN_G2P_VARIANTS(MRN_G2P_INSTANCE)
#undef MRN_G2P_INSTANCE

typedef struct KNAME(g2p_variant) {
  int kind;
  mrn_grid_velocity_kind gv;
  int fused, dv;
  KNAME(g2p_fn) run;
} KNAME(g2p_variant);

#define MRN_G2P_ENTRY(KIND, GV, FUSED, DV) {KIND, MRN_VGRID_##GV, FUSED, DV, KNAME(g2p_##KIND##_##GV##_##FUSED##DV)},
static const KNAME(g2p_variant) KNAME(g2p_variants)[] = {MRN_G2P_VARIANTS(MRN_G2P_ENTRY)};
#undef MRN_G2P_ENTRY

static KNAME(g2p_fn) KNAME(g2p_pick)(int kind, mrn_grid_velocity_kind gv, int fused, int dv) {
  const size_t count = sizeof KNAME(g2p_variants) / sizeof KNAME(g2p_variants)[0];
  for (size_t k = 0; k < count; k++) {
    const KNAME(g2p_variant) *v = &KNAME(g2p_variants)[k];
    if (v->kind == kind && v->gv == gv && v->fused == (fused != 0) && v->dv == (dv != 0)) return v->run;
  }
  return NULL;
}

static long KNAME(g2p_any)(mrn_transfer *tr, double dt, double *dx, const mrn_gradient_sink *sink,
                           const mrn_particle_pass *after, long *after_bad) {
  if (mrn_shape_tracks_domain(tr->kernel.shape)) return mrn_cpdi_g2p_then(tr, dt, dx, sink, after, after_bad);
  const double t0 = mrn_phase_begin();
  const mrn_kernel_options ko = tr->kernel;
  const mrn_scheme *sc = tr->scheme;
  /* XPIC's smoothed velocity is gathered by the general form only */
  int kind = sc->velocity_update == MRN_VUPDATE_XPIC ? 0 : KNAME(fast_kind)(&ko);
  if (kind == MRN_FAST_GIMP && sc->grid_velocity == MRN_VGRID_AFFINE) kind = 0; /* its D is not a constant */
  if (!kind && ko.shape == MRN_SHAPE_LINEAR && sc->grid_velocity != MRN_VGRID_PLAIN) kind = MRN_SUP_LINEAR_FIT;
  const mrn_velocity_update_kind vu = sc->velocity_update;
  KNAME(g2p_args) ar = {tr->grid, tr->particles, &ko, dt,
                        vu == MRN_VUPDATE_FLIP ? 1.0 : vu == MRN_VUPDATE_BLEND ? sc->flip_fraction : 0.0, dx,
                        vu == MRN_VUPDATE_XPIC ? tr->grid->vel_star : NULL, vu, sc->position_update,
                        tr->mass_floor};
  /* the change of the grid velocity, only where the update uses it */
  const int dv = ar.X > 0.0 || vu == MRN_VUPDATE_XPIC || sc->position_update == MRN_XUPDATE_XPIC;
  double spent = 0.0;
  const long bad = KNAME(g2p_pick)(kind, sc->grid_velocity, sink != NULL, dv)(&ar, sink, &spent, after, after_bad);
  mrn_phase_end_split(MRN_PHASE_G2P, sink ? sink->phase : MRN_PHASE_G2P, t0, spent,
                      tr->particles->n > MRN_OMP_MIN_ITEMS);
  return bad;
}

void KNAME(mrn_g2p)(mrn_transfer *tr, double dt, double *dx) { KNAME(g2p_any)(tr, dt, dx, NULL, NULL, NULL); }

long KNAME(mrn_g2p_then)(mrn_transfer *tr, double dt, double *dx, const mrn_gradient_sink *sink,
                         const mrn_particle_pass *after, long *after_bad) {
  return KNAME(g2p_any)(tr, dt, dx, sink, after, after_bad);
}

/* ---- XPIC's projections -------------------------------------------------------------- */

void KNAME(mrn_grid_to_particles)(mrn_transfer *tr, const double *gvel, double *pvel) {
  if (mrn_shape_tracks_domain(tr->kernel.shape)) {
    mrn_cpdi_grid_to_particles(tr, gvel, pvel);
    return;
  }
  const mrn_grid *g = tr->grid;
  const mrn_particles *ps = tr->particles;
  const mrn_kernel_options ko = tr->kernel;
  const long n = (long)ps->n;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    KNAME(stencil) s;
    KNAME(stencil_build)(g, &ko, ps->x + 3 * p, ps->vol0[p], &s);
    double v[3] = {0, 0, 0};
    for (int c = 0; c < s.count; c++)
      for (int d = 0; d < DIM; d++) v[d] += s.N[c] * gvel[3 * s.node[c] + d];
    for (int d = 0; d < 3; d++) pvel[3 * p + d] = v[d];
  }
}

void KNAME(mrn_particles_to_grid)(mrn_transfer *tr, const double *pvel, double *gvel) {
  if (mrn_shape_tracks_domain(tr->kernel.shape)) {
    mrn_cpdi_particles_to_grid(tr, pvel, gvel);
    return;
  }
  const mrn_grid *g = tr->grid;
  const mrn_particles *ps = tr->particles;
  const mrn_kernel_options ko = tr->kernel;
  memset(gvel, 0, 3 * g->n * sizeof(double));
  KNAME(stencil) s;
  for (size_t p = 0; p < ps->n; p++) {
    KNAME(stencil_build)(g, &ko, ps->x + 3 * p, ps->vol0[p], &s);
    for (int c = 0; c < s.count; c++) {
      const double wm = s.N[c] * ps->mass[p];
      for (int d = 0; d < DIM; d++) gvel[3 * s.node[c] + d] += wm * pvel[3 * p + d];
    }
  }
  for (size_t i = 0; i < g->n; i++) {
    double m = g->mass[i];
    for (int d = 0; d < 3; d++) gvel[3 * i + d] = m > tr->mass_floor ? gvel[3 * i + d] / m : 0.0;
  }
}

#undef MRN_P2G_VARIANTS
#undef MRN_GRADIENT_VARIANTS
#undef MRN_UPDATE_FORCE_VARIANTS
#undef MRN_G2P_VARIANTS_OF
#undef MRN_G2P_VARIANTS_GV
#undef MRN_P2G_VARIANTS_OF
#undef MRN_G2P_VARIANTS
#undef MRN_CHUNKED_LOOP
#undef MRN_INLINE
#undef MRN_FAST_VOL0
#undef TSTRIDE
