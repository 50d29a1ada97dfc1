#include "material/material.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

/* The registry: a new model adds one line here. */
static const mrn_material_type *const registry[] = {
    &mrn_material_linear_elastic,
    &mrn_material_mohr_coulomb,
    &mrn_material_drucker_prager,
    &mrn_material_von_mises,
    &mrn_material_newtonian,
    &mrn_material_hencky,
    &mrn_material_neo_hookean,
    &mrn_material_mu_i,
    &mrn_material_cam_clay,
    &mrn_material_user,
};
enum { REGISTRY_COUNT = sizeof registry / sizeof registry[0] };

int mrn_material_type_count(void) { return REGISTRY_COUNT; }
const mrn_material_type *mrn_material_type_at(int i) { return i >= 0 && i < REGISTRY_COUNT ? registry[i] : NULL; }

const mrn_material_type *mrn_material_type_find(const char *name) {
  for (int i = 0; i < REGISTRY_COUNT; i++)
    if (strcmp(registry[i]->name, name) == 0) return registry[i];
  return NULL;
}

const char *mrn_material_implicit_names(char *buf, size_t cap) {
  size_t used = 0;
  buf[0] = '\0';
  for (int i = 0; i < REGISTRY_COUNT && used < cap; i++)
    if (registry[i]->implicit)
      used += (size_t)snprintf(buf + used, cap - used, "%s%s", used ? ", " : "", registry[i]->name);
  return buf;
}

/* required parameters start as NaN so prepare() can tell they were not set */
mrn_material *mrn_material_new(const mrn_material_type *type) {
  mrn_material *m = calloc(1, sizeof *m);
  if (!m) {
    mrn_error("material: out of memory");
    return NULL;
  }
  m->type = type;
  m->refcount = 1;
  snprintf(m->name, sizeof m->name, "%s", type->name);
  for (int i = 0; i < type->nparams; i++) m->param[i] = type->params[i].required ? NAN : type->params[i].def;
  return m;
}

int mrn_material_set(mrn_material *m, const char *key, double value) {
  const mrn_spec *s = mrn_spec_find(m->type->params, m->type->nparams, key);
  if (!s) {
    const char *hint = mrn_spec_suggest(m->type->params, m->type->nparams, key);
    return mrn_error("material %s: unknown parameter '%s'%s", m->type->name, key, mrn_hint(hint).s);
  }
  char expected[128];
  if (mrn_spec_check_range(s, value, expected, sizeof expected))
    return mrn_error("material %s: %s = %s is out of range (expected %s)", m->type->name, key, mrn_num(value).s,
                     expected);
  m->param[s - m->type->params] = value;
  return MRN_OK;
}

int mrn_material_prepare(mrn_material *m) {
  for (int i = 0; i < m->type->nparams; i++)
    if (isnan(m->param[i]))
      return mrn_error("material %s: parameter '%s' (%s) is required", m->type->name, m->type->params[i].key,
                       m->type->params[i].doc);
  return m->type->prepare ? m->type->prepare(m) : MRN_OK;
}

void mrn_material_ref(mrn_material *m) {
  if (m) m->refcount++;
}

void mrn_material_unref(mrn_material *m) {
  if (m && --m->refcount == 0) {
    mrn_material_user_free(m);
    free(m);
  }
}

double mrn_material_get(const mrn_material *m, const char *key) {
  const mrn_spec *s = mrn_spec_find(m->type->params, m->type->nparams, key);
  return s ? m->param[s - m->type->params] : NAN;
}

double mrn_material_density(const mrn_material *m) { return mrn_material_get(m, "density"); }

double mrn_material_young(const mrn_material *m) {
  double E = mrn_material_get(m, "E");
  if (!isnan(E)) return E;
  /* models without E: the P-wave modulus rho c^2 gives the same a_tau scale */
  double c = m->type->wave_speed ? m->type->wave_speed(m) : NAN;
  return mrn_material_density(m) * c * c;
}

double mrn_material_isotropic_wave_speed(const mrn_material *m) {
  return sqrt((m->derived[0] + 2 * m->derived[1]) / m->param[0]);
}
