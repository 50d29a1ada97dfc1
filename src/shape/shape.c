#include "shape/shape.h"

#include <string.h>

static const mrn_shape_info shapes[MRN_SHAPE_KIND_COUNT] = {
    {MRN_SHAPE_LINEAR, "linear", 2,
     "piecewise-linear hat functions (C0; prone to cell-crossing noise, 000 §2.3)"},
    {MRN_SHAPE_QUADRATIC_BSPLINE, "quadratic_bspline", 3,
     "quadratic B-spline, C1, support of 3 cells per axis (002, Eq. 6)"},
};

static const char *const names[] = {"linear", "quadratic_bspline", NULL};

const mrn_shape_info *mrn_shape_info_of(mrn_shape_kind k) {
  return k < MRN_SHAPE_KIND_COUNT ? &shapes[k] : NULL;
}

int mrn_shape_from_name(const char *name, mrn_shape_kind *out) {
  for (int i = 0; i < MRN_SHAPE_KIND_COUNT; i++)
    if (strcmp(shapes[i].name, name) == 0) {
      *out = shapes[i].kind;
      return 1;
    }
  return 0;
}

const char *const *mrn_shape_names(void) { return names; }
