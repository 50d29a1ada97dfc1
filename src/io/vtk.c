#include "io/vtk.h"

#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "io/atomic_file.h"

/* values generated per buffer fill for the vertex cells and for byte swapping */
#define CHUNK_VALUES 65536

/* ---- a stream that remembers its first failure ------------------------- */

/* Every write goes through these helpers so the first failing call keeps its
 * errno (ENOSPC, EDQUOT, ...) for the error message; later calls are skipped
 * because the file is lost anyway. */
typedef struct vtk_writer {
  mrn_atomic_file file;
  int err;
} vtk_writer;

static void w_fail(vtk_writer *w) {
  if (!w->err) w->err = errno ? errno : EIO;
}

static void w_bytes(vtk_writer *w, const void *data, size_t size) {
  if (w->err || size == 0) return;
  errno = 0;
  if (fwrite(data, 1, size, w->file.fp) != size) w_fail(w);
}

static void w_printf(vtk_writer *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void w_printf(vtk_writer *w, const char *fmt, ...) {
  if (w->err) return;
  va_list ap;
  va_start(ap, fmt);
  errno = 0;
  if (vfprintf(w->file.fp, fmt, ap) < 0) w_fail(w);
  va_end(ap);
}

/* an attribute value with the XML special characters escaped */
static void w_attr(vtk_writer *w, const char *s) {
  for (; *s && !w->err; s++) {
    switch (*s) {
      case '&': w_printf(w, "&amp;"); break;
      case '<': w_printf(w, "&lt;"); break;
      case '>': w_printf(w, "&gt;"); break;
      case '"': w_printf(w, "&quot;"); break;
      default:
        errno = 0;
        if (putc(*s, w->file.fp) == EOF) w_fail(w);
    }
  }
}

static int w_open(vtk_writer *w, const char *path) {
  w->err = 0;
  return mrn_atomic_open(&w->file, path);
}

/* commit the file, or drop it and report the first write error */
static int w_finish(vtk_writer *w) {
  if (w->err) {
    int rc = mrn_error_code(MRN_ERR_IO, "cannot write '%s': %s", w->file.final_path, strerror(w->err));
    mrn_atomic_abort(&w->file);
    return rc;
  }
  return mrn_atomic_commit(&w->file);
}

/* ---- little-endian raw data -------------------------------------------- */

static int host_is_little_endian(void) {
  const uint16_t one = 1;
  return *(const unsigned char *)&one == 1;
}

/* `count` values of `elem` bytes each, in little-endian order. On the usual
 * little-endian hosts this is one fwrite of the whole array; a big-endian
 * host swaps through a buffer in chunks. */
static void w_le(vtk_writer *w, const void *data, size_t elem, size_t count, unsigned char *scratch) {
  if (host_is_little_endian()) {
    w_bytes(w, data, elem * count);
    return;
  }
  const unsigned char *src = data;
  while (count > 0 && !w->err) {
    size_t m = count < CHUNK_VALUES ? count : CHUNK_VALUES;
    for (size_t i = 0; i < m; i++)
      for (size_t b = 0; b < elem; b++) scratch[i * elem + b] = src[i * elem + elem - 1 - b];
    w_bytes(w, scratch, m * elem);
    src += m * elem;
    count -= m;
  }
}

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
  const void *data;
  uint64_t nbytes;
  uint64_t offset; /* position in the appended section */
} block;

static const char *type_name(mrn_vtk_type t) {
  switch (t) {
    case MRN_VTK_INT32: return "Int32";
    case MRN_VTK_INT64: return "Int64";
    default: return "Float64";
  }
}

static size_t type_size(mrn_vtk_type t) { return t == MRN_VTK_INT32 ? 4 : 8; }

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
    if (n > 0 && !a->data)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' has no data", path, name);
    if ((uint64_t)n > UINT64_MAX / 8 / (uint64_t)a->ncomp)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': array '%s' is too large", path, name);
  }
  return MRN_OK;
}

/* lay out the blocks in file order: point data, points, connectivity, offsets */
static void plan_blocks(block *b, size_t n, const double *points, const mrn_vtk_array *arrays, int narrays) {
  int k = 0;
  for (int i = 0; i < narrays; i++, k++)
    b[k] = (block){arrays[i].name, type_name(arrays[i].type), arrays[i].ncomp, type_size(arrays[i].type),
                   SRC_DATA, arrays[i].type, arrays[i].data, 0, 0};
  b[k++] = (block){"Points", "Float64", 3, 8, SRC_DATA, MRN_VTK_FLOAT64, points, 0, 0};
  b[k++] = (block){"connectivity", "Int64", 0, 8, SRC_CONNECTIVITY, MRN_VTK_INT64, NULL, 0, 0};
  b[k++] = (block){"offsets", "Int64", 0, 8, SRC_OFFSETS, MRN_VTK_INT64, NULL, 0, 0};
  uint64_t offset = 0;
  for (int i = 0; i < k; i++) {
    uint64_t ncomp = b[i].ncomp ? (uint64_t)b[i].ncomp : 1;
    b[i].nbytes = (uint64_t)n * ncomp * b[i].elem;
    b[i].offset = offset;
    offset += sizeof(uint64_t) + b[i].nbytes;
  }
}

/* ---- XML structure ------------------------------------------------------ */

static void w_array_open(vtk_writer *w, const block *b, mrn_vtk_encoding enc) {
  w_printf(w, "        <DataArray type=\"%s\" Name=\"", b->type);
  w_attr(w, b->name);
  w_printf(w, "\"");
  if (b->ncomp) w_printf(w, " NumberOfComponents=\"%d\"", b->ncomp);
  if (enc == MRN_VTK_BINARY)
    w_printf(w, " format=\"appended\" offset=\"%" PRIu64 "\"/>\n", b->offset);
  else
    w_printf(w, " format=\"ascii\">\n");
}

/* ASCII values of one array, one point per line (cells: 16 per line) */
static void w_ascii_values(vtk_writer *w, const block *b, size_t n) {
  size_t per_line = b->ncomp ? (size_t)b->ncomp : 16;
  size_t total = b->ncomp ? n * (size_t)b->ncomp : n;
  for (size_t i = 0; i < total && !w->err; i++) {
    int last = (i + 1) % per_line == 0 || i + 1 == total;
    const char *sep = last ? "\n" : " ";
    if (b->source == SRC_CONNECTIVITY) {
      w_printf(w, "%" PRIu64 "%s", (uint64_t)i, sep);
    } else if (b->source == SRC_OFFSETS) {
      w_printf(w, "%" PRIu64 "%s", (uint64_t)i + 1, sep);
    } else if (b->vtype == MRN_VTK_INT32) {
      w_printf(w, "%d%s", (int)((const int32_t *)b->data)[i], sep);
    } else if (b->vtype == MRN_VTK_INT64) {
      w_printf(w, "%lld%s", (long long)((const int64_t *)b->data)[i], sep);
    } else {
      w_printf(w, "%.17g%s", ((const double *)b->data)[i], sep);
    }
  }
}

static void w_array(vtk_writer *w, const block *b, size_t n, mrn_vtk_encoding enc) {
  w_array_open(w, b, enc);
  if (enc == MRN_VTK_ASCII) {
    w_ascii_values(w, b, n);
    w_printf(w, "        </DataArray>\n");
  }
}

static void w_structure(vtk_writer *w, const block *b, int narrays, size_t n, mrn_vtk_encoding enc) {
  w_printf(w, "<?xml version=\"1.0\"?>\n");
  w_printf(w, "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
  w_printf(w, "  <PolyData>\n");
  w_printf(w, "    <Piece NumberOfPoints=\"%zu\" NumberOfVerts=\"%zu\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
              "NumberOfPolys=\"0\">\n", n, n);
  w_printf(w, "      <PointData>\n");
  for (int i = 0; i < narrays; i++) w_array(w, &b[i], n, enc);
  w_printf(w, "      </PointData>\n");
  w_printf(w, "      <Points>\n");
  w_array(w, &b[narrays], n, enc);
  w_printf(w, "      </Points>\n");
  w_printf(w, "      <Verts>\n");
  w_array(w, &b[narrays + 1], n, enc);
  w_array(w, &b[narrays + 2], n, enc);
  w_printf(w, "      </Verts>\n");
  w_printf(w, "    </Piece>\n");
  w_printf(w, "  </PolyData>\n");
}

/* ---- appended binary data ---------------------------------------------- */

/* the vertex cells are generated, not stored: fill a buffer chunk by chunk
 * (connectivity 0..n-1, offsets 1..n) */
static void w_cell_values(vtk_writer *w, int64_t first, size_t n, int64_t *buf, unsigned char *scratch) {
  for (size_t done = 0; done < n && !w->err;) {
    size_t m = n - done < CHUNK_VALUES ? n - done : CHUNK_VALUES;
    for (size_t i = 0; i < m; i++) buf[i] = first + (int64_t)(done + i);
    w_le(w, buf, sizeof(int64_t), m, scratch);
    done += m;
  }
}

static void w_block(vtk_writer *w, const block *b, size_t n, int64_t *buf, unsigned char *scratch) {
  w_le(w, &b->nbytes, sizeof b->nbytes, 1, scratch);
  if (b->source == SRC_CONNECTIVITY)
    w_cell_values(w, 0, n, buf, scratch);
  else if (b->source == SRC_OFFSETS)
    w_cell_values(w, 1, n, buf, scratch);
  else
    w_le(w, b->data, b->elem, (size_t)(b->nbytes / b->elem), scratch);
}

static int w_appended(vtk_writer *w, const block *b, int nblocks, size_t n) {
  int64_t *buf = malloc(CHUNK_VALUES * sizeof *buf);
  unsigned char *scratch = host_is_little_endian() ? NULL : malloc(CHUNK_VALUES * 8);
  if (!buf || (!host_is_little_endian() && !scratch)) {
    free(buf);
    free(scratch);
    return ENOMEM;
  }
  w_printf(w, "  <AppendedData encoding=\"raw\">\n   _");
  for (int i = 0; i < nblocks && !w->err; i++) w_block(w, &b[i], n, buf, scratch);
  w_printf(w, "\n  </AppendedData>\n");
  free(buf);
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
  if (!blocks) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", path);
  plan_blocks(blocks, npoints, points, arrays, narrays);

  vtk_writer w;
  rc = w_open(&w, path);
  if (rc == MRN_OK) {
    w_structure(&w, blocks, narrays, npoints, encoding);
    if (encoding == MRN_VTK_BINARY && !w.err) {
      int err = w_appended(&w, blocks, nblocks, npoints);
      if (err && !w.err) w.err = err;
    }
    w_printf(&w, "</VTKFile>\n");
    rc = w_finish(&w);
  }
  free(blocks);
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
  vtk_writer w;
  int rc = w_open(&w, pvd->path);
  if (rc != MRN_OK) return rc;
  w_printf(&w, "<?xml version=\"1.0\"?>\n");
  w_printf(&w, "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
  w_printf(&w, "  <Collection>\n");
  for (int i = 0; i < pvd->count; i++) {
    w_printf(&w, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"", pvd->times[i]);
    w_attr(&w, pvd->files[i]);
    w_printf(&w, "\"/>\n");
  }
  w_printf(&w, "  </Collection>\n");
  w_printf(&w, "</VTKFile>\n");
  return w_finish(&w);
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
