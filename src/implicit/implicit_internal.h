/* moraine: the implicit integrator's state and its grid-side operations
 * (grid_system.c), shared with the step (implicit.c). Not a public header. */
#ifndef MRN_IMPLICIT_IMPLICIT_INTERNAL_H
#define MRN_IMPLICIT_IMPLICIT_INTERNAL_H

#include "implicit/emc_stress.h"
#include "implicit/implicit.h"
#include "implicit/linear_solver.h"
#include "implicit/stencil.h"

/* one cell of the volumetric averaging (bbar.c): the union of its points'
 * stencils (active node indices), the averaged gradients g_A, the averaged
 * divergence theta at the current iterate and the assembly's sums */
typedef struct mrn_bbar_cell {
  int count;
  int node[MRN_IMPLICIT_STENCIL_MAX];
  double g[MRN_IMPLICIT_STENCIL_MAX][3];
  size_t cell; /* grid index of its lower corner (im->cellvol) */
  double theta;
  double trP, S;
  double A[MRN_IMPLICIT_STENCIL_MAX][3], B[MRN_IMPLICIT_STENCIL_MAX][3], Nn[MRN_IMPLICIT_STENCIL_MAX][3];
} mrn_bbar_cell;

struct mrn_implicit {
  mrn_sim *sim;
  mrn_implicit_options opt;
  int dim;
  size_t np;
  mrn_emc_material mat[MRN_MAX_MATERIALS];
  mrn_emc_state *st;   /* per particle, start of step */
  mrn_emc_result *res; /* per particle, at the current Newton iterate */
  double *diss;        /* accumulated dissipation V_0 sum dD per particle */
  double *fpt;         /* 3 per particle: point forces */
  double load_factor;  /* multiplies every point force */
  mrn_implicit_stencil *sten;
  double work_ext;
  double work_con; /* work of the forces that hold the fixed components, sum over steps of r_c . u_c */
  double pic_loss; /* sum over steps of sum m |v_p - N v_t|^2 / 2 under PIC (001 Eq. 37) */
  mrn_implicit_history last; /* the last step made by mrn_run (implicit_run.c) */

  /* active nodes of the step, in grid-index order */
  int *dof;      /* grid.n: active index or -1 */
  size_t *act;   /* nact grid indices */
  int *ijk;      /* 3 per active node */
  size_t nact, act_cap;
  /* node pairs: column node b and row node a = b + off[r] */
  int W, R, NR, rc; /* stencil width 2 sup - 1, reach sup - 1, pairs per node, r of a == b */
  long off[343];
  double *Kb;    /* nact * NR * 9: K_(a i),(b k) at [(b NR + r) 9 + 3 i + k] */
  double *Mc;    /* nact * NR consistent mass */
  unsigned char *touched;
  double *ml;    /* lumped mass per active node */
  double *gmass; /* grid.n: lumped mass of every node, for the mass floor */
  int *fdof;     /* dim per active node: free dof index or -1 (fixed) */
  double *vfix;  /* 3 per active node: the prescribed velocity of fixed components (face conditions and
                  * sim:constrain{}), held through the step (0 elsewhere) */
  int nfree;
  /* ghost penalty (ghost.c): K_g per node pair (one scalar, the same for every
   * component), points' volume per cell, the modulus E it is scaled by and
   * the energy it removed, sum over steps of u^T K_g u */
  double *Gb, *cellvol, ghost_modulus, ghost_work;
  /* volumetric averaging (bbar.c): the cell of each point, each point's
   * stencil slots in its cell's union, the cell of each grid index */
  mrn_bbar_cell *bb;
  size_t bb_n, bb_cap;
  int *bb_of, *bb_index;
  unsigned char (*bb_slot)[MRN_IMPLICIT_STENCIL_MAX];
  double *v0, *u, *fint, *fext, *p, *r, *du; /* 3 per active node; r, du per free dof */
  mrn_csc A;
};

/* pair index of row node a and column node b (active indices): the offset
 * a - b in the (2 R + 1)^dim block */
static inline int mrn_implicit_pair_index(const mrn_implicit *im, size_t a, size_t b) {
  const int *ia = im->ijk + 3 * a, *ib = im->ijk + 3 * b;
  int r = 0;
  if (im->dim == 3) r = (ia[2] - ib[2] + im->R) * im->W;
  r = (r + ia[1] - ib[1] + im->R) * im->W;
  return r + ia[0] - ib[0] + im->R;
}

/* stencils at the start-of-step positions (small nodes left out), active
 * nodes, clamped components; 0 or error */
int mrn_implicit_setup_step(mrn_implicit *im);
/* mass matrices, grid momentum and mid-step external forces (001 Eqs. 15-19, 26) */
void mrn_implicit_map_to_grid(mrn_implicit *im);
/* the free-dof matrix alpha M~ + beta K in im->A */
int mrn_implicit_build_matrix(mrn_implicit *im, double alpha, double beta);
/* y = M~ x over all active components (3 per active node) */
void mrn_implicit_mass_multiply(const mrn_implicit *im, const double *x, double *y);
/* dF = I + sum_A u_A (x) grad N_A (001 Eq. 25) */
void mrn_implicit_increment(const mrn_implicit *im, const mrn_implicit_stencil *s, double dF[9]);
/* dF of point p: the above, with the cell-averaged divergence when the
 * volumetric averaging is on (bbar.c) */
void mrn_implicit_point_increment(const mrn_implicit *im, size_t p, double dF[9]);
/* grid index of the lower corner of the cell holding point p (start of
 * step; a point beyond the padded grid counts in its edge cell) */
size_t mrn_implicit_point_cell(const mrn_implicit *im, size_t p);
/* im->cellvol: the start-of-step volume of the points in each cell, indexed
 * by its lower corner (for the ghost penalty and the volumetric averaging;
 * nothing when both are off) */
int mrn_implicit_cell_volumes(mrn_implicit *im);
/* internal forces (001 Eq. 44) and stiffness (001 Eq. A.10) at the current u */
void mrn_implicit_assemble(mrn_implicit *im);
/* point_state.c: the points' history (b_e, tau, psi, xi) in the particle
 * fields implicit_be, implicit_tau, implicit_psi, implicit_xi, registered if
 * absent, so that checkpoints keep it. load fills im->st and im->diss from
 * them (b_e = F F^T where none is stored yet); store writes im->st back. */
int mrn_implicit_state_load(mrn_implicit *im);
void mrn_implicit_state_store(mrn_implicit *im);

/* M~ v = p on the free components (001 Eq. 26) */
int mrn_implicit_project_velocity(mrn_implicit *im, const double *p, double *v);

/* ghost stabilisation (ghost.c): the penalty matrix K_g of the step's cut
 * faces (after map_to_grid); f_int += K_g u and K += K_g (in assemble); the
 * energy u^T K_g u the penalty removes in the step */
int mrn_implicit_ghost_build(mrn_implicit *im);
void mrn_implicit_ghost_apply(mrn_implicit *im);
double mrn_implicit_ghost_work(const mrn_implicit *im);

/* volumetric averaging (bbar.c), when options.bbar: the cells and their
 * averaged gradients (after map_to_grid); the averaged divergences at the
 * current u (first in assemble); a point's force and stiffness terms beside
 * its own (in assemble, after the point's stress); the cells' terms (after
 * every point) */
int mrn_implicit_bbar_setup(mrn_implicit *im);
void mrn_implicit_bbar_theta(mrn_implicit *im);
void mrn_implicit_bbar_point(mrn_implicit *im, size_t p, const double P[9], const double D[81]);
void mrn_implicit_bbar_cells(mrn_implicit *im);

#endif
