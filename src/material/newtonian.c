/* moraine: weakly compressible Newtonian fluid.
 *
 *   sigma = -p I + 2 mu dev(d)            (002, Eq. 69)
 *   p = c^2 (rho - rho_ref)               (002, Eq. 70, Morris's equation of state)
 * with rho = rho_ref / J from the particle's deformation gradient and the
 * rate of deformation d = dstrain / dt. The stress is a function of the
 * current J and d, not of its own history, so the model is not in rate form.
 *
 * Energies: the pressure derives from the stored energy per reference volume
 *   psi(J) = rho_ref c^2 (J - 1 - ln J),  dpsi/dJ = -p,
 * so de_elastic = (psi(J) - psi(J_old)) / ((J_old + J) / 2) sums exactly
 * (the step multiplies it by V0 (J_old + J) / 2). The viscous stress only
 * dissipates: dw_plastic = -2 mu dev(d) : dev(d) dt <= 0.
 *
 * Time step: viscous diffusion limits dt to h^2 / nu, nu = mu / rho_ref
 * (002, Eq. 36). */
#include <math.h>

#include "core/tensor.h"
#include "material/material.h"

enum { P_DENSITY, P_VISCOSITY, P_SOUND, P_COUNT };

static const mrn_spec params[P_COUNT] = {
    [P_DENSITY] = {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3", "reference density rho_ref", NULL},
    [P_VISCOSITY] = {"viscosity", MRN_SPEC_NUMBER, 0, 0.0, 0, HUGE_VAL, 0, 0, "Pa s", "dynamic viscosity mu", NULL},
    [P_SOUND] = {"sound_speed", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "m/s",
                 "speed of sound c of the equation of state p = c^2 (rho - rho_ref)", NULL},
};

static double stored_energy(const mrn_material *m, double J) {
  double c = m->param[P_SOUND];
  return m->param[P_DENSITY] * c * c * (J - 1 - log(J));
}

static inline void update_point(const mrn_material *m, mrn_material_point *pt) {
  const double rho0 = m->param[P_DENSITY], mu = m->param[P_VISCOSITY], c = m->param[P_SOUND];
  double p = c * c * (rho0 / pt->J - rho0); /* (002, Eq. 70) */
  double dev[6];
  sym_dev(pt->dstrain, dev);
  for (int k = 0; k < 6; k++) pt->stress[k] = 2 * mu * dev[k] / pt->dt + (k < 3 ? -p : 0.0); /* (002, Eq. 69) */
  pt->de_elastic = (stored_energy(m, pt->J) - stored_energy(m, pt->J_old)) / (0.5 * (pt->J_old + pt->J));
  pt->dw_plastic = -2 * mu * sym_ddot(dev, dev) / pt->dt;
}

MRN_MATERIAL_BATCH_UPDATE(update_point)

static double wave_speed(const mrn_material *m) { return m->param[P_SOUND]; }

/* h^2 / nu (002, Eq. 36); no limit for an inviscid fluid */
static double viscous_dt(const mrn_material *m, double h) {
  double mu = m->param[P_VISCOSITY];
  return mu > 0.0 ? h * h * m->param[P_DENSITY] / mu : HUGE_VAL;
}

const mrn_material_type mrn_material_newtonian = {
    .name = "newtonian",
    .summary = "weakly compressible Newtonian fluid with Morris's equation of state (002, Eqs. 69-70)",
    .params = params,
    .nparams = P_COUNT,
    .nstate = 0,
    .state_names = NULL,
    .rate_form = 0,
    .prepare = NULL,
    .update = update,
    .wave_speed = wave_speed,
    .viscous_dt = viscous_dt,
};
