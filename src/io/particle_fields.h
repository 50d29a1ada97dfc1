/* moraine: per-particle output quantities, by name.
 *
 * One table serves the VTK writer (which arrays a deck asks for) and the Lua
 * accessors: each entry computes its values for a range of particles into a
 * buffer of ncomp doubles (or int32/int64 for ids) per particle; the VTK
 * writer asks for them a chunk at a time, so a snapshot never holds a whole
 * field in memory. */
#ifndef MRN_IO_PARTICLE_FIELDS_H
#define MRN_IO_PARTICLE_FIELDS_H

#include <stddef.h>

#include "io/vtk.h"

struct mrn_sim;

typedef struct mrn_output_field {
  const char *name;
  int ncomp;
  mrn_vtk_type type;
  const char *unit;
  const char *doc;
  /* fill `out` with the values of particles [first, first + count) (count * ncomp values of `type`) */
  void (*compute)(const struct mrn_sim *sim, size_t first, size_t count, void *out);
  int ncomp_2d;   /* values per particle in 2D when not ncomp (0: ncomp) */
  int on_request; /* written only when named (not among "all fields"): worked out from the grid */
} mrn_output_field;

int mrn_output_field_count(void);
const mrn_output_field *mrn_output_field_at(int i);
const mrn_output_field *mrn_output_field_find(const char *name);
/* NULL-terminated list of names */
const char *const *mrn_output_field_names(void);

/* A field of a given simulation by name: a built-in one of the table above,
 * or a value the deck registered (particles/particles.h, mrn_user_field). */
typedef struct mrn_field_ref {
  const char *name;
  int ncomp;
  mrn_vtk_type type;
  const mrn_output_field *builtin; /* NULL for a registered field */
  const struct mrn_user_field *user;
} mrn_field_ref;

/* 1 and *out filled when `name` is a field of sim, else 0; out->ncomp is
 * the field's count in sim's dimension */
int mrn_field_lookup(const struct mrn_sim *sim, const char *name, mrn_field_ref *out);
/* n * ncomp values of the field (of its type) into out */
void mrn_field_fill(const struct mrn_sim *sim, const mrn_field_ref *f, void *out);
/* the same for particles [first, first + count) only: count * ncomp values */
void mrn_field_fill_range(const struct mrn_sim *sim, const mrn_field_ref *f, size_t first, size_t count, void *out);

#endif
