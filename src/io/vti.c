#include "io/vti.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/xml_writer.h"

/* ---- a stream that remembers its first failure ------------------------- */

/* ---- the image's shape ------------------------------------------------- */

/* the domain nodes: how many along each axis, and in all */
typedef struct image {
  int np[3];      /* points per axis (1 along z in 2D) */
  size_t npoints;
} image;

static image image_of(const mrn_grid *g) {
  image im;
  im.npoints = 1;
  for (int d = 0; d < 3; d++) {
    im.np[d] = d < g->dim ? g->ncell[d] + 1 : 1;
    im.npoints *= (size_t)im.np[d];
  }
  return im;
}

/* the grid's linear index of the first node of row (j, k) */
static size_t row_start(const mrn_grid *g, int j, int k) { return mrn_grid_index(g, 0, j, k); }

static int check_input(const char *path, const mrn_grid *g, const mrn_vtk_array *arrays, int narrays) {
  if (!g || (g->dim != 2 && g->dim != 3) || g->n == 0)
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': no grid", path);
  if (narrays > 0 && !arrays) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': no arrays", path);
  for (int i = 0; i < narrays; i++) {
    const mrn_vtk_array *a = &arrays[i];
    if (!a->name || !*a->name)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array %d has no name", path, i + 1);
    if (a->ncomp < 1 || a->ncomp > 64)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' has %d components", path, a->name,
                            a->ncomp);
    if (a->type != MRN_VTK_FLOAT64 && a->type != MRN_VTK_INT32 && a->type != MRN_VTK_INT64)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' has an unknown type", path, a->name);
    if (!a->data) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' has no data", path, a->name);
  }
  return MRN_OK;
}

/* ---- XML structure ------------------------------------------------------ */

static void w_header(mrn_xml_writer *w, const mrn_grid *g, const image *im, double time) {
  /* 2D: a one-point-thick image at z = 0; a spacing of 1 rather than 0 keeps
   * VTK's filters (and its bounds) well defined */
  double spacing_z = g->dim == 3 ? g->cell : 1.0;
  mrn_xw_printf(w, "<?xml version=\"1.0\"?>\n");
  mrn_xw_printf(w, "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
  mrn_xw_printf(w, "  <ImageData WholeExtent=\"0 %d 0 %d 0 %d\"", im->np[0] - 1, im->np[1] - 1, im->np[2] - 1);
  mrn_xw_printf(w, " Origin=\"%.17g %.17g %.17g\"", g->origin[0], g->origin[1], g->dim == 3 ? g->origin[2] : 0.0);
  mrn_xw_printf(w, " Spacing=\"%.17g %.17g %.17g\">\n", g->cell, g->cell, spacing_z);
  if (!isnan(time)) {
    mrn_xw_printf(w, "    <FieldData>\n");
    mrn_xw_printf(w, "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">");
    mrn_xw_printf(w, "%.17g</DataArray>\n", time);
    mrn_xw_printf(w, "    </FieldData>\n");
  }
  mrn_xw_printf(w, "    <Piece Extent=\"0 %d 0 %d 0 %d\">\n", im->np[0] - 1, im->np[1] - 1, im->np[2] - 1);
}

static void w_array_tag(mrn_xml_writer *w, const mrn_vtk_array *a, mrn_vtk_encoding enc, uint64_t offset) {
  mrn_xw_printf(w, "        <DataArray type=\"%s\" Name=\"", mrn_vtk_type_name(a->type));
  mrn_xw_attr(w, a->name);
  mrn_xw_printf(w, "\" NumberOfComponents=\"%d\"", a->ncomp);
  if (enc == MRN_VTK_BINARY)
    mrn_xw_printf(w, " format=\"appended\" offset=\"%" PRIu64 "\"/>\n", offset);
  else
    mrn_xw_printf(w, " format=\"ascii\">\n");
}

/* one node per line */
static void w_ascii_values(mrn_xml_writer *w, const mrn_grid *g, const image *im, const mrn_vtk_array *a) {
  for (int k = 0; k < im->np[2]; k++)
    for (int j = 0; j < im->np[1] && !w->file.err; j++) {
      size_t first = row_start(g, j, k) * (size_t)a->ncomp;
      size_t count = (size_t)im->np[0] * (size_t)a->ncomp;
      for (size_t i = 0; i < count && !w->file.err; i++) {
        const char *sep = (i + 1) % (size_t)a->ncomp == 0 ? "\n" : " ";
        if (a->type == MRN_VTK_INT32)
          mrn_xw_printf(w, "%d%s", (int)((const int32_t *)a->data)[first + i], sep);
        else if (a->type == MRN_VTK_INT64)
          mrn_xw_printf(w, "%lld%s", (long long)((const int64_t *)a->data)[first + i], sep);
        else
          mrn_xw_printf(w, "%.17g%s", ((const double *)a->data)[first + i], sep);
      }
    }
}

static uint64_t array_bytes(const image *im, const mrn_vtk_array *a) {
  return (uint64_t)im->npoints * (uint64_t)a->ncomp * mrn_vtk_type_size(a->type);
}

static void w_point_data(mrn_xml_writer *w, const mrn_grid *g, const image *im, const mrn_vtk_array *arrays, int narrays,
                         mrn_vtk_encoding enc) {
  mrn_xw_printf(w, "      <PointData>\n");
  uint64_t offset = 0;
  for (int i = 0; i < narrays; i++) {
    w_array_tag(w, &arrays[i], enc, offset);
    offset += sizeof(uint64_t) + array_bytes(im, &arrays[i]);
    if (enc == MRN_VTK_ASCII) {
      w_ascii_values(w, g, im, &arrays[i]);
      mrn_xw_printf(w, "        </DataArray>\n");
    }
  }
  mrn_xw_printf(w, "      </PointData>\n");
  mrn_xw_printf(w, "      <CellData>\n      </CellData>\n");
  mrn_xw_printf(w, "    </Piece>\n");
  mrn_xw_printf(w, "  </ImageData>\n");
}

/* ---- appended binary data ---------------------------------------------- */

/* Each x-row of domain nodes is contiguous in the grid's arrays, so a block
 * is written row by row without gathering the whole array first. */
static void w_block(mrn_xml_writer *w, const mrn_grid *g, const image *im, const mrn_vtk_array *a, unsigned char *scratch) {
  uint64_t nbytes = array_bytes(im, a);
  mrn_xw_le(w, &nbytes, sizeof nbytes, 1, scratch);
  size_t elem = mrn_vtk_type_size(a->type);
  size_t row_values = (size_t)im->np[0] * (size_t)a->ncomp;
  const unsigned char *base = a->data;
  for (int k = 0; k < im->np[2]; k++)
    for (int j = 0; j < im->np[1] && !w->file.err; j++)
      mrn_xw_le(w, base + row_start(g, j, k) * (size_t)a->ncomp * elem, elem, row_values, scratch);
}

static void w_appended(mrn_xml_writer *w, const mrn_grid *g, const image *im, const mrn_vtk_array *arrays, int narrays) {
  unsigned char *scratch = NULL;
  if (!mrn_host_is_little_endian()) {
    int widest = 1;
    for (int i = 0; i < narrays; i++)
      if (arrays[i].ncomp > widest) widest = arrays[i].ncomp;
    scratch = malloc((size_t)im->np[0] * (size_t)widest * 8 + 8);
    if (!scratch) {
      w->file.err = ENOMEM;
      return;
    }
  }
  mrn_xw_printf(w, "  <AppendedData encoding=\"raw\">\n   _");
  for (int i = 0; i < narrays && !w->file.err; i++) w_block(w, g, im, &arrays[i], scratch);
  mrn_xw_printf(w, "\n  </AppendedData>\n");
  free(scratch);
}

/* ---- .vti --------------------------------------------------------------- */

int mrn_vti_write(const char *path, const mrn_grid *g, double time, const mrn_vtk_array *arrays, int narrays,
                  mrn_vtk_encoding encoding) {
  if (!path) return mrn_error_code(MRN_ERR_IO, "cannot write a VTK file without a path");
  if (narrays < 0) narrays = 0;
  int rc = check_input(path, g, arrays, narrays);
  if (rc != MRN_OK) return rc;
  image im = image_of(g);
  mrn_xml_writer w;
  rc = mrn_xw_open(&w, path);
  if (rc != MRN_OK) return rc;
  w_header(&w, g, &im, time);
  w_point_data(&w, g, &im, arrays, narrays, encoding);
  if (encoding == MRN_VTK_BINARY) w_appended(&w, g, &im, arrays, narrays);
  mrn_xw_printf(&w, "</VTKFile>\n");
  return mrn_xw_finish(&w);
}

int mrn_vti_write_grid(const char *path, const mrn_grid *g, double time, mrn_vtk_encoding encoding) {
  if (!g) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': no grid", path ? path : "");
  const mrn_vtk_array arrays[] = {
      {.name = "mass", .ncomp = 1, .type = MRN_VTK_FLOAT64, .data = g->mass},
      {.name = "velocity", .ncomp = 3, .type = MRN_VTK_FLOAT64, .data = g->vel},
      {.name = "force", .ncomp = 3, .type = MRN_VTK_FLOAT64, .data = g->force},
  };
  return mrn_vti_write(path, g, time, arrays, 3, encoding);
}
