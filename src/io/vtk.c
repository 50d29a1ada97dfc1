#include "io/vtk.h"

#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <zlib.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/xml_writer.h"


/* ---- what the file holds ------------------------------------------------ */

/* one DataArray of the file, whether point data, points or cells */
typedef enum { SRC_DATA, SRC_CONNECTIVITY, SRC_OFFSETS } block_source;

typedef struct block {
  const char *name;
  const char *type; /* VTK type name as written */
  int ncomp;        /* 0: no NumberOfComponents attribute (cell arrays) */
  size_t elem;      /* bytes per value as held */
  size_t out_elem;  /* bytes per value as written (4 for Float64 written as Float32) */
  block_source source;
  mrn_vtk_type vtype;
  const void *data; /* or NULL and made by fill (mrn_vtk_array) */
  void (*fill)(const void *ctx, size_t first, size_t count, void *out);
  const void *ctx;
  uint64_t nbytes;  /* bytes as written, uncompressed */
  uint64_t offset;  /* position in the appended section */
  unsigned char *packed; /* compressed: header and blocks, as written */
  uint64_t packed_size;
} block;

/* reject arrays the file could not describe, before any file is created */
int mrn_vtk_check_arrays(const char *path, size_t n, const double *points, const mrn_vtk_array *arrays,
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

/* the VTK type name an array of type t is written as */
static const char *written_type(mrn_vtk_type t, int float32) {
  return float32 && t == MRN_VTK_FLOAT64 ? "Float32" : mrn_vtk_type_name(t);
}

static block make_block(const char *name, int ncomp, mrn_vtk_type t, block_source src, const void *data,
                        void (*fill)(const void *, size_t, size_t, void *), const void *ctx, int float32) {
  const int narrow = float32 && t == MRN_VTK_FLOAT64;
  return (block){.name = name, .type = written_type(t, float32), .ncomp = ncomp,
                 .elem = mrn_vtk_type_size(t), .out_elem = narrow ? 4 : mrn_vtk_type_size(t), .source = src,
                 .vtype = t, .data = data, .fill = fill, .ctx = ctx};
}

/* lay out the blocks in file order: point data, points, connectivity,
 * offsets; the offsets of raw blocks (compressed ones: pack_blocks) */
static void plan_blocks(block *b, size_t n, const double *points, const mrn_vtk_array *arrays, int narrays,
                        int float32) {
  int k = 0;
  for (int i = 0; i < narrays; i++, k++)
    b[k] = make_block(arrays[i].name, arrays[i].ncomp, arrays[i].type, SRC_DATA, arrays[i].data, arrays[i].fill,
                      arrays[i].ctx, float32);
  b[k++] = make_block("Points", 3, MRN_VTK_FLOAT64, SRC_DATA, points, NULL, NULL, float32);
  b[k++] = make_block("connectivity", 0, MRN_VTK_INT64, SRC_CONNECTIVITY, NULL, NULL, NULL, 0);
  b[k++] = make_block("offsets", 0, MRN_VTK_INT64, SRC_OFFSETS, NULL, NULL, NULL, 0);
  uint64_t offset = 0;
  for (int i = 0; i < k; i++) {
    uint64_t ncomp = b[i].ncomp ? (uint64_t)b[i].ncomp : 1;
    b[i].nbytes = (uint64_t)n * ncomp * b[i].out_elem;
    b[i].offset = offset;
    offset += sizeof(uint64_t) + b[i].nbytes;
  }
}

/* points per chunk of a block: what one fill may be asked for */
static size_t chunk_points(const block *b) { return MRN_VTK_FILL_POINTS(b->ncomp ? b->ncomp : 1); }

/* The values of points [first, first + count) of a block (count at most
 * chunk_points): where they are held, or made into buf (room for
 * MRN_VTK_FILL_VALUES values of 8 bytes). The vertex cells are generated,
 * not stored: connectivity 0..n-1, offsets 1..n. */
static const void *block_values(const block *b, size_t first, size_t count, void *buf) {
  if (b->source != SRC_DATA) {
    int64_t *v = buf;
    const int64_t base = b->source == SRC_OFFSETS ? 1 : 0;
    for (size_t i = 0; i < count; i++) v[i] = base + (int64_t)(first + i);
    return buf;
  }
  if (b->data) return (const char *)b->data + first * (size_t)b->ncomp * b->elem;
  b->fill(b->ctx, first, count, buf);
  return buf;
}

/* The same values as written: narrowed to Float32 when asked, in
 * little-endian order; in `conv` (room for MRN_VTK_FILL_VALUES values of 8
 * bytes) unless they can be written as they are. *size: their bytes. */
static const void *block_bytes(const block *b, size_t first, size_t count, void *buf, unsigned char *conv,
                               size_t *size) {
  const size_t nv = count * (size_t)(b->ncomp ? b->ncomp : 1);
  const void *vals = block_values(b, first, count, buf);
  *size = nv * b->out_elem;
  if (b->out_elem != b->elem) {
    const double *d = vals;
    float *f = (float *)conv;
    for (size_t i = 0; i < nv; i++) f[i] = (float)d[i];
    vals = conv;
  }
  if (mrn_host_is_little_endian()) return vals;
  const unsigned char *src = vals;
  unsigned char tmp[8];
  for (size_t i = 0; i < nv; i++) { /* in place when vals is conv */
    for (size_t k = 0; k < b->out_elem; k++) tmp[k] = src[i * b->out_elem + b->out_elem - 1 - k];
    memcpy(conv + i * b->out_elem, tmp, b->out_elem);
  }
  return conv;
}

/* ---- zlib-compressed blocks (vtkZLibDataCompressor) --------------------- */

/* A block's appended data when compressed: a UInt64 header [number of
 * blocks, bytes per block, bytes of the last block if partial (else 0),
 * compressed size of each block] followed by the compressed blocks. */
typedef struct zpack {
  int level;
  unsigned char raw[MRN_VTK_ZLIB_BLOCK];
  size_t fill;
  unsigned char *out; /* compressed blocks */
  size_t out_len, out_cap;
  uint64_t *sizes;
  size_t nblocks, sizes_cap;
  int err;
} zpack;

static void zpack_flush(zpack *z) {
  if (z->fill == 0 || z->err) return;
  uLong bound = compressBound((uLong)z->fill);
  if (z->out_len + bound > z->out_cap || z->nblocks == z->sizes_cap) {
    size_t cap = 2 * (z->out_cap + bound);
    size_t scap = z->sizes_cap ? 2 * z->sizes_cap : 64;
    unsigned char *out = realloc(z->out, cap);
    if (out) z->out = out, z->out_cap = cap;
    uint64_t *sizes = realloc(z->sizes, scap * sizeof *sizes);
    if (sizes) z->sizes = sizes, z->sizes_cap = scap;
    if (!out || !sizes) {
      z->err = ENOMEM;
      return;
    }
  }
  uLongf len = (uLongf)(z->out_cap - z->out_len);
  if (compress2(z->out + z->out_len, &len, z->raw, (uLong)z->fill, z->level) != Z_OK) {
    z->err = ENOMEM; /* compress2 fails only for want of memory with a sufficient bound */
    return;
  }
  z->out_len += len;
  z->sizes[z->nblocks++] = len;
  z->fill = 0;
}

static void zpack_feed(zpack *z, const unsigned char *data, size_t size) {
  while (size > 0 && !z->err) {
    size_t m = MRN_VTK_ZLIB_BLOCK - z->fill < size ? MRN_VTK_ZLIB_BLOCK - z->fill : size;
    memcpy(z->raw + z->fill, data, m);
    z->fill += m, data += m, size -= m;
    if (z->fill == MRN_VTK_ZLIB_BLOCK) zpack_flush(z);
  }
}

/* header and blocks of b's values, into b->packed */
static int pack_block(block *b, size_t n, int level, void *buf, unsigned char *conv) {
  zpack *z = calloc(1, sizeof *z);
  if (!z) return ENOMEM;
  z->level = level;
  const size_t most = chunk_points(b);
  for (size_t first = 0; first < n && !z->err; first += most) {
    const size_t count = n - first < most ? n - first : most;
    size_t size;
    const void *bytes = block_bytes(b, first, count, buf, conv, &size);
    zpack_feed(z, bytes, size);
  }
  const uint64_t last = z->fill; /* a partial last block, or 0 */
  zpack_flush(z);
  int err = z->err;
  const size_t header = (3 + z->nblocks) * sizeof(uint64_t);
  if (!err && !(b->packed = malloc(header + z->out_len))) err = ENOMEM;
  if (!err) {
    const uint64_t head[3] = {z->nblocks, MRN_VTK_ZLIB_BLOCK, last % MRN_VTK_ZLIB_BLOCK};
    for (size_t i = 0; i < 3 + z->nblocks; i++) {
      uint64_t v = i < 3 ? head[i] : z->sizes[i - 3];
      for (int k = 0; k < 8; k++) b->packed[8 * i + k] = (unsigned char)(v >> (8 * k)); /* little-endian */
    }
    if (z->out_len) memcpy(b->packed + header, z->out, z->out_len); /* no particles: nothing packed, out NULL */
    b->packed_size = header + z->out_len;
  }
  free(z->out);
  free(z->sizes);
  free(z);
  return err;
}

/* compress every block and lay them out one after the other */
static int pack_blocks(block *b, int nblocks, size_t n, int level, void *buf, unsigned char *conv) {
  uint64_t offset = 0;
  for (int i = 0; i < nblocks; i++) {
    int err = pack_block(&b[i], n, level, buf, conv);
    if (err) return err;
    b[i].offset = offset;
    offset += b[i].packed_size;
  }
  return 0;
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
  const size_t per_line = b->ncomp ? (size_t)b->ncomp : 16, nc = b->ncomp ? (size_t)b->ncomp : 1;
  const size_t total = n * nc, most = chunk_points(b);
  const void *vals = NULL;
  size_t base = 0, held = 0; /* vals holds the values [base, base + held) */
  for (size_t i = 0; i < total && !w->file.err; i++) {
    const char *sep = (i + 1) % per_line == 0 || i + 1 == total ? "\n" : " ";
    if (i >= base + held) { /* the next chunk of points */
      const size_t first = i / nc, count = n - first < most ? n - first : most;
      vals = block_values(b, first, count, buf);
      base = i;
      held = count * nc;
    }
    const size_t k = i - base;
    if (b->vtype == MRN_VTK_INT32)
      mrn_xw_printf(w, "%d%s", (int)((const int32_t *)vals)[k], sep);
    else if (b->vtype == MRN_VTK_INT64)
      mrn_xw_printf(w, "%lld%s", (long long)((const int64_t *)vals)[k], sep);
    else if (b->out_elem == 4)
      mrn_xw_printf(w, "%.9g%s", (double)(float)((const double *)vals)[k], sep);
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

static void w_header(mrn_xml_writer *w, const mrn_vtp_options *o) {
  const int packed = o->encoding == MRN_VTK_BINARY && o->compress > 0;
  mrn_xw_printf(w, "<?xml version=\"1.0\"?>\n");
  mrn_xw_printf(w, "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"%s>\n",
                packed ? " compressor=\"vtkZLibDataCompressor\"" : "");
  mrn_xw_printf(w, "  <PolyData>\n");
  if (o->has_time) { /* ParaView's reader takes the time of a file from this field */
    mrn_xw_printf(w, "    <FieldData>\n");
    mrn_xw_printf(w, "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">\n");
    mrn_xw_printf(w, "        %.17g\n      </DataArray>\n    </FieldData>\n", o->time);
  }
}

static void w_structure(mrn_xml_writer *w, const block *b, int narrays, size_t n, const mrn_vtp_options *o,
                        void *buf) {
  const mrn_vtk_encoding enc = o->encoding;
  w_header(w, o);
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

/* a raw block: its byte count (UInt64), then its values chunk by chunk */
static void w_block(mrn_xml_writer *w, const block *b, size_t n, void *buf, unsigned char *conv) {
  unsigned char size[8];
  for (int k = 0; k < 8; k++) size[k] = (unsigned char)(b->nbytes >> (8 * k)); /* little-endian */
  mrn_xw_bytes(w, size, sizeof size);
  const size_t most = chunk_points(b);
  for (size_t first = 0; first < n && !w->file.err; first += most) {
    const size_t count = n - first < most ? n - first : most;
    size_t bytes;
    const void *data = block_bytes(b, first, count, buf, conv, &bytes);
    mrn_xw_bytes(w, data, bytes);
  }
}

static void w_appended(mrn_xml_writer *w, const block *b, int nblocks, size_t n, void *buf, unsigned char *conv) {
  mrn_xw_printf(w, "  <AppendedData encoding=\"raw\">\n   _");
  for (int i = 0; i < nblocks && !w->file.err; i++) {
    if (b[i].packed)
      mrn_xw_bytes(w, b[i].packed, b[i].packed_size);
    else
      w_block(w, &b[i], n, buf, conv);
  }
  mrn_xw_printf(w, "\n  </AppendedData>\n");
}

/* ---- .vtp --------------------------------------------------------------- */

static int write_blocks(const char *path, block *blocks, int narrays, size_t n, const mrn_vtp_options *o, void *buf,
                        unsigned char *conv) {
  const int nblocks = narrays + 3;
  const int packed = o->encoding == MRN_VTK_BINARY && o->compress > 0;
  if (packed) {
    const int level = o->compress > 9 ? 9 : o->compress;
    if (pack_blocks(blocks, nblocks, n, level, buf, conv) != 0)
      return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory while compressing", path);
  }
  mrn_xml_writer w;
  int rc = o->piece ? mrn_xw_open_own(&w, path) : mrn_xw_open(&w, path);
  if (rc != MRN_OK) return rc;
  w_structure(&w, blocks, narrays, n, o, buf);
  if (o->encoding == MRN_VTK_BINARY && !w.file.err) w_appended(&w, blocks, nblocks, n, buf, conv);
  mrn_xw_printf(&w, "</VTKFile>\n");
  return mrn_xw_finish(&w);
}

int mrn_vtp_write_with(const char *path, size_t npoints, const double *points, const mrn_vtk_array *arrays,
                       int narrays, const mrn_vtp_options *options) {
  if (!path) return mrn_error_code(MRN_ERR_IO, "cannot write a VTK file without a path");
  const mrn_vtp_options plain = {0};
  const mrn_vtp_options *o = options ? options : &plain;
  if (narrays < 0) narrays = 0;
  int rc = mrn_vtk_check_arrays(path, npoints, points, arrays, narrays);
  if (rc != MRN_OK) return rc;
  const int nblocks = narrays + 3;
  block *blocks = calloc((size_t)nblocks, sizeof *blocks);
  /* the values made on demand or converted, a chunk at a time */
  void *buf = malloc(MRN_VTK_FILL_VALUES * sizeof(int64_t));
  unsigned char *conv = malloc(MRN_VTK_FILL_VALUES * sizeof(int64_t));
  if (!blocks || !buf || !conv) {
    rc = mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", path);
  } else {
    plan_blocks(blocks, npoints, points, arrays, narrays, o->float32);
    rc = write_blocks(path, blocks, narrays, npoints, o, buf, conv);
  }
  for (int i = 0; blocks && i < nblocks; i++) free(blocks[i].packed);
  free(blocks);
  free(buf);
  free(conv);
  return rc;
}

int mrn_vtp_write(const char *path, size_t npoints, const double *points, const mrn_vtk_array *arrays,
                  int narrays, mrn_vtk_encoding encoding) {
  const mrn_vtp_options o = {.encoding = encoding};
  return mrn_vtp_write_with(path, npoints, points, arrays, narrays, &o);
}

/* ---- .pvtp -------------------------------------------------------------- */

static void w_pdata_array(mrn_xml_writer *w, const char *type, const char *name, int ncomp) {
  mrn_xw_printf(w, "      <PDataArray type=\"%s\" Name=\"", type);
  mrn_xw_attr(w, name);
  mrn_xw_printf(w, "\" NumberOfComponents=\"%d\"/>\n", ncomp);
}

int mrn_pvtp_write(const char *path, const mrn_vtk_array *arrays, int narrays, const mrn_vtp_options *options,
                   const char *const *pieces, int npieces) {
  if (!path) return mrn_error_code(MRN_ERR_IO, "cannot write a VTK file without a path");
  const int float32 = options && options->float32;
  if (narrays < 0) narrays = 0;
  int rc = mrn_vtk_check_arrays(path, 0, NULL, arrays, narrays);
  if (rc != MRN_OK) return rc;
  mrn_xml_writer w;
  if ((rc = mrn_xw_open(&w, path)) != MRN_OK) return rc;
  mrn_xw_printf(&w, "<?xml version=\"1.0\"?>\n");
  mrn_xw_printf(&w, "<VTKFile type=\"PPolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
  mrn_xw_printf(&w, "  <PPolyData GhostLevel=\"0\">\n");
  mrn_xw_printf(&w, "    <PPointData>\n");
  for (int i = 0; i < narrays; i++)
    w_pdata_array(&w, written_type(arrays[i].type, float32), arrays[i].name, arrays[i].ncomp);
  mrn_xw_printf(&w, "    </PPointData>\n");
  mrn_xw_printf(&w, "    <PPoints>\n");
  w_pdata_array(&w, written_type(MRN_VTK_FLOAT64, float32), "Points", 3);
  mrn_xw_printf(&w, "    </PPoints>\n");
  for (int r = 0; r < npieces; r++) {
    mrn_xw_printf(&w, "    <Piece Source=\"");
    mrn_xw_attr(&w, pieces[r]);
    mrn_xw_printf(&w, "\"/>\n");
  }
  mrn_xw_printf(&w, "  </PPolyData>\n");
  mrn_xw_printf(&w, "</VTKFile>\n");
  return mrn_xw_finish(&w);
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

void mrn_file_series_init(mrn_pvd *pvd, const char *path) {
  mrn_pvd_init(pvd, path);
  pvd->json = 1;
}

/* a JSON string: quotes, backslashes and control characters escaped */
static void json_string(mrn_xml_writer *w, const char *s) {
  mrn_xw_printf(w, "\"");
  for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
    if (*c == '"' || *c == '\\') mrn_xw_printf(w, "\\%c", *c);
    else if (*c < 0x20) mrn_xw_printf(w, "\\u%04x", *c);
    else mrn_xw_bytes(w, c, 1);
  }
  mrn_xw_printf(w, "\"");
}

/* ParaView's file-series reader (vtkFileSeriesReader) takes the time of
 * each file from this list */
static void series_json(mrn_xml_writer *w, const mrn_pvd *pvd) {
  mrn_xw_printf(w, "{\n  \"file-series-version\": \"1.0\",\n  \"files\": [");
  for (int i = 0; i < pvd->count; i++) {
    mrn_xw_printf(w, "%s\n    { \"name\": ", i ? "," : "");
    json_string(w, pvd->files[i]);
    mrn_xw_printf(w, ", \"time\": %.17g }", pvd->times[i]);
  }
  mrn_xw_printf(w, "\n  ]\n}\n");
}

static int pvd_rewrite(const mrn_pvd *pvd) {
  mrn_xml_writer w;
  int rc = mrn_xw_open(&w, pvd->path);
  if (rc != MRN_OK) return rc;
  if (pvd->json) {
    series_json(&w, pvd);
    return mrn_xw_finish(&w);
  }
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
