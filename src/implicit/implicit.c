/* moraine: implicit energy-momentum consistent MPM step (see implicit.h). */
#include "implicit/implicit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/tensor.h"
#include "grid/wall.h"
#include "implicit/implicit_internal.h"
#include "solver/timestep.h"

void mrn_implicit_options_default(mrn_implicit_options *o) {
  o->mass = MRN_MASS_CONSISTENT;
  o->eps = 0.0;
  o->mapping = MRN_MAPPING_FLIP;
  o->tol = 1e-11;
  o->max_iter = 20;
  o->dt = 0.0;
  o->dt_factor = 5.0;
  o->min_node_mass = 1e-3;
  o->ghost = 0.0;
  o->bbar = 0;
  o->cutbacks = 0;
}

/* the law the integrator runs for material m: the finite-strain form its
 * type declares (material.h), whatever the model is in explicit runs */
static int material_of(const mrn_material *m, mrn_emc_material *out) {
  const mrn_implicit_form *form = m->type->implicit;
  if (!form) {
    char names[256];
    return mrn_error_code(MRN_ERR,
                          "implicit: material '%s' (%s) has no implicit form; materials with one: %s "
                          "(doc/implicit.md)",
                          m->name, m->type->name, mrn_material_implicit_names(names, sizeof names));
  }
  mrn_implicit_law law;
  form->law_of(m, &law);
  out->lambda = law.lambda;
  out->G = law.G;
  out->yield = law.yield;
  out->H = law.hardening;
  return 0;
}

void mrn_implicit_free(mrn_implicit *im) {
  if (!im) return;
  mrn_implicit_detach(im);
  free(im->st), free(im->res), free(im->diss), free(im->fpt), free(im->sten);
  free(im->dof), free(im->act), free(im->ijk), free(im->Kb), free(im->Mc), free(im->touched), free(im->ml), free(im->gmass);
  free(im->Gb), free(im->cellvol);
  free(im->bb), free(im->bb_of), free(im->bb_index), free(im->bb_slot);
  free(im->fdof), free(im->vfix), free(im->v0), free(im->u), free(im->fint), free(im->fext), free(im->p), free(im->r), free(im->du);
  mrn_csc_free(&im->A);
  free(im);
}

/* options in range, and a simulation the integrator can run; 0 or an error */
static int check_setup(const mrn_sim *sim, const mrn_implicit_options *o) {
  if (o->max_iter < 2 || o->max_iter > MRN_IMPLICIT_MAX_ITER || !(o->tol > 0) || o->eps < 0 || o->eps > 1 ||
      !(o->dt > 0 || o->dt_factor > 0) || !(o->min_node_mass >= 0 && o->min_node_mass < 1) ||
      !(o->ghost >= 0 && isfinite(o->ghost)) || o->cutbacks < 0 || o->cutbacks > MRN_IMPLICIT_MAX_CUTBACKS)
    return mrn_error_code(MRN_ERR, "implicit: invalid options (max_iter 2..%d, tol > 0, eps in [0, 1], dt or dt_factor "
                                   "> 0, ghost >= 0, cutbacks 0..%d)",
                          MRN_IMPLICIT_MAX_ITER, MRN_IMPLICIT_MAX_CUTBACKS);
  if (o->ghost > 0 && sim->shape != MRN_SHAPE_LINEAR && sim->shape != MRN_SHAPE_GIMP)
    /* the penalty on the jump of the first normal derivative is the one of
     * the linear (hat) grid basis; B-splines would need the jumps of higher
     * derivatives */
    return mrn_error_code(MRN_ERR, "implicit: ghost penalty: only the linear and gimp shape functions (hat grid basis) "
                                   "are supported, not '%s'",
                          mrn_shape_info_of(sim->shape)->name);
  for (int f = 0; f < 2 * sim->dim; f++) {
    mrn_bc_kind kind = sim->boundary.face[f].kind;
    if (kind == MRN_BC_FRICTION || kind == MRN_BC_PERIODIC)
      return mrn_error_code(MRN_ERR, "implicit: the %s face is '%s'; the implicit integrator takes free, slip, fixed "
                                     "and velocity faces",
                            mrn_face_name(f), mrn_bc_kind_name(kind));
  }
  if (sim->boundary.walls && sim->boundary.walls->count)
    return mrn_error_code(MRN_ERR, "implicit: the simulation has rigid walls (sim:add_wall), which the implicit "
                                   "integrator does not take");
  if (sim->shape == MRN_SHAPE_CUBIC_BSPLINE || mrn_shape_tracks_domain(sim->shape))
    return mrn_error_code(MRN_ERR, "implicit: shape = '%s' is not supported (use linear, gimp or quadratic_bspline)",
                          mrn_shape_info_of(sim->shape)->name);
  /* both belong to the explicit step (solver/step.c, solver/source.c) */
  if (sim->mass_scaling != 1.0 || sim->nsources > 0)
    return mrn_error_code(MRN_ERR, "implicit: mass scaling and inflow sources are explicit-only (mass_scaling = %g, "
                                   "%d source(s))", sim->mass_scaling, sim->nsources);
  return 0;
}

/* the laws of the materials, and the ghost penalty's modulus: the stiffest Young's modulus */
static int set_materials(mrn_implicit *im) {
  const mrn_sim *sim = im->sim;
  for (int i = 0; i < sim->nmaterials; i++)
    if (material_of(sim->materials[i], &im->mat[i])) return MRN_ERR;
  for (int i = 0; i < sim->nmaterials; i++) {
    double l = im->mat[i].lambda, G = im->mat[i].G;
    im->ghost_modulus = fmax(im->ghost_modulus, G * (3.0 * l + 2.0 * G) / (l + G));
  }
  return 0;
}

/* the per-point arrays and the node index; 0 or an error */
static int alloc_points(mrn_implicit *im) {
  size_t n = im->np;
  im->st = calloc(n ? n : 1, sizeof *im->st);
  im->res = calloc(n ? n : 1, sizeof *im->res);
  im->diss = calloc(n ? n : 1, sizeof *im->diss);
  im->fpt = calloc(3 * (n ? n : 1), sizeof *im->fpt);
  im->sten = malloc((n ? n : 1) * sizeof *im->sten);
  im->dof = malloc(im->sim->grid.n * sizeof *im->dof);
  if (!im->st || !im->res || !im->diss || !im->fpt || !im->sten || !im->dof)
    return mrn_error_code(MRN_ERR, "implicit: out of memory");
  return 0;
}

/* the node pairs reachable through one particle: offsets within R nodes */
static void set_reach(mrn_implicit *im) {
  const mrn_sim *sim = im->sim;
  int sup = mrn_shape_support(sim->shape);
  im->R = sup - 1;
  if (im->opt.ghost > 0 && im->R < 2) im->R = 2; /* the face jumps couple nodes two cells apart (ghost.c) */
  /* the points of one cell reach sup + 1 nodes per axis (bbar.c) */
  if (im->opt.bbar && im->R < sup) im->R = sup;
  im->W = 2 * im->R + 1;
  im->NR = im->dim == 3 ? im->W * im->W * im->W : im->W * im->W;
  int r = 0;
  for (int dk = (im->dim == 3 ? -im->R : 0); dk <= (im->dim == 3 ? im->R : 0); dk++)
    for (int dj = -im->R; dj <= im->R; dj++)
      for (int di = -im->R; di <= im->R; di++) {
        if (!di && !dj && !dk) im->rc = r;
        im->off[r++] = di * sim->grid.stride[0] + dj * sim->grid.stride[1] + (im->dim == 3 ? dk * sim->grid.stride[2] : 0);
      }
}

mrn_implicit *mrn_implicit_new(mrn_sim *sim, const mrn_implicit_options *o) {
  if (check_setup(sim, o)) return NULL;
  mrn_implicit *im = calloc(1, sizeof *im);
  if (!im) return NULL;
  im->sim = sim;
  im->opt = *o;
  im->load_factor = 1.0;
  im->dim = sim->dim;
  im->np = sim->particles.n;
  /* the points' history: from the particle fields a checkpoint or an earlier
   * integrator left, else b_e = F F^T (point_state.c) */
  if (set_materials(im) || alloc_points(im) || mrn_implicit_state_load(im)) {
    mrn_implicit_free(im);
    return NULL;
  }
  set_reach(im);
  return im;
}

int mrn_implicit_set_point_force(mrn_implicit *im, size_t p, const double f[3]) {
  if (p >= im->np) return mrn_error_code(MRN_ERR, "implicit: point force on particle %zu of %zu", p, im->np);
  for (int d = 0; d < 3; d++) im->fpt[3 * p + d] = d < im->dim ? f[d] : 0.0;
  return 0;
}

void mrn_implicit_set_load_factor(mrn_implicit *im, double factor) { im->load_factor = factor; }

void mrn_implicit_clear_point_forces(mrn_implicit *im) { memset(im->fpt, 0, 3 * im->np * sizeof *im->fpt); }

int mrn_implicit_next_dt(mrn_implicit *im, double *dt) {
  *dt = im->opt.dt > 0 ? im->opt.dt : im->opt.dt_factor * mrn_dt_grid_critical(im->sim); /* 001 Eq. 61 */
  if (!(*dt > 0) || !isfinite(*dt)) return mrn_error_code(MRN_ERR_STATE, "implicit: time step %s", mrn_num(*dt).s);
  return 0;
}

/* B: grid velocity from M~ v = p on the free components (001 Eq. 26), the
 * fixed ones holding their prescribed velocity: M~_ff v_f = p_f - M~_fc v_c;
 * and Newton's starting displacement u */
static int grid_velocity(mrn_implicit *im, double dt) {
  const mrn_sim *sim = im->sim;
  const size_t nact = im->nact;
  const int dim = im->dim;
  double *rhs = im->r, *sol = im->du;
  mrn_implicit_mass_multiply(im, im->vfix, im->fint); /* fint as scratch */
  for (size_t a = 0; a < nact; a++)
    for (int d = 0; d < dim; d++)
      if (im->fdof[dim * a + d] >= 0) rhs[im->fdof[dim * a + d]] = im->p[3 * a + d] - im->fint[3 * a + d];
  int rc = mrn_implicit_project_velocity(im, rhs, sol);
  if (rc) {
    char msg[512];
    snprintf(msg, sizeof msg, "%s", mrn_error_message());
    return mrn_error_code(rc, "step %ld (t = %g s): grid velocity projection: %s", sim->step + 1, sim->time, msg);
  }
  memset(im->v0, 0, 3 * nact * sizeof(double));
  memset(im->u, 0, 3 * nact * sizeof(double));
  for (size_t a = 0; a < nact; a++)
    for (int d = 0; d < dim; d++) {
      int f = im->fdof[dim * a + d];
      /* Newton starts from u = dt p / m_lumped: the consistent projection v_t
       * is badly determined at lightly supported nodes (huge or noisy values
       * that are harmless in M v_t but not as displacements), and a start
       * from dt v_t there leaves Newton stalling */
      if (f >= 0) im->v0[3 * a + d] = sol[f], im->u[3 * a + d] = dt * im->p[3 * a + d] / im->ml[a];
      else im->v0[3 * a + d] = im->vfix[3 * a + d], im->u[3 * a + d] = dt * im->vfix[3 * a + d];
    }
  return 0;
}

/* The kinetic energy PIC will lose in this step: the part of the point
 * velocities the grid cannot represent, sum m |v_p - N v_t|^2 / 2; with the
 * consistent mass FLIP keeps it (001 Eqs. 37-38). */
static double pic_loss_of(const mrn_implicit *im) {
  const mrn_particles *ps = &im->sim->particles;
  double pic_loss = 0.0;
  if (im->opt.mapping != MRN_MAPPING_PIC) return pic_loss;
  for (size_t q = 0; q < im->np; q++) {
    const mrn_implicit_stencil *s = &im->sten[q];
    double w[3] = {ps->v[3 * q], ps->v[3 * q + 1], ps->v[3 * q + 2]};
    for (int k2 = 0; k2 < s->count; k2++)
      for (int d = 0; d < im->dim; d++) w[d] -= s->N[k2] * im->v0[3 * (size_t)im->dof[s->node[k2]] + d];
    pic_loss += 0.5 * ps->mass[q] * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  }
  return pic_loss;
}

/* the Newton iteration's state over the active nodes' components */
typedef struct newton {
  double dt, c2;            /* c2 = 2 / dt^2 */
  double *tmp, *Mw, *uprev; /* u - dt v_t, M~ (u - dt v_t), the last full iterate */
  double resmax, scale;     /* max |r| over the free components, and the size of its terms */
  double rn_prev, alpha;    /* |r|_2 at the last full iterate, the line search's step */
  double err1;              /* f_err^(1) */
} newton;

/* C: the mid-point residual r = f_int + (2/dt^2) M~ (u - dt v_t) - f_ext
 * (001 Eqs. 20, 22-24) on the free components; returns |r|_2 */
static double residual(mrn_implicit *im, newton *nw) {
  const size_t nact = im->nact;
  const int dim = im->dim;
  mrn_implicit_assemble(im);
  for (size_t q = 0; q < 3 * nact; q++) nw->tmp[q] = im->u[q] - nw->dt * im->v0[q];
  mrn_implicit_mass_multiply(im, nw->tmp, nw->Mw);
  nw->scale = 0.0;
  nw->resmax = 0.0;
  for (size_t a = 0; a < nact; a++)
    for (int d = 0; d < dim; d++) {
      int f = im->fdof[dim * a + d];
      if (f < 0) continue;
      size_t q = 3 * a + (size_t)d;
      im->r[f] = im->fint[q] + nw->c2 * nw->Mw[q] - im->fext[q];
      nw->resmax = fmax(nw->resmax, fabs(im->r[f]));
      /* the size of the terms of r: forces and the inertia 2 p / dt */
      nw->scale = fmax(nw->scale, fmax(fmax(fabs(im->fint[q]), fabs(2.0 * im->p[q] / nw->dt)),
                                       fmax(fabs(nw->c2 * nw->Mw[q]), fabs(im->fext[q]))));
    }
  double rn = 0.0;
  for (int f = 0; f < im->nfree; f++) rn += im->r[f] * im->r[f];
  return sqrt(rn);
}

/* u = u_prev + alpha du on the free components */
static void move_along(mrn_implicit *im, const double *uprev, double alpha) {
  for (size_t a = 0; a < im->nact; a++)
    for (int d = 0; d < im->dim; d++) {
      int f = im->fdof[im->dim * a + d];
      if (f >= 0) im->u[3 * a + d] = uprev[3 * a + d] + alpha * im->du[f];
    }
}

/* 1 when iteration k (of the accepted iterate, its step alpha du) has
 * converged: on the relative measure f_err^(k) / f_err^(1) (001 §3.4), or
 * the residual is at round-off of the terms that make it (a body at rest, a
 * rigid translation) */
static int newton_done(const mrn_implicit *im, newton *nw, mrn_implicit_history *h, int k) {
  if (k == 0) return nw->resmax <= 1e-14 * nw->scale;
  double err = 0.0; /* f_err^(k) = sum |r^(k)| |du^(k)| (001 §3.4) */
  for (int f = 0; f < im->nfree; f++) err += fabs(im->r[f]) * fabs(nw->alpha * im->du[f]);
  if (k == 1) nw->err1 = err;
  double rel = nw->err1 > 0.0 ? err / nw->err1 : 0.0;
  h->err[k - 1] = rel, h->iterations = k;
  return (k >= 2 && rel < im->opt.tol) || nw->err1 == 0.0 || nw->resmax <= 1e-14 * nw->scale;
}

/* D: Newton-Raphson on the mid-point residual (001 Eqs. 20, 27, §3.4) from
 * the u of grid_velocity. Backtracking on |r|_2 (Armijo) keeps it on course
 * when the first full step overshoots; near the solution the full step is
 * always taken, so the convergence stays quadratic. 0 (*converged says
 * whether it converged) or an error of the linear solver. */
static int newton_solve(mrn_implicit *im, newton *nw, mrn_implicit_history *h, int *converged) {
  const size_t nact = im->nact;
  int rc = 0;
  nw->rn_prev = HUGE_VAL, nw->alpha = 1.0;
  for (int k = 0; k <= im->opt.max_iter;) {
    double rn = residual(im, nw);
    if (k >= 1 && rn > (1.0 - 1e-4 * nw->alpha) * nw->rn_prev && nw->alpha > 1.0 / 64 &&
        nw->resmax > 1e-12 * nw->scale) {
      nw->alpha *= 0.5;
      move_along(im, nw->uprev, nw->alpha);
      continue;
    }
    if (newton_done(im, nw, h, k)) {
      *converged = 1;
      break;
    }
    if (k == im->opt.max_iter) break;
    if ((rc = mrn_implicit_build_matrix(im, nw->c2, 1.0))) break;
    for (int f = 0; f < im->nfree; f++) im->r[f] = -im->r[f];
    if ((rc = mrn_linear_solve(&im->A, im->r, im->du))) break;
    memcpy(nw->uprev, im->u, 3 * nact * sizeof(double));
    nw->rn_prev = rn;
    nw->alpha = 1.0;
    k++;
    move_along(im, im->u, 1.0);
  }
  return rc;
}

/* The work of the forces that hold the fixed components: the residual
 * there, r_c = f_int + (2/dt^2) M~ (u - dt v_t) - f_ext, is the force they
 * exert, and u_c = dt v_c its displacement (0 for clamped components); Mw =
 * M~ (u - dt v_t) and f_int are those of the accepted iterate. */
static double constraint_work(const mrn_implicit *im, const newton *nw) {
  double work_con = 0.0;
  for (size_t a = 0; a < im->nact; a++)
    for (int d = 0; d < im->dim; d++) {
      const size_t q = 3 * a + (size_t)d;
      if (im->fdof[im->dim * a + d] < 0 && im->u[q] != 0.0)
        work_con += (im->fint[q] + nw->c2 * nw->Mw[q] - im->fext[q]) * im->u[q];
    }
  return work_con;
}

/* C and D for one attempt: 0 (*converged, the history and *work_con set) or an error */
static int solve_attempt(mrn_implicit *im, double dt, mrn_implicit_history *h, int *converged, double *work_con) {
  const size_t nact = im->nact;
  newton nw = {.dt = dt, .c2 = 2.0 / (dt * dt)};
  nw.tmp = malloc(3 * nact * sizeof(double));
  nw.Mw = malloc(3 * nact * sizeof(double));
  nw.uprev = malloc(3 * nact * sizeof(double));
  memset(h, 0, sizeof *h), h->dt = dt;
  int rc = !nw.tmp || !nw.Mw || !nw.uprev ? mrn_error_code(MRN_ERR, "implicit: out of memory")
                                          : newton_solve(im, &nw, h, converged);
  if (!rc) {
    *work_con = constraint_work(im, &nw);
    h->residual = nw.resmax;
  }
  free(nw.tmp), free(nw.Mw), free(nw.uprev);
  return rc;
}

/* E on one point: velocity by PIC or FLIP, position x += N u (001 Eqs. 28-30),
 * F = dF F_t (001 Eq. 25), and the state of the converged iterate mirrored
 * into the particle fields the output reads (im->p holds v_{t+dt}) */
static void update_point(mrn_implicit *im, size_t q) {
  mrn_particles *ps = &im->sim->particles;
  const int dim = im->dim;
  const mrn_implicit_stencil *s = &im->sten[q];
  double dF[9], vpic[3] = {0}, dv[3] = {0}, dx[3] = {0};
  mrn_implicit_point_increment(im, q, dF);
  for (int k2 = 0; k2 < s->count; k2++) {
    size_t a = (size_t)im->dof[s->node[k2]];
    for (int d = 0; d < dim; d++) {
      vpic[d] += s->N[k2] * im->p[3 * a + d];
      dv[d] += s->N[k2] * (im->p[3 * a + d] - im->v0[3 * a + d]);
      dx[d] += s->N[k2] * im->u[3 * a + d];
    }
  }
  for (int d = 0; d < dim; d++) {
    ps->v[3 * q + d] = im->opt.mapping == MRN_MAPPING_PIC ? vpic[d] : ps->v[3 * q + d] + dv[d];
    ps->x[3 * q + d] += dx[d];
  }
  mrn_emc_state *st = &im->st[q];
  const mrn_emc_result *re = &im->res[q];
  double F[9];
  mat_mul(dF, st->Ft, F);
  memcpy(st->Ft, F, sizeof F);
  memcpy(st->be, re->be, sizeof st->be);
  memcpy(st->tau, re->tau, sizeof st->tau);
  st->psi = re->psi;
  st->xi = re->xi;
  im->diss[q] += ps->vol0[q] * re->dissipation;
  mrn_tensor_pack(dim, F, ps->F + (size_t)mrn_tensor_stride(dim) * q);
  double J = mat_det(F);
  for (int a = 0; a < 3; a++)
    for (int c = a; c < 3; c++) ps->stress[6 * q + sym_index(a, c)] = re->tau[3 * a + c] / J;
  ps->e_elastic[q] = ps->vol0[q] * re->psi;
  ps->w_plastic[q] = -im->diss[q];
}

/* E: grid-to-particle mapping and update (001 Eqs. 23-25, 28-30) of a converged attempt */
static int finish_step(mrn_implicit *im, double dt) {
  mrn_sim *sim = im->sim;
  for (size_t q = 0; q < 3 * im->nact; q++) {
    double v1 = 2.0 * im->u[q] / dt - im->v0[q]; /* mid-point rule: u = dt (v_t + v_t+dt) / 2 */
    im->work_ext += im->fext[q] * im->u[q];
    im->p[q] = v1; /* reuse p for v_{t+dt} */
  }
  for (size_t q = 0; q < im->np; q++) update_point(im, q);
  mrn_implicit_state_store(im);
  sim->time += dt;
  sim->step++;
  sim->dt = dt;
  return mrn_sim_check_state(sim);
}

/* One attempt at a step of length dt. Nothing that outlives the step
 * (particles, accumulated energies) changes unless Newton converges:
 * *converged = 0 with return 0 leaves the state as it was, so that the step
 * can be tried again with a shorter dt. */
static int step_attempt(mrn_implicit *im, double dt, mrn_implicit_history *h, int *converged) {
  int rc;
  *converged = 0;
  if ((rc = mrn_implicit_setup_step(im))) return rc;
  mrn_implicit_map_to_grid(im);
  if ((rc = mrn_implicit_cell_volumes(im)) || (rc = mrn_implicit_ghost_build(im)) || (rc = mrn_implicit_bbar_setup(im)) ||
      (rc = grid_velocity(im, dt)))
    return rc;
  const double pic_loss = pic_loss_of(im);
  double work_con = 0.0;
  if ((rc = solve_attempt(im, dt, h, converged, &work_con)) || !*converged) return rc;
  im->pic_loss += pic_loss;
  im->ghost_work += mrn_implicit_ghost_work(im); /* the kinetic energy the penalty took in the step (ghost.c) */
  im->work_con += work_con;
  return finish_step(im, dt);
}

/* A step that does not converge in max_iter iterations is tried again with
 * half the time step, up to `cutbacks` times; the history is that of the
 * accepted attempt, with the cuts and the iterations the rejected attempts
 * spent. */
int mrn_implicit_step(mrn_implicit *im, mrn_implicit_history *h) {
  mrn_sim *sim = im->sim;
  if (sim->particles.n != im->np)
    return mrn_error_code(MRN_ERR, "implicit: the particle count changed (%zu -> %zu) after the integrator was made",
                          im->np, sim->particles.n);
  mrn_implicit_history local;
  if (!h) h = &local;
  double dt;
  int rc = mrn_implicit_next_dt(im, &dt), converged = 0, rejected = 0, cut = 0;
  if (rc) return rc;
  const double dt_first = dt;
  for (;; cut++, dt *= 0.5) {
    if ((rc = step_attempt(im, dt, h, &converged))) return rc;
    if (converged || cut == im->opt.cutbacks) break;
    rejected += h->iterations;
  }
  if (!converged) {
    char hist[256] = "";
    for (int q = 0, len = 0; q < h->iterations && len < 200; q++)
      len += snprintf(hist + len, sizeof hist - (size_t)len, " %s", mrn_num_digits(h->err[q], 2).s);
    char cuts[96] = "";
    if (cut > 0) snprintf(cuts, sizeof cuts, " after %d cutback%s from dt = %g s", cut, cut > 1 ? "s" : "", dt_first);
    return mrn_error_code(MRN_ERR_STATE, "implicit: step %ld (t = %g s, dt = %g s%s): Newton did not converge in %d "
                                         "iterations (f_err ratios:%s; tol %.3g, max |r| %s N)",
                          sim->step + 1, sim->time, dt, cuts, im->opt.max_iter, hist, im->opt.tol,
                          mrn_num_digits(h->residual, 3).s);
  }
  h->cuts = cut;
  h->rejected_iterations = rejected;
  return MRN_OK;
}

void mrn_implicit_energies(const mrn_implicit *im, mrn_implicit_energy *e) {
  const mrn_particles *ps = &im->sim->particles;
  memset(e, 0, sizeof *e);
  for (size_t q = 0; q < im->np; q++) {
    const double m = ps->mass[q], *v = ps->v + 3 * q, *x = ps->x + 3 * q;
    e->kinetic += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    e->strain += ps->vol0[q] * im->st[q].psi;
    e->dissipated += im->diss[q];
    for (int d = 0; d < 3; d++) e->momentum[d] += m * v[d];
    e->angular[0] += m * (x[1] * v[2] - x[2] * v[1]);
    e->angular[1] += m * (x[2] * v[0] - x[0] * v[2]);
    e->angular[2] += m * (x[0] * v[1] - x[1] * v[0]);
  }
  e->external_work = im->work_ext;
  e->constraint_work = im->work_con;
  e->mapping_loss = im->pic_loss;
  e->ghost = im->ghost_work;
  e->total = e->kinetic + e->strain + e->dissipated + e->ghost - e->external_work - e->constraint_work;
}
