#include "transfer/scheme.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

static const char *const preset_names[] = {"PIC", "FLIP", "FLIPX", "NFLIP", "NFLIPX", NULL};
static const char *const stress_names[] = {"USF", "USL", "MUSL", NULL};
static const char *const vupdate_names[] = {"PIC", "FLIP", "blend", NULL};
static const char *const xupdate_names[] = {"grid", "particle", NULL};
static const char *const vgrid_names[] = {"plain", NULL};

const char *const *mrn_scheme_preset_names(void) { return preset_names; }
const char *const *mrn_stress_update_names(void) { return stress_names; }
const char *const *mrn_velocity_update_names(void) { return vupdate_names; }
const char *const *mrn_position_update_names(void) { return xupdate_names; }
const char *const *mrn_grid_velocity_names(void) { return vgrid_names; }

void mrn_scheme_default(mrn_scheme *s) {
  memset(s, 0, sizeof *s);
  s->grid_velocity = MRN_VGRID_PLAIN;
  s->velocity_update = MRN_VUPDATE_FLIP;
  s->position_update = MRN_XUPDATE_GRID;
  s->flip_fraction = 1.0;
  s->stress_update = MRN_STRESS_USF;
  snprintf(s->name, sizeof s->name, "FLIP");
}

/* parse the X of "FLIP0.99": a number in [0, 1] right after the prefix */
static int parse_fraction(const char *text, double *x) {
  char *end;
  double v = strtod(text, &end);
  if (end == text || *end != '\0' || !(v >= 0.0 && v <= 1.0)) return 0;
  *x = v;
  return 1;
}

int mrn_scheme_from_preset(const char *name, mrn_scheme *s) {
  mrn_stress_update_kind keep = s->stress_update;
  int natural = 0;
  const char *rest = name;
  if (strncmp(name, "NFLIP", 5) == 0) {
    natural = 1;
    rest = name + 5;
  } else if (strncmp(name, "FLIP", 4) == 0) {
    rest = name + 4;
  } else if (strcmp(name, "PIC") == 0) {
    s->grid_velocity = MRN_VGRID_PLAIN;
    s->velocity_update = MRN_VUPDATE_PIC;
    s->position_update = MRN_XUPDATE_GRID;
    s->flip_fraction = 0.0;
    snprintf(s->name, sizeof s->name, "PIC");
    return MRN_OK;
  } else {
    rest = NULL;
  }
  if (rest) {
    double x = 1.0;
    if (*rest == '\0' || parse_fraction(rest, &x)) {
      s->grid_velocity = MRN_VGRID_PLAIN;
      s->velocity_update = x == 1.0 ? MRN_VUPDATE_FLIP : MRN_VUPDATE_BLEND;
      s->flip_fraction = x;
      s->position_update = natural ? MRN_XUPDATE_PARTICLE : MRN_XUPDATE_GRID;
      s->stress_update = keep;
      snprintf(s->name, sizeof s->name, "%s", name);
      return MRN_OK;
    }
  }
  return mrn_error("unknown strategy '%s' (valid: PIC, FLIP, FLIPX as FLIP<X> with X in [0,1] e.g. FLIP0.99, "
                   "NFLIP, NFLIPX as NFLIP<X>)", name);
}

void mrn_scheme_describe(mrn_scheme *s) {
  const char *prefix = s->position_update == MRN_XUPDATE_PARTICLE ? "N" : "";
  switch (s->velocity_update) {
  case MRN_VUPDATE_PIC:
    snprintf(s->name, sizeof s->name, s->position_update == MRN_XUPDATE_GRID ? "PIC" : "custom");
    break;
  case MRN_VUPDATE_FLIP:
    snprintf(s->name, sizeof s->name, "%sFLIP", prefix);
    break;
  case MRN_VUPDATE_BLEND:
    snprintf(s->name, sizeof s->name, "%sFLIP%g", prefix, s->flip_fraction);
    break;
  }
}

int mrn_stress_update_from_name(const char *name, mrn_stress_update_kind *out) {
  for (int i = 0; stress_names[i]; i++)
    if (strcmp(stress_names[i], name) == 0) {
      *out = (mrn_stress_update_kind)i;
      return 1;
    }
  return 0;
}
