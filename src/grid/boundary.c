#include "grid/boundary.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "grid/wall.h"

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

/* Apply one face condition (not friction: see mrn_contact_apply) to the node
 * velocity v (3 components); `axis` is the face normal axis. */
static void apply_face(const mrn_face_bc *f, double *v, int axis) {
  switch (f->kind) {
  case MRN_BC_VELOCITY:
    v[0] = f->velocity[0];
    v[1] = f->velocity[1];
    v[2] = f->velocity[2];
    return;
  case MRN_BC_FIXED:
    v[0] = v[1] = v[2] = 0.0;
    return;
  case MRN_BC_SLIP:
    v[axis] = 0.0;
    return;
  default:
    return;
  }
}

/* the index of node l of the column */
static inline size_t column_node(const mrn_contact_column *c, int l) {
  return c->nodes ? c->nodes[l] : (size_t)((long)c->first + l * c->step);
}

/* node n counts in the column's sums: above the mass floor (lighter nodes
 * are empty, or hold a kernel's negative weight with `wls`) and, in a
 * shared column, on this process's rows */
static inline int column_sums(const mrn_contact_column *c, const mrn_grid *g, double mass_floor, size_t n) {
  return g->mass[n] > mass_floor && (!c->shared || mrn_grid_owns(g, (long)n));
}

double mrn_contact_push(const mrn_contact_column *c, const mrn_grid *g, double mass_floor, const double *vel) {
  double N = 0.0;
  for (int l = 0; l < c->count; l++) {
    const size_t n = column_node(c, l);
    if (!column_sums(c, g, mass_floor, n)) continue;
    const double *v = vel + 3 * n;
    /* a face's (m v) n_axis as one product: a compiler that fuses the
     * multiply-add then rounds as it always did */
    if (c->axis >= 0) N += g->mass[n] * (v[c->axis] - c->w[c->axis]) * c->n[c->axis];
    else N += g->mass[n] * ((v[0] - c->w[0]) * c->n[0] + (v[1] - c->w[1]) * c->n[1] + (v[2] - c->w[2]) * c->n[2]);
  }
  return N;
}

int mrn_contact_held(double N, int with_friction, int touching, unsigned char *state, unsigned char bit) {
  const int held = touching && (N > 0.0 || (!with_friction && (*state & bit)));
  if (with_friction) *state = (unsigned char)(held ? *state | bit : *state & ~bit);
  return held;
}

void mrn_contact_hold(const mrn_contact_column *c, const mrn_grid *g, double mass_floor, double *vel, double J[3]) {
  for (int l = 0; l < c->count; l++) {
    const size_t n = column_node(c, l);
    if (!(g->mass[n] > mass_floor)) continue;
    const int books = mrn_grid_owns(g, (long)n); /* once over the processes */
    double *v = vel + 3 * n;
    const double vn = (v[0] - c->w[0]) * c->n[0] + (v[1] - c->w[1]) * c->n[1] + (v[2] - c->w[2]) * c->n[2];
    for (int d = 0; d < 3; d++)
      if (c->n[d] != 0.0) { /* a face's tangential components stay untouched, the sign of a zero included */
        v[d] -= vn * c->n[d];
        if (books) J[d] -= g->mass[n] * vn * c->n[d];
      }
  }
}

void mrn_contact_slide_sums(const mrn_contact_column *c, const mrn_grid *g, double mass_floor, const double *vel,
                            double MP[4]) {
  for (int k = 0; k < 4; k++) MP[k] = 0.0;
  for (int l = 0; l < c->count; l++) {
    const size_t n = column_node(c, l);
    if (!column_sums(c, g, mass_floor, n)) continue;
    MP[0] += g->mass[n];
    for (int d = 0; d < 3; d++) MP[1 + d] += g->mass[n] * (vel[3 * n + d] - c->w[d]);
  }
}

/* The normal impulse that bounds a column's friction in V~: Coulomb's law
 * bounds the tangential impulse by mu times the whole normal one of the
 * step, and the face acts in it more than once: in V~ (N) and, before, in
 * the holds of the first V and of XPIC's smoothed fields (held: their sum,
 * each with its weight in V*, signed: a column held while a field moves it
 * away is pulled). The holds reach the particles in the share hold_share of
 * the velocity update (mrn_hold_share, solver/step.c: PIC-like updates take
 * V~ whole, FLIP only V~ - V, which a hold does not change); only that
 * share is an impulse on the material. Counting N alone let the material a
 * PIC-like update brings towards the face each step, stopped in V, press
 * without friction: a sliding layer one cell thick decelerated at
 * 0.92 mu g. */
double mrn_contact_bound(double N, double held, double hold_share) { return fmax(0.0, N + hold_share * held); }

double mrn_contact_slide(const mrn_contact_column *c, const mrn_grid *g, double mass_floor, double *vel, double mu,
                         double N, const double MP[4], double J[3]) {
  const double M = MP[0];
  double P[3] = {MP[1], MP[2], MP[3]};
  /* what is left of the normal part is round-off (none on a face) */
  const double Pn = P[0] * c->n[0] + P[1] * c->n[1] + P[2] * c->n[2];
  if (Pn != 0.0)
    for (int d = 0; d < 3; d++) P[d] -= Pn * c->n[d];
  const double pt = sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
  if (mu <= 0.0 || pt <= 0.0) return 0.0;
  const double Jt = fmin(mu * N, pt);
  double work = 0.0;
  for (int l = 0; l < c->count; l++) {
    const size_t n = column_node(c, l);
    if (!(g->mass[n] > mass_floor)) continue;
    const int books = mrn_grid_owns(g, (long)n); /* once over the processes */
    for (int d = 0; d < 3; d++) {
      const double dv = -Jt * P[d] / (pt * M);
      vel[3 * n + d] += dv;
      if (!books) continue;
      work += g->mass[n] * dv * (vel[3 * n + d] - c->w[d]);
      J[d] += g->mass[n] * dv;
    }
  }
  return work;
}

/* A unilateral contact (Signorini) with Coulomb friction on one column
 * (Bardenhagen et al. 2000, with the face or wall as a rigid second body;
 * see doc/numerics.md, "Friction faces" and "Rigid walls").
 *
 * With friction (the updated velocity V~, once the forces of the step are
 * known) the column is in contact when its normal momentum points into the
 * obstacle, N > 0: N is removed and friction bounds the tangential impulse
 * by mu N. A column moving away is left free, so the obstacle never pulls.
 * The outcome is kept in the column's contact bit.
 *
 * Without friction (the velocity V of P2G, for the stress update) the
 * column is held, its normal velocity removed, when it moves into the
 * obstacle or when it ended the last step in contact.
 * Either way only a column the material touches can be held: material away
 * from the obstacle moves freely until it reaches it. V carries the
 * particles' own velocities (FLIP keeps what the grid does not show), so a
 * column resting on the obstacle can seem to leave it before the forces have
 * acted; letting it go then, and catching it again in V~, gave the stress
 * update a velocity field the step did not follow. Separation is decided with
 * the forces, in V~.
 *
 * Friction: the column's tangential momentum relative to the obstacle, P_t,
 * is reduced by min(mu N, |P_t|) along -P_t, the same velocity change for
 * every node (the column's mean relative velocity never reverses); the
 * frictional work is sum m dV . (V_after - w) (000, Eq. 66, in the
 * obstacle's frame). N is the step's whole normal impulse: that of V~ and
 * the share of the step's holds that reaches the particles
 * (mrn_contact_bound). `held` (may be NULL), the column's memory of the
 * step's holds: a call without friction adds its hold with `weight`, the
 * call with friction reads it. */
double mrn_contact_apply(const mrn_contact_column *c, mrn_grid *g, double mass_floor, double *vel, double mu,
                         int with_friction, int touching, unsigned char *state, unsigned char bit, double J[3],
                         double *held, double weight, double hold_share) {
  const double N = mrn_contact_push(c, g, mass_floor, vel);
  const int in_contact = mrn_contact_held(N, with_friction, touching, state, bit);
  if (held && in_contact && !with_friction) *held += weight * N;
  if (!in_contact) return 0.0;
  double scratch[3] = {0.0, 0.0, 0.0}, MP[4];
  if (!J) J = scratch;
  mrn_contact_hold(c, g, mass_floor, vel, J);
  if (!with_friction) return 0.0;
  mrn_contact_slide_sums(c, g, mass_floor, vel, MP);
  const double bound = mrn_contact_bound(N, held ? *held : 0.0, hold_share);
  return mrn_contact_slide(c, g, mass_floor, vel, mu, bound, MP, J);
}

/* the node index range [lo, hi] of the layers on and beyond one face
 * (domain numbering; zero extent along unused axes) */
static void face_layers(const mrn_grid *g, int axis, int side, int lo[3], int hi[3]) {
  for (int d = 0; d < 3; d++) {
    lo[d] = d < g->dim ? -g->pad : 0;
    hi[d] = d < g->dim ? g->ncell[d] + g->pad : 0;
  }
  lo[axis] = side == 0 ? -g->pad : g->ncell[axis];
  hi[axis] = side == 0 ? 0 : g->ncell[axis] + g->pad;
}

/* 1 when a particle at x of half side r lies over the cell-sized patch of
 * a face or wall centred at c along the surface coordinate: their extents
 * overlap by more than round-off (a regular lattice of particles has its
 * extents end exactly on the patches' edges) */
int mrn_contact_over_patch(double x, double c, double r, double cell) {
  return fabs(x - c) < r + 0.5 * cell - 1e-9 * cell;
}

/* 1 when the particle at x, of half side r, lies over the patch of face
 * node (i, j, k) of a face normal to `axis` */
static int face_over(const mrn_grid *g, const double *x, double r, int axis, int i, int j, int k) {
  const int ijk[3] = {i, j, k};
  for (int d = 0; d < g->dim; d++)
    if (d != axis && !mrn_contact_over_patch(x[d], g->origin[d] + ijk[d] * g->cell, r, g->cell)) return 0;
  return 1;
}

/* Visit the face nodes of face `face` within `reach` cells of a particle at
 * x, of half side r, whose columns its momentum lands in. A particle on the
 * face (`on`) marks them touched (with `held_only`, only those whose column
 * ended the last step in contact), and in `marks` (may be NULL) those whose
 * patch it lies over. A particle above the face marks in `marks` those
 * whose patch it lies over. */
static void touch_visit(mrn_grid *g, unsigned char *marks, const double *x, double r, int face, double reach, int on,
                        int held_only) {
  const int axis = face / 2;
  const unsigned char bit = (unsigned char)(1u << face);
  int lo[3], hi[3];
  mrn_grid_reach_box(g, x, reach, lo, hi);
  lo[axis] = hi[axis] = face % 2 == 0 ? 0 : g->ncell[axis]; /* the face nodes only */
  for (int k = lo[2]; k <= hi[2]; k++)
    for (int j = lo[1]; j <= hi[1]; j++)
      for (int i = lo[0]; i <= hi[0]; i++) {
        const size_t n = mrn_grid_index(g, i, j, k);
        const int above = face_over(g, x, r, axis, i, j, k);
        if (on && (!held_only || (g->contact[n] & bit))) {
          g->touch[n] |= bit;
          if (above && marks) marks[n] |= bit;
        } else if (!on && above) {
          marks[n] |= bit;
        }
      }
}

/* the index box [lo, hi] of one face's face nodes */
static void face_nodes(const mrn_grid *g, int face, int lo[3], int hi[3]) {
  face_layers(g, face / 2, face % 2, lo, hi);
  lo[face / 2] = hi[face / 2] = face % 2 == 0 ? 0 : g->ncell[face / 2];
}

/* a new step on one face: the touch bits of its face nodes and their memory
 * of the holds cleared */
static void touch_clear(mrn_grid *g, int face) {
  int lo[3], hi[3];
  face_nodes(g, face, lo, hi);
  for (int k = lo[2]; k <= hi[2]; k++)
    for (int j = lo[1]; j <= hi[1]; j++)
      for (int i = lo[0]; i <= hi[0]; i++) {
        const size_t n = mrn_grid_index(g, i, j, k);
        g->touch[n] &= (unsigned char)~(1u << face);
        g->held[n] = 0.0;
      }
}

/* gap_check's release on one face: a column whose patch material above the
 * face lies over (`clear`), and no material on the face (`over`), has
 * material standing clear of it and is not touched (doc/numerics.md,
 * "Rolling") */
static void touch_release(mrn_grid *g, int face, const unsigned char *over, const unsigned char *clear) {
  const unsigned char bit = (unsigned char)(1u << face);
  int lo[3], hi[3];
  face_nodes(g, face, lo, hi);
  for (int k = lo[2]; k <= hi[2]; k++)
    for (int j = lo[1]; j <= hi[1]; j++)
      for (int i = lo[0]; i <= hi[0]; i++) {
        const size_t n = mrn_grid_index(g, i, j, k);
        if (clear[n] & ~over[n] & bit) g->touch[n] &= (unsigned char)~bit;
      }
}

/* How far, in initial half sides, a particle's extent may stand off a face
 * and keep a contact it has: a body resting on a face sits with its
 * particles' half sides just on it, and without this slack vibrations of a
 * fraction of a micrometre made its contact flicker and friction act only
 * part of the time (a block sliding 3 % too fast). A new contact needs the
 * material on the face: a column caught within the slack holds the material
 * where it is, above the face, so a vibrating block that lifted off was
 * caught higher each time and climbed by the slack. */
#define MRN_TOUCH_SLACK 0.5

/* the distance of x from face `face` less the half side r */
static double face_gap(const mrn_grid *g, const double *x, int face, double r) {
  const int axis = face / 2;
  const double lo = g->origin[axis], hi = lo + g->size[axis];
  return (face % 2 == 0 ? x[axis] - lo : hi - x[axis]) - r;
}

int mrn_boundary_touch(const mrn_boundary *bc, mrn_grid *g, double reach, const double *x, const double *vol0, size_t n,
                       mrn_marks_share share, void *ctx) {
  int faces[MRN_FACE_COUNT], nf = 0;
  for (int f = 0; f < 2 * g->dim; f++)
    if (bc->face[f].kind == MRN_BC_FRICTION) faces[nf++] = f;
  if (!nf) return MRN_OK;
  if (!g->held && !(g->held = calloc(g->n, sizeof *g->held))) return mrn_error("friction faces: out of memory");
  for (int k = 0; k < nf; k++) touch_clear(g, faces[k]);
  /* bit 1 << face of over[]: material on the face lies over the column, of
   * clear[]: material above the face does; for the faces with gap_check */
  int check = 0;
  for (int k = 0; k < nf; k++) check |= bc->face[faces[k]].gap_check;
  unsigned char *over = check ? calloc(2 * g->n, 1) : NULL, *clear = over ? over + g->n : NULL;
  int rc = check && !over ? mrn_error("friction faces: out of memory for gap_check") : MRN_OK;
  for (size_t p = 0; p < n && rc == MRN_OK; p++) {
    /* half the particle's initial side, as uGIMP's (transfer/stencil.h) */
    const double r = 0.5 * (g->dim == 2 ? sqrt(vol0[p]) : cbrt(vol0[p]));
    for (int k = 0; k < nf; k++) {
      const double gap = face_gap(g, x + 3 * p, faces[k], r);
      if (gap <= MRN_TOUCH_SLACK * r) touch_visit(g, over, x + 3 * p, r, faces[k], reach, 1, gap > 0.0);
      if (clear && bc->face[faces[k]].gap_check && gap > 0.0 && gap + r < reach * g->cell)
        touch_visit(g, clear, x + 3 * p, r, faces[k], reach, 0, 0);
    }
  }
  /* the release needs every particle's marks */
  if (check && share) rc = share(ctx, over, 2, rc);
  for (int k = 0; k < nf && rc == MRN_OK; k++)
    if (bc->face[faces[k]].gap_check) touch_release(g, faces[k], over, clear);
  free(over);
  return rc;
}

/* one friction face, column by column: the face node and the ghost nodes
 * beyond it along the normal stand for the same point of the face and share
 * one contact, whose bit 1 << face is kept at the face node in g->contact.
 * The holds of the step are added up in g->held (cleared by the touch) with
 * their weight in what reaches the particles: 1 for the velocity V (the
 * grid's), pass_weight for XPIC's smoothed fields; V~ reads them. A
 * re-map's V (MUSL, USAVG) adds after V~ has read, and the next touch
 * clears it. */
static double apply_friction_face(const mrn_face_bc *f, mrn_grid *g, double mass_floor, double *vel, int axis, int side,
                                  int with_friction, const mrn_boundary *bc) {
  const double weight = with_friction ? 0.0 : vel == g->vel ? 1.0 : bc->pass_weight;
  int lo[3], hi[3];
  face_layers(g, axis, side, lo, hi);
  /* the columns start at the face node and run outwards */
  mrn_contact_column c = {.step = side == 0 ? -g->stride[axis] : g->stride[axis], .count = hi[axis] - lo[axis] + 1};
  c.n[axis] = side == 0 ? -1.0 : 1.0;
  c.axis = axis;
  const unsigned char bit = (unsigned char)(1u << (2 * axis + side));
  lo[axis] = hi[axis] = side == 0 ? 0 : g->ncell[axis];
  double work = 0.0;
  for (int k = lo[2]; k <= hi[2]; k++)
    for (int j = lo[1]; j <= hi[1]; j++)
      for (int i = lo[0]; i <= hi[0]; i++) {
        c.first = mrn_grid_index(g, i, j, k);
        /* a column lies on one row or on the first slab's: whole on the processes that hold it */
        work += mrn_contact_apply(&c, g, mass_floor, vel, f->mu, with_friction, (g->touch[c.first] & bit) != 0,
                                  g->contact + c.first, bit, NULL, g->held ? g->held + c.first : NULL, weight,
                                  bc->hold_share);
      }
  return work;
}

double mrn_boundary_apply(const mrn_boundary *bc, mrn_grid *g, double mass_floor, double *vel, int with_friction) {
  double work = 0.0;
  for (int axis = 0; axis < g->dim; axis++) {
    for (int side = 0; side < 2; side++) {
      const mrn_face_bc *f = &bc->face[2 * axis + side];
      if (f->kind == MRN_BC_FREE || f->kind == MRN_BC_PERIODIC) continue;
      if (f->kind == MRN_BC_FRICTION) {
        work += apply_friction_face(f, g, mass_floor, vel, axis, side, with_friction, bc);
        continue;
      }
      int lo[3], hi[3];
      face_layers(g, axis, side, lo, hi);
      for (int k = lo[2]; k <= hi[2]; k++)
        for (int j = lo[1]; j <= hi[1]; j++)
          for (int i = lo[0]; i <= hi[0]; i++) {
            size_t n = mrn_grid_index(g, i, j, k);
            if (g->mass[n] <= 0.0) continue;
            apply_face(f, vel + 3 * n, axis);
          }
    }
  }
  if (bc->walls) work += mrn_walls_apply(bc->walls, g, mass_floor, vel, with_friction, bc->hold_share, bc->pass_weight);
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
