/* moraine: material points through one step, from their velocity gradients.
 *
 * The single place where a point's kinematics and constitutive update meet;
 * the explicit step (solver/step.c) and the single-point driver
 * (material/driver.c) both call it:
 *   F_new = A F with A = (I - L dt/2)^-1 (I + L dt/2) (mid-point, the default:
 *           a rigid spin stays a pure rotation) or A = I + L dt (002, Eq. 27);
 *   rate-form models get the stress co-rotated by the Jaumann spin
 *   (002, Eqs. 28-30) and the strain increment sym(L) dt;
 *   the energies per unit volume are weighted by the mid-step volume and
 *   added to the points' sums, or returned for the caller to weight.
 * Points are advanced in batches of one material: the kinematics are
 * specialised by dimension (in plane strain L and A have no z coupling) and
 * the model's update is called once per batch, not once per point. */
#ifndef MRN_MATERIAL_ADVANCE_H
#define MRN_MATERIAL_ADVANCE_H

#include <stddef.h>

#include "material/material.h"

typedef enum { MRN_F_UPDATE_EULER = 0, MRN_F_UPDATE_MIDPOINT = 1 } mrn_f_update;

typedef struct mrn_point_result {
  double J;               /* det F after the step */
  double de_elastic;      /* per unit volume, see mrn_material_point */
  double dw_plastic;
  int inverted;           /* 1: the increment would invert F; the point was left unchanged */
} mrn_point_result;

/* Where a batch's energies go (000, Eqs. 64-65): each point's increments
 * per unit volume (de_elastic, dw_plastic of mrn_material_point), weighted
 * by its mid-step volume V0 (J_old + J) / 2, are added to e_elastic and
 * w_plastic. Each pointer is to the batch's first point, laid out as the
 * particle arrays (one value per point). */
typedef struct mrn_energy_sums {
  const double *vol0; /* reference volumes V0 */
  double *e_elastic;
  double *w_plastic;
} mrn_energy_sums;

/* Advances n points of one material whose data lie in the particle arrays'
 * layout: L 9 values per point (a full row-major 3 x 3), F
 * mrn_tensor_stride(dim) (9 in 3D, the in-plane block xx, xy, yx, yy in
 * 2D), stress and strain 6 (strain may be NULL), state `state_stride` (may
 * be NULL). dim 2 is plane strain: L must have no z row or column (as the
 * 2D gradient kernels store it); dim 3 is general. The energies are added
 * as `energy` says (may be NULL); out[i] receives point i's result (out may
 * be NULL). Returns the index of the first point whose increment would
 * invert F, or -1; such points are left unchanged (energies included), the
 * others are advanced. */
long mrn_material_advance_points(const mrn_material *mat, int dim, mrn_f_update f_update, double dt, size_t n,
                                 const double *L, double *F, double *stress, double *strain, double *state,
                                 int state_stride, const mrn_energy_sums *energy, mrn_point_result *out);

/* One point (3D, general L). Updates F, stress, strain (may be NULL) and
 * state in place. Returns 0, or 1 when the increment would invert F
 * (nothing is changed then). */
int mrn_material_advance(const mrn_material *mat, const double L[9], double dt, mrn_f_update f_update, double F[9],
                         double stress[6], double strain[6], double *state, mrn_point_result *out);

#endif
