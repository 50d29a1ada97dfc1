#include "solver/diagnostics.h"

#include <string.h>

typedef struct column {
  const char *name;
  const char *unit;
} column;

/* the CSV header and the thermo columns come from this one table */
static const column columns[] = {
    {"E_kinetic", "J"}, {"E_gravity", "J"},  {"E_elastic", "J"}, {"E_total", "J"},  {"W_plastic", "J"},
    {"W_friction", "J"}, {"W_damping", "J"}, {"W_external", "J"}, {"W_walls", "J"}, {"E_bodies", "J"},
    {"W_bodies", "J"}, {"E_inflow", "J"},
    {"W_inflow", "J"}, {"E_outflow", "J"}, {"W_MPM", "J"}, {"momentum_x", "kg m/s"}, {"momentum_y", "kg m/s"},
    {"momentum_z", "kg m/s"},
    {"angular_x", "kg m^2/s"}, {"angular_y", "kg m^2/s"}, {"angular_z", "kg m^2/s"}, {"L_centroid", "kg m^2/s"},
    {"com_x", "m"}, {"com_y", "m"}, {"com_z", "m"}, {"mass", "kg"}, {"particles", ""},
};
enum { COLUMN_COUNT = sizeof columns / sizeof columns[0] };

int mrn_diagnostics_column_count(void) { return COLUMN_COUNT; }
const char *mrn_diagnostics_column_name(int i) { return columns[i].name; }
const char *mrn_diagnostics_column_unit(int i) { return columns[i].unit; }

/* a 2D simulation is a slab of unit thickness: its extensive quantities
 * (energies, masses, momenta) are per metre of it, the others as in 3D */
const char *mrn_diagnostics_column_unit_in(int i, int dim) {
  static const char *const per_metre[][2] = {
      {"J", "J/m"}, {"kg", "kg/m"}, {"kg m/s", "kg m/s/m"}, {"kg m^2/s", "kg m^2/s/m"}};
  for (int k = 0; dim == 2 && k < (int)(sizeof per_metre / sizeof per_metre[0]); k++)
    if (strcmp(columns[i].unit, per_metre[k][0]) == 0) return per_metre[k][1];
  return columns[i].unit;
}

void mrn_diagnostics_values(const mrn_diagnostics *d, double *v) {
  int k = 0;
  v[k++] = d->kinetic;
  v[k++] = d->gravity;
  v[k++] = d->elastic;
  v[k++] = d->total;
  v[k++] = d->plastic;
  v[k++] = d->friction;
  v[k++] = d->damping;
  v[k++] = d->external;
  v[k++] = d->walls;
  v[k++] = d->bodies;
  v[k++] = d->bodies_work;
  v[k++] = d->inflow;
  v[k++] = d->inflow_work;
  v[k++] = d->outflow;
  v[k++] = d->mpm_error;
  for (int i = 0; i < 3; i++) v[k++] = d->momentum[i];
  for (int i = 0; i < 3; i++) v[k++] = d->angular[i];
  v[k++] = d->L_centroid;
  for (int i = 0; i < 3; i++) v[k++] = d->com[i];
  v[k++] = d->mass;
  v[k++] = (double)d->particles;
}
