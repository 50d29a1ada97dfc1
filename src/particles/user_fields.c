/* moraine: per-particle values registered by a deck (sim:particle_field).
 *
 * They live in one array of `user_stride` doubles per particle, the fields
 * side by side in the order registered; a new field widens every record and
 * fills its slots with the field's initial value. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "particles/particles.h"

const mrn_user_field *mrn_particles_user_field(const mrn_particles *p, const char *name) {
  for (int i = 0; name && i < p->nuser; i++)
    if (strcmp(p->user_fields[i].name, name) == 0) return &p->user_fields[i];
  return NULL;
}

int mrn_particles_add_user_field(mrn_particles *p, const char *name, int ncomp, double init, const char *unit) {
  if (!name || !*name || strlen(name) >= MRN_USER_FIELD_NAME)
    return mrn_error("particle field: a name of 1 to %d characters is needed", MRN_USER_FIELD_NAME - 1);
  if (mrn_particles_user_field(p, name)) return mrn_error("particle field '%s' is already registered", name);
  if (p->nuser == MRN_USER_FIELDS_MAX) return mrn_error("at most %d particle fields can be registered", MRN_USER_FIELDS_MAX);
  if (ncomp < 1 || ncomp > 9) return mrn_error("particle field '%s': 1 to 9 components, not %d", name, ncomp);
  const int old = p->user_stride, stride = old + ncomp;
  double *u = malloc(sizeof(double) * (size_t)stride * (p->cap ? p->cap : 1));
  if (!u) return mrn_error("particles: out of memory for particle field '%s'", name);
  for (size_t i = 0; i < p->n; i++) {
    for (int k = 0; k < old; k++) u[i * stride + k] = p->user[i * old + k];
    for (int k = 0; k < ncomp; k++) u[i * stride + old + k] = init;
  }
  free(p->user);
  p->user = u;
  p->user_stride = stride;
  mrn_user_field *f = &p->user_fields[p->nuser++];
  memset(f, 0, sizeof *f);
  snprintf(f->name, sizeof f->name, "%s", name);
  snprintf(f->unit, sizeof f->unit, "%s", unit ? unit : "");
  f->ncomp = ncomp;
  f->offset = old;
  f->init = init;
  return MRN_OK;
}
