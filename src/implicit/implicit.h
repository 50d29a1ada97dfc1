/* moraine: implicit energy-momentum consistent updated-Lagrangian MPM
 * (paper 001).
 *
 * One step (001 Fig. 2, Eqs. 18-30):
 *   B  map mass and momentum to the grid: M~ v_t = sum m N v_p (001 Eq. 26)
 *      with the effective mass M~ = (1 - eps) M + eps M_lumped (001 Eqs. 15,
 *      18, 19), nodes fixed by constraints held at zero;
 *   C  mid-point residual (001 Eqs. 20, 22-24) in the grid displacement u:
 *        r(u) = f_int(u) + (2 / dt^2) M~ (u - dt v_t) - f_ext,
 *      f_int from the energy-consistent algorithmic stress (emc_stress.h,
 *      001 Eq. 44), f_ext from point forces on material points and gravity,
 *      both at mid-step;
 *      plus, with options.ghost > 0, the ghost penalty K_g u (ghost.c);
 *   D  Newton-Raphson from u = dt p / m_lumped, J = 2/dt^2 M~ + K (001 Eq. 27
 *      and §3.4), with a backtracking line search, until the
 *      error f_err^(k) = sum_I |r_I^(k)| |du_I^(k)| falls below tol times
 *      f_err^(1) (001 §3.4); a step not converged in max_iter iterations
 *      fails, or with options.cutbacks > 0 is started again from B with
 *      half the time step (nothing of the abandoned attempt is kept);
 *   E  v_{t+dt} = 2 u / dt - v_t on the grid; particles by PIC (001 Eq. 28)
 *      or FLIP (001 Eq. 29), positions x += N u (001 Eq. 30),
 *      F = dF F_t (001 Eq. 25).
 * The shape functions are evaluated once per step at the start-of-step
 * positions. The step size is fixed or dt_factor times the grid-averaged
 * CFL estimate of 001 Eq. 61 (solver/timestep.h).
 *
 * Fixed components: the simulation's free, slip, fixed and velocity faces
 * (on the nodes on and beyond each face, as in the explicit step) and its
 * grid constraints, with their prescribed velocities held through the step
 * (u = dt v there); friction and periodic faces are refused.
 *
 * Limits: materials whose type has an implicit form (material.h: hencky,
 * elastic, and von_mises, whose E, nu, yield and hardening are used in the
 * finite-strain Hencky form of emc_stress.h); particles may not be added after the integrator is created; initial
 * particle stresses are ignored (the state starts from b_e = F F^T). Each
 * point's history (b_e, tau, psi, xi) is kept in the registered particle
 * fields implicit_* (point_state.c), so checkpoints hold it and a new
 * integrator continues from it. */
#ifndef MRN_IMPLICIT_IMPLICIT_H
#define MRN_IMPLICIT_IMPLICIT_H

#include <stddef.h>

#include "solver/simulation.h"

typedef enum { MRN_MASS_CONSISTENT = 0, MRN_MASS_LUMPED, MRN_MASS_EFFECTIVE } mrn_mass_kind;
typedef enum { MRN_MAPPING_FLIP = 0, MRN_MAPPING_PIC } mrn_mapping_kind;

#define MRN_IMPLICIT_MAX_ITER 50
#define MRN_IMPLICIT_MAX_CUTBACKS 10

typedef struct mrn_implicit_options {
  mrn_mass_kind mass;
  double eps;               /* weight of the lumped mass for MRN_MASS_EFFECTIVE, [0, 1] */
  mrn_mapping_kind mapping;
  double tol;               /* f_err^(k) / f_err^(1) below which a step has converged (001: 1e-11) */
  int max_iter;             /* Newton iterations before the step fails (<= MRN_IMPLICIT_MAX_ITER) */
  double dt;                /* fixed step (s) when > 0 */
  double dt_factor;         /* otherwise dt = dt_factor * (001 Eq. 61) at the start of every step */
  double min_node_mass;     /* nodes lighter than this times the heaviest point are left out of the
                             * step and the points touching them get MLS functions (grid_system.c) */
  double ghost;             /* ghost penalty factor gamma (ghost.c), times the largest Young's modulus;
                             * 0: off. Linear and gimp shapes only. */
  int bbar;                 /* 1: the divergence of each point's step increment is averaged over the
                             * points of its cell (bbar.c), against volumetric locking */
  int cutbacks;             /* a step not converged in max_iter iterations is tried again with half the
                             * time step, at most this many times (0..MRN_IMPLICIT_MAX_CUTBACKS); 0: it fails */
} mrn_implicit_options;

/* consistent mass, FLIP, tol 1e-11, 20 iterations, dt_factor 5, min_node_mass 1e-3, no ghost penalty,
 * no volumetric averaging, no cutbacks */
void mrn_implicit_options_default(mrn_implicit_options *o);

typedef struct mrn_implicit_history {
  double dt;
  int iterations;                   /* linear solves after the grid velocity projection */
  double err[MRN_IMPLICIT_MAX_ITER]; /* f_err^(k) / f_err^(1), k = 1 .. iterations */
  double residual;                  /* max |r_I| at the accepted state (N) */
  int cuts;                         /* times the step was halved before Newton converged (cutbacks) */
  int rejected_iterations;          /* Newton iterations of the attempts that were cut */
} mrn_implicit_history;

typedef struct mrn_implicit_energy {
  double kinetic;       /* sum m v^2 / 2 of the particles (J; J/m in 2D) */
  double strain;        /* sum V_0 psi */
  double dissipated;    /* accumulated plastic dissipation sum V_0 dD */
  double external_work; /* work of point forces and gravity, sum f_ext . u */
  double constraint_work; /* work of the forces holding components at a prescribed nonzero velocity */
  double ghost;         /* energy removed by the ghost penalty, sum over steps of u^T K_g u (ghost.c) */
  double total;         /* kinetic + strain + dissipated + ghost - external_work - constraint_work */
  double mapping_loss;  /* kinetic energy the PIC mapping removed, sum of m |v_p - N v_t|^2 / 2 (001 Eq. 37) */
  double momentum[3];   /* sum m v */
  double angular[3];    /* sum x x m v (z only in 2D) */
} mrn_implicit_energy;

typedef struct mrn_implicit mrn_implicit;

/* NULL with a message on failure (unsupported material, bad options) */
mrn_implicit *mrn_implicit_new(mrn_sim *sim, const mrn_implicit_options *o);
void mrn_implicit_free(mrn_implicit *im);

/* force (N; N/m in 2D) on particle p, applied from the next step until changed */
int mrn_implicit_set_point_force(mrn_implicit *im, size_t p, const double f[3]);
void mrn_implicit_clear_point_forces(mrn_implicit *im);
/* every point force is multiplied by factor (default 1) from the next step:
 * a load history without reselecting the loaded points */
void mrn_implicit_set_load_factor(mrn_implicit *im, double factor);

/* the step size the next step will use */
int mrn_implicit_next_dt(mrn_implicit *im, double *dt);

/* one step; fills h (may be NULL). 0, or an error (message set) when Newton
 * does not converge within max_iter or a linear solve fails. */
int mrn_implicit_step(mrn_implicit *im, mrn_implicit_history *h);

void mrn_implicit_energies(const mrn_implicit *im, mrn_implicit_energy *e);

/* Make mrn_run (sim:run) advance the simulation with this integrator instead
 * of the explicit step (implicit_run.c): each step is shortened so that a
 * run of given duration ends on time; the work of the point forces goes to
 * the simulation's work_external and the energy the ghost penalty removes to
 * its work_damping, so the diagnostics' W_MPM is the implicit step's energy
 * error. mrn_implicit_free detaches it (the explicit step again). */
void mrn_implicit_attach(mrn_implicit *im);
/* One step as mrn_run makes it: ending at or before t_end (HUGE_VAL: the
 * integrator's own step), with the energy booking above. 0, MRN_STEP_NONE
 * when what is left before t_end is a round-off sliver, or an error. */
int mrn_implicit_advance(mrn_implicit *im, double t_end, mrn_implicit_history *h);
void mrn_implicit_detach(mrn_implicit *im);
/* Newton history of the last step mrn_run made */
const mrn_implicit_history *mrn_implicit_last(const mrn_implicit *im);

#endif
