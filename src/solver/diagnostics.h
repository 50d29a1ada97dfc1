/* moraine: whole-system diagnostics (000, Eqs. 46-48, 64-68).
 * Energies are in J (J/m per unit thickness in 2D). */
#ifndef MRN_SOLVER_DIAGNOSTICS_H
#define MRN_SOLVER_DIAGNOSTICS_H

typedef struct mrn_diagnostics {
  double kinetic;      /* E_k = sum 1/2 m |v|^2 (000, Eq. 47) */
  double gravity;      /* E_g = -sum m g . x, zero at the origin's height (000, Eq. 48) */
  double elastic;      /* E_el, accumulated increments (000, Eq. 64) */
  double plastic;      /* W_pl, accumulated, <= 0 (000, Eq. 65) */
  double friction;     /* W_frict, accumulated, <= 0 (000, Eq. 66) */
  double damping;      /* W_damp, work of the damping forces, accumulated, <= 0 */
  double external;     /* W_ext, work of the point forces, accumulated */
  double inflow;       /* E_in, E_k + E_g + E_el of the particles added (sources, hooks), accumulated */
  double inflow_work;  /* W_in, work of the sources' inlet nodes, accumulated */
  double outflow;      /* E_out, E_k + E_g + E_el - W_pl of the particles deleted on leaving, accumulated */
  double walls;        /* W_walls, work of the rigid walls of prescribed motion on the material, accumulated */
  double bodies;       /* E_bodies, kinetic energy of the rigid bodies (grid/wall.h) */
  double bodies_work;  /* W_bodies, work of gravity, loads and fixings on the rigid bodies, accumulated */
  double contact;      /* W_contact, work of friction between bodies, accumulated, <= 0 */
  double mpm_error;    /* W_MPM = E + E_bodies - E_ref - W_pl - W_frict - W_damp - W_ext - W_walls - W_bodies
                        * - W_contact - E_in - W_in + E_out (000, Eqs. 67-68) */
  double total;        /* E_k + E_g + E_el */
  double mass;
  double momentum[3];  /* sum m v */
  double angular[3];   /* sum m x cross v, about the origin */
  double L_centroid;   /* |sum m (x - x_c) cross v| about the centroid x_c = mean x (000, Eqs. 54, 56) */
  double com[3];       /* centre of mass */
  double com_velocity[3];
  long particles;
} mrn_diagnostics;

/* one name per column, in the order mrn_diagnostics_values() fills them */
int mrn_diagnostics_column_count(void);
const char *mrn_diagnostics_column_name(int i);
const char *mrn_diagnostics_column_unit(int i);
/* the unit in a `dim`-dimensional simulation: per metre of thickness in 2D
 * for the extensive columns ("J/m", "kg/m", "kg m/s/m", "kg m^2/s/m") */
const char *mrn_diagnostics_column_unit_in(int i, int dim);
void mrn_diagnostics_values(const mrn_diagnostics *d, double *values);

#endif
