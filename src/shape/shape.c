#include "shape/shape.h"

#include <string.h>

static const mrn_shape_info shapes[MRN_SHAPE_KIND_COUNT] = {
    {MRN_SHAPE_LINEAR, "linear", 2,
     "piecewise-linear hat functions (C0; prone to cell-crossing noise, 000 §2.3)"},
    {MRN_SHAPE_GIMP, "gimp", 3,
     "uGIMP: hat functions convolved with the particle's initial extent (Bardenhagen & Kober)"},
    {MRN_SHAPE_QUADRATIC_BSPLINE, "quadratic_bspline", 3,
     "quadratic B-spline, C1, support of 3 cells per axis (002 §4, Eq. 52)"},
    {MRN_SHAPE_CUBIC_BSPLINE, "cubic_bspline", 4,
     "cubic B-spline, C2, support of 4 cells per axis (000 §2.3; 002 Fig. 4)"},
    {MRN_SHAPE_CPDI, "cpdi", 2,
     "CPDI: linear hat functions averaged over the particle's domain, tracked from F (Sadeghirad et al. 2011)"},
    {MRN_SHAPE_CPDI2, "cpdi2", 2,
     "CPDI2 (2D): linear hat functions averaged over a quadrilateral whose corners move with the grid "
     "(Sadeghirad et al. 2013)"},
    {MRN_SHAPE_CPGIMP, "cpgimp", 3,
     "cpGIMP: uGIMP with the particle's axis-aligned box stretched by the diagonal of F (Wallstedt & Guilkey 2008)"},
};

static const char *const names[] = {"linear", "gimp", "quadratic_bspline", "cubic_bspline", "cpdi", "cpdi2", "cpgimp",
                                    NULL};
static const char *const boundary_names[] = {"extended", "truncated", "modified", "wls", NULL};

const char *const *mrn_kernel_boundary_names(void) { return boundary_names; }

int mrn_kernel_boundary_from_name(const char *name, mrn_kernel_boundary *out) {
  for (int i = 0; boundary_names[i]; i++)
    if (strcmp(boundary_names[i], name) == 0) {
      *out = (mrn_kernel_boundary)i;
      return 1;
    }
  return 0;
}

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
