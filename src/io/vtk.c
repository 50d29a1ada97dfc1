#include "io/vtk.h"

#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/xml_writer.h"


/* ---- what the file holds ------------------------------------------------ */

/* one DataArray of the file, whether point data, points or cells */
typedef enum { SRC_DATA, SRC_CONNECTIVITY, SRC_OFFSETS } block_source;

typedef struct block {
  const char *name;
  const char *type; /* VTK type name */
  int ncomp;        /* 0: no NumberOfComponents attribute (cell arrays) */
  size_t elem;      /* bytes per value */
  block_source source;
  mrn_vtk_type vtype;
  const void *data; /* or NULL and made by fill (mrn_vtk_array) */
  void (*fill)(const void *ctx, size_t first, size_t count, void *out);
  const void *ctx;
  uint64_t nbytes;
  uint64_t offset; /* position in the appended section */
} block;

/* reject arrays the file could not describe, before any file is created */
static int check_arrays(const char *path, size_t n, const double *points, const mrn_vtk_array *arrays,
                        int narrays) {
  if (n > 0 && !points) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': no point coordinates", path);
  if (narrays > 0 && !arrays) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': no arrays", path);
  for (int i = 0; i < narrays; i++) {
    const mrn_vtk_array *a = &arrays[i];
    const char *name = a->name ? a->name : "(unnamed)";
    if (!a->name || !*a->name)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array %d has no name", path, i + 1);
    if (a->ncomp < 1)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' has %d components", path, name, a->ncomp);
    if (a->type != MRN_VTK_FLOAT64 && a->type != MRN_VTK_INT32 && a->type != MRN_VTK_INT64)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' has an unknown type", path, name);
    if (n > 0 && !a->data && !a->fill)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' has no data", path, name);
    if (a->ncomp > MRN_VTK_FILL_VALUES)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' has %d components, at most %d", path, name,
                            a->ncomp, MRN_VTK_FILL_VALUES);
    if ((uint64_t)n > UINT64_MAX / 8 / (uint64_t)a->ncomp)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' is too large", path, name);
  }
  return MRN_OK;
}

/* lay out the blocks in file order: point data, points, connectivity, offsets */
static void plan_blocks(block *b, size_t n, const double *points, const mrn_vtk_array *arrays, int narrays) {
  int k = 0;
  for (int i = 0; i < narrays; i++, k++)
    b[k] = (block){arrays[i].name, mrn_vtk_type_name(arrays[i].type), arrays[i].ncomp,
                   mrn_vtk_type_size(arrays[i].type), SRC_DATA, arrays[i].type, arrays[i].data, arrays[i].fill,
                   arrays[i].ctx, 0, 0};
  b[k++] = (block){"Points", "Float64", 3, 8, SRC_DATA, MRN_VTK_FLOAT64, points, NULL, NULL, 0, 0};
  b[k++] = (block){"connectivity", "Int64", 0, 8, SRC_CONNECTIVITY, MRN_VTK_INT64, NULL, NULL, NULL, 0, 0};
  b[k++] = (block){"offsets", "Int64", 0, 8, SRC_OFFSETS, MRN_VTK_INT64, NULL, NULL, NULL, 0, 0};
  uint64_t offset = 0;
  for (int i = 0; i < k; i++) {
    uint64_t ncomp = b[i].ncomp ? (uint64_t)b[i].ncomp : 1;
    b[i].nbytes = (uint64_t)n * ncomp * b[i].elem;
    b[i].offset = offset;
    offset += sizeof(uint64_t) + b[i].nbytes;
  }
}

/* The values of points [first, first + count) of a data block (count at most
 * MRN_VTK_FILL_POINTS(ncomp)): where they are held, or made into buf (room
 * for MRN_VTK_FILL_VALUES values of 8 bytes). */
static const void *block_values(const block *b, size_t first, size_t count, void *buf) {
  if (b->data) return (const char *)b->data + first * (size_t)b->ncomp * b->elem;
  b->fill(b->ctx, first, count, buf);
  return buf;
}

/* ---- XML structure ------------------------------------------------------ */

static void w_array_open(mrn_xml_writer *w, const block *b, mrn_vtk_encoding enc) {
  mrn_xw_printf(w, "        <DataArray type=\"%s\" Name=\"", b->type);
  mrn_xw_attr(w, b->name);
  mrn_xw_printf(w, "\"");
  if (b->ncomp) mrn_xw_printf(w, " NumberOfComponents=\"%d\"", b->ncomp);
  if (enc == MRN_VTK_BINARY)
    mrn_xw_printf(w, " format=\"appended\" offset=\"%" PRIu64 "\"/>\n", b->offset);
  else
    mrn_xw_printf(w, " format=\"ascii\">\n");
}

/* ASCII values of one array, one point per line (cells: 16 per line); buf
 * as for block_values */
static void w_ascii_values(mrn_xml_writer *w, const block *b, size_t n, void *buf) {
  size_t per_line = b->ncomp ? (size_t)b->ncomp : 16;
  size_t total = b->ncomp ? n * (size_t)b->ncomp : n;
  const void *vals = NULL;
  size_t base = 0, held = 0; /* vals holds the values [base, base + held) */
  for (size_t i = 0; i < total && !w->file.err; i++) {
    int last = (i + 1) % per_line == 0 || i + 1 == total;
    const char *sep = last ? "\n" : " ";
    if (b->source == SRC_CONNECTIVITY) {
      mrn_xw_printf(w, "%" PRIu64 "%s", (uint64_t)i, sep);
      continue;
    }
    if (b->source == SRC_OFFSETS) {
      mrn_xw_printf(w, "%" PRIu64 "%s", (uint64_t)i + 1, sep);
      continue;
    }
    if (i >= base + held) { /* the next chunk of points */
      const size_t first = i / (size_t)b->ncomp, left = n - first, most = MRN_VTK_FILL_POINTS(b->ncomp);
      const size_t count = left < most ? left : most;
      vals = block_values(b, first, count, buf);
      base = i;
      held = count * (size_t)b->ncomp;
    }
    const size_t k = i - base;
    if (b->vtype == MRN_VTK_INT32)
      mrn_xw_printf(w, "%d%s", (int)((const int32_t *)vals)[k], sep);
    else if (b->vtype == MRN_VTK_INT64)
      mrn_xw_printf(w, "%lld%s", (long long)((const int64_t *)vals)[k], sep);
    else
      mrn_xw_printf(w, "%.17g%s", ((const double *)vals)[k], sep);
  }
}

static void w_array(mrn_xml_writer *w, const block *b, size_t n, mrn_vtk_encoding enc, void *buf) {
  w_array_open(w, b, enc);
  if (enc == MRN_VTK_ASCII) {
    w_ascii_values(w, b, n, buf);
    mrn_xw_printf(w, "        </DataArray>\n");
  }
}

static void w_structure(mrn_xml_writer *w, const block *b, int narrays, size_t n, mrn_vtk_encoding enc,
                        void *buf) {
  mrn_xw_printf(w, "<?xml version=\"1.0\"?>\n");
  mrn_xw_printf(w, "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
  mrn_xw_printf(w, "  <PolyData>\n");
  mrn_xw_printf(w, "    <Piece NumberOfPoints=\"%zu\" NumberOfVerts=\"%zu\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
              "NumberOfPolys=\"0\">\n", n, n);
  mrn_xw_printf(w, "      <PointData>\n");
  for (int i = 0; i < narrays; i++) w_array(w, &b[i], n, enc, buf);
  mrn_xw_printf(w, "      </PointData>\n");
  mrn_xw_printf(w, "      <Points>\n");
  w_array(w, &b[narrays], n, enc, buf);
  mrn_xw_printf(w, "      </Points>\n");
  mrn_xw_printf(w, "      <Verts>\n");
  w_array(w, &b[narrays + 1], n, enc, buf);
  w_array(w, &b[narrays + 2], n, enc, buf);
  mrn_xw_printf(w, "      </Verts>\n");
  mrn_xw_printf(w, "    </Piece>\n");
  mrn_xw_printf(w, "  </PolyData>\n");
}

/* ---- appended binary data ---------------------------------------------- */

/* the vertex cells are generated, not stored: fill a buffer chunk by chunk
 * (connectivity 0..n-1, offsets 1..n) */
static void w_cell_values(mrn_xml_writer *w, int64_t first, size_t n, int64_t *buf, unsigned char *scratch) {
  for (size_t done = 0; done < n && !w->file.err;) {
    size_t m = n - done < MRN_VTK_FILL_VALUES ? n - done : MRN_VTK_FILL_VALUES;
    for (size_t i = 0; i < m; i++) buf[i] = first + (int64_t)(done + i);
    mrn_xw_le(w, buf, sizeof(int64_t), m, scratch);
    done += m;
  }
}

static void w_block(mrn_xml_writer *w, const block *b, size_t n, int64_t *buf, unsigned char *scratch) {
  mrn_xw_le(w, &b->nbytes, sizeof b->nbytes, 1, scratch);
  if (b->source == SRC_CONNECTIVITY) {
    w_cell_values(w, 0, n, buf, scratch);
  } else if (b->source == SRC_OFFSETS) {
    w_cell_values(w, 1, n, buf, scratch);
  } else { /* held or made on demand, a chunk of points at a time */
    const size_t most = MRN_VTK_FILL_POINTS(b->ncomp);
    for (size_t first = 0; first < n && !w->file.err; first += most) {
      const size_t count = n - first < most ? n - first : most;
      mrn_xw_le(w, block_values(b, first, count, buf), b->elem, count * (size_t)b->ncomp, scratch);
    }
  }
}

static int w_appended(mrn_xml_writer *w, const block *b, int nblocks, size_t n, int64_t *buf) {
  unsigned char *scratch = mrn_host_is_little_endian() ? NULL : malloc(MRN_XW_CHUNK_VALUES * 8);
  if (!mrn_host_is_little_endian() && !scratch) return ENOMEM;
  mrn_xw_printf(w, "  <AppendedData encoding=\"raw\">\n   _");
  for (int i = 0; i < nblocks && !w->file.err; i++) w_block(w, &b[i], n, buf, scratch);
  mrn_xw_printf(w, "\n  </AppendedData>\n");
  free(scratch);
  return 0;
}

/* ---- .vtp --------------------------------------------------------------- */

int mrn_vtp_write(const char *path, size_t npoints, const double *points, const mrn_vtk_array *arrays,
                  int narrays, mrn_vtk_encoding encoding) {
  if (!path) return mrn_error_code(MRN_ERR_IO, "cannot write a VTK file without a path");
  if (narrays < 0) narrays = 0;
  int rc = check_arrays(path, npoints, points, arrays, narrays);
  if (rc != MRN_OK) return rc;
  int nblocks = narrays + 3;
  block *blocks = malloc((size_t)nblocks * sizeof *blocks);
  /* one buffer for the cells, the values made on demand and the ASCII chunks */
  int64_t *buf = malloc(MRN_VTK_FILL_VALUES * sizeof *buf);
  if (!blocks || !buf) {
    free(blocks);
    free(buf);
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", path);
  }
  plan_blocks(blocks, npoints, points, arrays, narrays);

  mrn_xml_writer w;
  rc = mrn_xw_open(&w, path);
  if (rc == MRN_OK) {
    w_structure(&w, blocks, narrays, npoints, encoding, buf);
    if (encoding == MRN_VTK_BINARY && !w.file.err) {
      int err = w_appended(&w, blocks, nblocks, npoints, buf);
      if (err && !w.file.err) w.file.err = err;
    }
    mrn_xw_printf(&w, "</VTKFile>\n");
    rc = mrn_xw_finish(&w);
  }
  free(blocks);
  free(buf);
  return rc;
}

/* ---- .pvd --------------------------------------------------------------- */

void mrn_pvd_init(mrn_pvd *pvd, const char *path) {
  memset(pvd, 0, sizeof *pvd);
  pvd->path = path ? strdup(path) : NULL;
}

void mrn_pvd_free(mrn_pvd *pvd) {
  for (int i = 0; i < pvd->count; i++) free(pvd->files[i]);
  free(pvd->files);
  free(pvd->times);
  free(pvd->path);
  memset(pvd, 0, sizeof *pvd);
}

static int pvd_rewrite(const mrn_pvd *pvd) {
  mrn_xml_writer w;
  int rc = mrn_xw_open(&w, pvd->path);
  if (rc != MRN_OK) return rc;
  mrn_xw_printf(&w, "<?xml version=\"1.0\"?>\n");
  mrn_xw_printf(&w, "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
  mrn_xw_printf(&w, "  <Collection>\n");
  for (int i = 0; i < pvd->count; i++) {
    mrn_xw_printf(&w, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"", pvd->times[i]);
    mrn_xw_attr(&w, pvd->files[i]);
    mrn_xw_printf(&w, "\"/>\n");
  }
  mrn_xw_printf(&w, "  </Collection>\n");
  mrn_xw_printf(&w, "</VTKFile>\n");
  return mrn_xw_finish(&w);
}

static int pvd_reserve(mrn_pvd *pvd) {
  if (pvd->count < pvd->cap) return 0;
  int cap = pvd->cap ? 2 * pvd->cap : 16;
  double *times = realloc(pvd->times, (size_t)cap * sizeof *times);
  if (!times) return -1;
  pvd->times = times;
  char **files = realloc(pvd->files, (size_t)cap * sizeof *files);
  if (!files) return -1;
  pvd->files = files;
  pvd->cap = cap;
  return 0;
}

int mrn_pvd_add(mrn_pvd *pvd, double time, const char *relative_file) {
  if (!pvd->path) return mrn_error_code(MRN_ERR_IO, "cannot update a collection without a path");
  char *file = relative_file ? strdup(relative_file) : NULL;
  if (!file || pvd_reserve(pvd) != 0) {
    free(file);
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", pvd->path);
  }
  pvd->times[pvd->count] = time;
  pvd->files[pvd->count] = file;
  pvd->count++;
  int rc = pvd_rewrite(pvd);
  if (rc != MRN_OK) {
    /* leave the collection as it was, so a retry does not list the file twice */
    pvd->count--;
    free(pvd->files[pvd->count]);
  }
  return rc;
}
