/* moraine: per-particle output quantities, by name.
 *
 * One table serves the VTK writer (which arrays a deck asks for) and the Lua
 * accessors: each entry computes its values for every particle into a buffer
 * of n * ncomp doubles (or int32/int64 for ids). */
#ifndef MRN_IO_PARTICLE_FIELDS_H
#define MRN_IO_PARTICLE_FIELDS_H

#include "io/vtk.h"

struct mrn_sim;

typedef struct mrn_output_field {
  const char *name;
  int ncomp;
  mrn_vtk_type type;
  const char *unit;
  const char *doc;
  /* fill `out` (n * ncomp values of `type`) */
  void (*compute)(const struct mrn_sim *sim, void *out);
} mrn_output_field;

int mrn_output_field_count(void);
const mrn_output_field *mrn_output_field_at(int i);
const mrn_output_field *mrn_output_field_find(const char *name);
/* NULL-terminated list of names */
const char *const *mrn_output_field_names(void);

#endif
