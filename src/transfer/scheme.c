#include "transfer/scheme.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

static const char *const preset_names[] = {"PIC",   "FLIP",  "FLIPX", "NFLIP", "NFLIPX", "APIC",
                                           "AFLIP", "AFLIPX", "ANFLIP", "ANFLIPX", "TPIC", "TFLIP",
                                           "TFLIPX", "XPIC(m)", "MLS", NULL};
static const char *const stress_names[] = {"USF", "USL", "MUSL", "USAVG", NULL};
static const char *const vupdate_names[] = {"PIC", "FLIP", "blend", "XPIC", NULL};
static const char *const xupdate_names[] = {"grid", "particle", "XPIC", NULL};
static const char *const vgrid_names[] = {"plain", "affine", "taylor", NULL};
static const char *const volumetric_names[] = {"standard", "fbar", NULL};
static const char *const holds_names[] = {"grid", "particles", NULL};

const char *const *mrn_scheme_preset_names(void) { return preset_names; }
const char *const *mrn_stress_update_names(void) { return stress_names; }
const char *const *mrn_velocity_update_names(void) { return vupdate_names; }
const char *const *mrn_position_update_names(void) { return xupdate_names; }
const char *const *mrn_grid_velocity_names(void) { return vgrid_names; }
const char *const *mrn_volumetric_names(void) { return volumetric_names; }
const char *const *mrn_holds_names(void) { return holds_names; }

int mrn_name_index(const char *const *names, const char *name) {
  for (int i = 0; names[i]; i++)
    if (strcmp(names[i], name) == 0) return i;
  return -1;
}

void mrn_scheme_default(mrn_scheme *s) {
  memset(s, 0, sizeof *s);
  s->grid_velocity = MRN_VGRID_PLAIN;
  s->velocity_update = MRN_VUPDATE_FLIP;
  s->position_update = MRN_XUPDATE_GRID;
  s->flip_fraction = 1.0;
  s->xpic_order = 1;
  s->stress_update = MRN_STRESS_USF;
  snprintf(s->name, sizeof s->name, "FLIP");
}

/* "0.99" -> 0.99 in [0, 1]; the whole text must be the number */
static int parse_fraction(const char *text, double *x) {
  char *end;
  double v = strtod(text, &end);
  if (end == text || *end != '\0' || !(v >= 0.0 && v <= 1.0)) return 0;
  *x = v;
  return 1;
}

/* "XPIC(3)" or "XPIC3" -> 3 */
static int parse_xpic(const char *name, int *m) {
  if (strncmp(name, "XPIC", 4) != 0) return 0;
  const char *p = name + 4;
  int paren = *p == '(';
  if (paren) p++;
  char *end;
  long v = strtol(p, &end, 10);
  if (end == p) return 0;
  if (paren && *end++ != ')') return 0;
  if (*end != '\0' || v < 1 || v > MRN_XPIC_MAX_ORDER) return 0;
  *m = (int)v;
  return 1;
}

static int unknown(const char *name) {
  return mrn_error("unknown strategy '%s' (valid: PIC, FLIP, FLIPX as FLIP<X> with X in [0,1] e.g. FLIP0.99, NFLIP, "
                   "NFLIPX, APIC, AFLIP, AFLIPX, ANFLIP, ANFLIPX, TPIC, TFLIP, TFLIPX, XPIC(m) with m in 1..%d, MLS)",
                   name, MRN_XPIC_MAX_ORDER);
}

int mrn_scheme_from_preset(const char *name, mrn_scheme *s) {
  mrn_scheme out = *s;
  out.mls_gradient = 0;
  out.flip_fraction = 1.0;
  out.xpic_order = 1;
  int m;
  if (parse_xpic(name, &m)) {
    out.grid_velocity = MRN_VGRID_PLAIN;
    out.velocity_update = MRN_VUPDATE_XPIC;
    out.position_update = MRN_XUPDATE_XPIC;
    out.xpic_order = m;
  } else if (strcmp(name, "MLS") == 0) {
    out.grid_velocity = MRN_VGRID_AFFINE;
    out.velocity_update = MRN_VUPDATE_PIC;
    out.position_update = MRN_XUPDATE_GRID;
    out.mls_gradient = 1;
  } else {
    /* [A|T] then PIC, or [A|T][N]FLIP[X] */
    const char *p = name;
    out.grid_velocity = MRN_VGRID_PLAIN;
    if (*p == 'A') { out.grid_velocity = MRN_VGRID_AFFINE; p++; }
    else if (*p == 'T') { out.grid_velocity = MRN_VGRID_TAYLOR; p++; }
    if (strcmp(p, "PIC") == 0) {
      out.velocity_update = MRN_VUPDATE_PIC;
      out.position_update = MRN_XUPDATE_GRID;
      out.flip_fraction = 0.0;
    } else {
      int natural = 0;
      if (*p == 'N') { natural = 1; p++; }
      if (strncmp(p, "FLIP", 4) != 0) return unknown(name);
      p += 4;
      double x = 1.0;
      if (*p && !parse_fraction(p, &x)) return unknown(name);
      out.velocity_update = x == 1.0 ? MRN_VUPDATE_FLIP : MRN_VUPDATE_BLEND;
      out.flip_fraction = x;
      out.position_update = natural ? MRN_XUPDATE_PARTICLE : MRN_XUPDATE_GRID;
    }
  }
  snprintf(out.name, sizeof out.name, "%s", name);
  *s = out;
  return MRN_OK;
}

int mrn_scheme_validate(const mrn_scheme *s) {
  if ((s->position_update == MRN_XUPDATE_XPIC) != (s->velocity_update == MRN_VUPDATE_XPIC))
    return mrn_error("the XPIC position update (000, Eq. 41) goes with the XPIC velocity update (000, Eq. 40)");
  if (s->velocity_update == MRN_VUPDATE_XPIC && (s->xpic_order < 1 || s->xpic_order > MRN_XPIC_MAX_ORDER))
    return mrn_error("xpic_order = %d is outside 1..%d", s->xpic_order, MRN_XPIC_MAX_ORDER);
  if (!(s->flip_fraction >= 0.0 && s->flip_fraction <= 1.0))
    return mrn_error("flip_fraction = %s is outside [0, 1]", mrn_num(s->flip_fraction).s);
  return MRN_OK;
}

void mrn_scheme_describe(mrn_scheme *s) {
  static const char *const grid_prefix[] = {"", "A", "T"};
  const char *g = grid_prefix[s->grid_velocity];
  const char *n = s->position_update == MRN_XUPDATE_PARTICLE ? "N" : "";
  switch (s->velocity_update) {
  case MRN_VUPDATE_PIC:
    if (s->mls_gradient && s->grid_velocity == MRN_VGRID_AFFINE) snprintf(s->name, sizeof s->name, "MLS");
    else snprintf(s->name, sizeof s->name, "%s%sPIC", n, g);
    break;
  case MRN_VUPDATE_FLIP:
    snprintf(s->name, sizeof s->name, "%s%sFLIP", g, n);
    break;
  case MRN_VUPDATE_BLEND:
    snprintf(s->name, sizeof s->name, "%s%sFLIP%g", g, n, s->flip_fraction);
    break;
  case MRN_VUPDATE_XPIC:
    snprintf(s->name, sizeof s->name, "%sXPIC(%d)", g, s->xpic_order);
    break;
  }
}

int mrn_stress_update_from_name(const char *name, mrn_stress_update_kind *out) {
  int i = mrn_name_index(stress_names, name);
  if (i < 0) return 0;
  *out = (mrn_stress_update_kind)i;
  return 1;
}
