#include "core/warn.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"

/* every kind of warning moraine prints; doc/lua-api.md (mpm.warnings) lists them */
static const mrn_warning_kind kinds[] = {
    {"dt_above_cfl", "a fixed time step above the particle CFL estimate (002, Eqs. 34-37)"},
    {"courant_above_one", "a CFL policy with a Courant number above 1"},
    {"one_particle_per_cell", "particles seeded one per cell (per_axis = 1)"},
    {"checkpoint_no_checksums", "a checkpoint of format version 1, which has no checksums, loaded or imported"},
    {"unused_set", "a --set NAME=VALUE whose NAME the deck never read with mpm.param"},
};
#define NKINDS ((int)(sizeof kinds / sizeof kinds[0]))

static const char *ids[NKINDS + 1];
static int ignored[NKINDS], printed[NKINDS];
static int ignore_all, count;

static int index_of(const char *id) {
  for (int i = 0; i < NKINDS; i++)
    if (strcmp(kinds[i].id, id) == 0) return i;
  return -1;
}

const char *const *mrn_warning_ids(void) {
  for (int i = 0; i < NKINDS; i++) ids[i] = kinds[i].id;
  ids[NKINDS] = NULL;
  return ids;
}

const mrn_warning_kind *mrn_warning_find(const char *id) {
  int i = index_of(id);
  return i < 0 ? NULL : &kinds[i];
}

int mrn_warning(const char *id, const char *fmt, ...) {
  int i = index_of(id);
  if (i < 0 || ignore_all || ignored[i] || printed[i]) return 0;
  printed[i] = 1;
  count++;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  mrn_log_printf(stderr, "moraine: warning [%s]: %s (silence: mpm.warnings{ignore = {\"%s\"}} or --ignore-warning %s)\n",
                 id, msg, id, id);
  return 1;
}

int mrn_warning_ignore(const char *id) {
  if (strcmp(id, "all") == 0) {
    ignore_all = 1;
    return MRN_OK;
  }
  int i = index_of(id);
  if (i < 0) return mrn_error("unknown warning '%s'", id);
  ignored[i] = 1;
  return MRN_OK;
}

void mrn_warning_reset(void) {
  memset(ignored, 0, sizeof ignored);
  memset(printed, 0, sizeof printed);
  ignore_all = 0;
  count = 0;
}

int mrn_warning_count(void) { return count; }
