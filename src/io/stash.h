/* moraine: named values stored beside a simulation in a checkpoint — what a
 * resumed run needs that the engine's state does not hold: the settings and
 * counters of its outputs, the target of the run it was in.
 *
 * One function per owner walks its values in both directions: saving, each
 * call records the value; loading, each call sets the variable from the
 * stored value when there is one (and leaves it alone otherwise, so files
 * written before a value existed still load). A new value is one line:
 *
 *   void mrn_output_stash(mrn_output *o, mrn_stash *s) {
 *     mrn_stash_text(s, "output.vtk", &o->vtk_name);
 *     mrn_stash_real(s, "output.vtk_every", &o->vtk_every_time);
 *     ...
 *
 * Names are at most 63 bytes; checkpoints keep them as the attributes of the
 * group /resume (doc/checkpoint-format.md). */
#ifndef MRN_IO_STASH_H
#define MRN_IO_STASH_H

#include <stdint.h>

typedef enum { MRN_STASH_REAL, MRN_STASH_INT, MRN_STASH_TEXT } mrn_stash_kind;

typedef struct mrn_stash_value {
  char name[64];
  mrn_stash_kind kind;
  double real;
  int64_t integer;
  char *text; /* malloc'd */
} mrn_stash_value;

typedef struct mrn_stash {
  int loading; /* 0: the calls record values; 1: they set variables from them */
  mrn_stash_value *v;
  int n, cap;
} mrn_stash;

/* an empty stash for saving, or one for loading (filled by a reader) */
void mrn_stash_init(mrn_stash *s, int loading);
void mrn_stash_free(mrn_stash *s);

/* the walkers: record *value, or set it from the stored value of that name */
void mrn_stash_real(mrn_stash *s, const char *name, double *value);
void mrn_stash_long(mrn_stash *s, const char *name, long *value);
void mrn_stash_int(mrn_stash *s, const char *name, int *value);
/* a malloc'd string or NULL (stored as ""; "" loads as NULL) */
void mrn_stash_text(mrn_stash *s, const char *name, char **value);

/* a stored value added by a reader (0, or -1 out of memory) */
int mrn_stash_put(mrn_stash *s, const char *name, mrn_stash_kind kind, double real, int64_t integer, const char *text);
/* the stored value of that name, or NULL */
const mrn_stash_value *mrn_stash_find(const mrn_stash *s, const char *name);

#endif
