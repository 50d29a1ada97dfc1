/* moraine: one material point through one step, from its velocity gradient.
 *
 * The single place where a point's kinematics and constitutive update meet;
 * the explicit step (solver/step.c) and the single-point driver
 * (material/driver.c) both call it:
 *   F_new = A F with A = (I - L dt/2)^-1 (I + L dt/2) (mid-point, the default:
 *           a rigid spin stays a pure rotation) or A = I + L dt (002, Eq. 27);
 *   rate-form models get the stress co-rotated by the Jaumann spin
 *   (002, Eqs. 28-30) and the strain increment sym(L) dt;
 *   the energies per unit volume are returned for the caller to weight. */
#ifndef MRN_MATERIAL_ADVANCE_H
#define MRN_MATERIAL_ADVANCE_H

#include "material/material.h"

typedef enum { MRN_F_UPDATE_EULER = 0, MRN_F_UPDATE_MIDPOINT = 1 } mrn_f_update;

typedef struct mrn_point_result {
  double J_old, J;        /* det F before and after */
  double de_elastic;      /* per unit volume, see mrn_material_point */
  double dw_plastic;
} mrn_point_result;

/* Updates F, stress, strain (may be NULL) and state in place. Returns 0, or 1
 * when the increment would invert F (nothing is changed then). */
int mrn_material_advance(const mrn_material *mat, const double L[9], double dt, mrn_f_update f_update, double F[9],
                         double stress[6], double strain[6], double *state, mrn_point_result *out);

#endif
