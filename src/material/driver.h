/* moraine: the material-point driver.
 *
 * Runs one material at a single point, without grid or particles, to test a
 * model in isolation along a prescribed path. A step takes a velocity
 * gradient L over dt and does exactly what the explicit step does for a
 * particle (solver/step.c): F <- (I + L dt) F, Jaumann rotation of the stress
 * by the spin skew(L) dt for rate-form models, the model's update with the
 * strain increment sym(L) dt, and the energies integrated over the mid-step
 * volume.
 *
 * Mixed control prescribes some stress components instead of the matching
 * strain-rate components (triaxial, uniaxial stress, oedometer with a
 * constant load, simple shear at constant normal stress): the free
 * components of sym(L) are found by Newton iteration with a finite-
 * difference tangent so that those stress components reach their targets at
 * the end of the step. The spin skew(L) is always the one given. */
#ifndef MRN_MATERIAL_DRIVER_H
#define MRN_MATERIAL_DRIVER_H

#include "material/material.h"

#define MRN_DRIVER_MAX_STATE 16

/* How F is advanced: as the explicit step does, or with the mid-point
 * (Hughes-Winget) increment (I - L dt/2)^-1 (I + L dt/2), which is exactly
 * orthogonal for a pure spin. */
typedef enum { MRN_DRIVER_F_EULER = 0, MRN_DRIVER_F_MIDPOINT = 1 } mrn_driver_kinematics;

typedef struct mrn_driver {
  const mrn_material *mat;
  double stress[6];                   /* Cauchy stress, tension positive */
  double strain[6];                   /* sum of sym(L) dt, as the particles' strain */
  double F[9];
  double state[MRN_DRIVER_MAX_STATE]; /* the model's history variables */
  double e_elastic;                   /* elastic energy per unit reference volume (000, Eq. 64) */
  double w_plastic;                   /* plastic work per unit reference volume, <= 0 (000, Eq. 65) */
  double de_elastic, dw_plastic;      /* the last step's increments as the model returned them */
  double time;
  int kinematics;                     /* mrn_driver_kinematics */
  int iterations;                     /* Newton iterations of the last mixed step */
} mrn_driver;

/* start at F = I with the given stress (NULL: zero) and zero history */
int mrn_driver_init(mrn_driver *d, const mrn_material *m, const double stress0[6]);

/* one strain-controlled step with the full velocity gradient L (1/s);
 * returns 0, or an error when F would invert */
int mrn_driver_step(mrn_driver *d, const double L[9], double dt);

/* one strain-controlled step without spin: L = deps / dt (deps in
 * 6-component storage, tensor shear components) */
int mrn_driver_strain(mrn_driver *d, const double deps[6], double dt);

/* One mixed step: for every k with stress_ctrl[k] set, the symmetric
 * component k of L (xx, yy, zz, xy, yz, xz) is unknown and stress[k] must
 * equal target[k] at the end of the step; the other components of L are
 * prescribed as given (its value for a free component is the first guess).
 * Returns 0, or an error when the iteration does not converge. */
int mrn_driver_step_mixed(mrn_driver *d, const double L[9], const int stress_ctrl[6], const double target[6],
                          double dt);

/* Common paths (axis z axial, compression negative, rates in 1/s). */
/* triaxial: D_zz = rate, sigma_xx = sigma_yy = lateral, no shear strain */
int mrn_driver_triaxial(mrn_driver *d, double rate, double lateral, double dt);
/* uniaxial stress: D_zz = rate, sigma_xx = sigma_yy = 0 */
int mrn_driver_uniaxial(mrn_driver *d, double rate, double dt);
/* plane-strain biaxial: D_yy = rate, sigma_xx = lateral, D_zz = 0 */
int mrn_driver_biaxial(mrn_driver *d, double rate, double lateral, double dt);
/* oedometer: D_zz = rate, every other strain rate zero */
int mrn_driver_oedometer(mrn_driver *d, double rate, double dt);
/* simple shear in the x-y plane, v_x = gamma_rate y (L_xy = gamma_rate,
 * with its spin); sigma_yy = normal held when normal is finite, otherwise
 * constant volume (D_yy = 0); D_xx = D_zz = 0 */
int mrn_driver_simple_shear(mrn_driver *d, double gamma_rate, double normal, double dt);

#endif
