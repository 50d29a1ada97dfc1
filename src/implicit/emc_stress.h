/* moraine: the energy-momentum consistent algorithmic stress of the
 * implicit integrator (001 §5).
 *
 * Material: Hencky elasticity, tau = lambda tr(e) I + 2 G e with the
 * logarithmic elastic strain e = ln(b_e) / 2, and optionally von Mises
 * plasticity with linear isotropic hardening, return-mapped in principal
 * logarithmic strains (001 Eqs. 62-63; stored energy
 * psi = e:D:e / 2 + H xi^2 / 2, 001 App. A.2).
 *
 * For a step with deformation-gradient increment dF (F = dF F_t) the
 * algorithmic Kirchhoff stress is (001 Eqs. 48-51, 56)
 *   tau_mp = tau_bar + Delta^PF b (dH / ||dC||^2),
 *   tau_bar = (dF tau_t dF^T + tau)/2,  Delta^PF b = F dC F^T,  dC = C - C_t,
 *   dH = 2 (dpsi + dD) - 2 tau_bar : d_bar,  d_bar = F^-T dC F^-1 / 2,
 * so that tau_mp : d_bar = dpsi + dD exactly (001 Eq. 56). The internal force
 * of 001 Eq. 44 written on the grid of the step (gradients at the start of
 * the step, where the shape functions stay fixed during the Newton loop) is
 *   f_A = V_0 P grad N_A,  P = dF_theta dF^-1 tau_mp dF^-T,
 * dF_theta = (I + dF)/2 the mid-point increment (001 Eqs. 22, 42, 44).
 *
 * The functions take complex arguments: the derivative dP/d(dF) used for the
 * stiffness matrix (001 Eq. A.10) is obtained by complex-step
 * differentiation, P(dF + i h E_kl) = P + i h dP/d(dF_kl) + O(h^2) with
 * h = 1e-30, which is exact to round-off (no difference is taken). This is
 * NOT the hand-expanded linearisation of 001 Appendix A (Eqs. A.11-A.29): it
 * differentiates the same algorithmic stress automatically. The matrix
 * logarithm of the perturbed b_e uses the eigen-decomposition of its real
 * part and the Daleckii-Krein formula for the imaginary part. */
#ifndef MRN_IMPLICIT_EMC_STRESS_H
#define MRN_IMPLICIT_EMC_STRESS_H

#include <complex.h>

typedef struct mrn_emc_material {
  double lambda, G; /* Lame constants (Pa) */
  double yield;     /* uniaxial yield stress sigma_y (Pa); <= 0 or inf: elastic */
  double H;         /* linear isotropic hardening modulus (Pa) */
} mrn_emc_material;

/* state at the start of the step */
typedef struct mrn_emc_state {
  double Ft[9];  /* total deformation gradient F_t */
  double be[9];  /* elastic left Cauchy-Green tensor b_e,t */
  double tau[9]; /* Kirchhoff stress tau_t */
  double psi;    /* stored energy per reference volume psi_t (J/m^3) */
  double xi;     /* equivalent plastic strain (hardening variable) */
} mrn_emc_state;

/* end-of-step values that become the next state */
typedef struct mrn_emc_result {
  double be[9], tau[9], psi, xi;
  double dissipation; /* dD = sqrt(2/3) sigma_y dgamma per reference volume (J/m^3) */
} mrn_emc_result;

/* P(dF) (see above), per unit reference volume. `end` (may be NULL) receives
 * the real parts of the end-of-step state. */
void mrn_emc_stress(const mrn_emc_material *m, const mrn_emc_state *s, const double complex dF[9],
                    double complex P[9], mrn_emc_result *end);

/* P and its derivative dP_ij/d(dF_kl) = D[9 * (3k + l) + 3i + j] for the
 * in-plane k, l < dim (the others are not touched). */
void mrn_emc_tangent(const mrn_emc_material *m, const mrn_emc_state *s, const double dF[9], int dim,
                     double P[9], double D[81], mrn_emc_result *end);

/* Hencky stress and stored energy of an elastic b_e (start-of-run state) */
void mrn_emc_hencky(const mrn_emc_material *m, const double be[9], double tau[9], double *psi);

#endif
