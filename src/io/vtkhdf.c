#include "io/vtkhdf.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/h5image.h"
#include "io/h5util.h"

enum { VTK_VERTEX = 1 }; /* VTK's cell type of a single point */

/* The Type attribute: fixed-length ASCII without a terminating NUL, as the
 * format's own examples store it (VTK compares the whole string). */
static void w_type(mrn_h5w *w, hid_t group, const char *type) {
  if (w->failed) return;
  hid_t t = H5Tcopy(H5T_C_S1), space = H5Screate(H5S_SCALAR);
  hid_t a = t < 0 || space < 0 || H5Tset_size(t, strlen(type)) < 0 || H5Tset_strpad(t, H5T_STR_NULLPAD) < 0
                ? -1
                : H5Acreate2(group, "Type", t, space, H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0 || H5Awrite(a, t, type) < 0) mrn_h5w_fail(w, group, "Type", 1);
  if (a >= 0) H5Aclose(a);
  if (space >= 0) H5Sclose(space);
  if (t >= 0) H5Tclose(t);
}

/* rows of a compressed dataset's chunks: about MRN_VTK_ZLIB_BLOCK bytes */
static hsize_t chunk_rows(int ncomp) { return MRN_VTK_ZLIB_BLOCK / 8 / (hsize_t)ncomp; }

/* A dataset of n rows x ncomp (ncomp 1: rank 1), stored as `stored`, empty.
 * With a zlib level: in chunks through the shuffle filter (bytes of equal
 * rank side by side, which deflate packs better) and deflate. */
static hid_t make_dataset(mrn_h5w *w, hid_t group, const char *name, hid_t stored, size_t n, int ncomp, int level) {
  if (w->failed) return H5I_INVALID_HID;
  hsize_t dims[2] = {(hsize_t)n, (hsize_t)ncomp}, chunk[2] = {chunk_rows(ncomp), (hsize_t)ncomp};
  if (chunk[0] > dims[0]) chunk[0] = dims[0];
  const int rank = ncomp > 1 ? 2 : 1;
  hid_t space = H5Screate_simple(rank, dims, NULL), dcpl = H5Pcreate(H5P_DATASET_CREATE);
  /* an empty dataset cannot be chunked (a chunk is at least one row) */
  if (level > 0 && n > 0 && dcpl >= 0 &&
      (H5Pset_chunk(dcpl, rank, chunk) < 0 || H5Pset_shuffle(dcpl) < 0 || H5Pset_deflate(dcpl, (unsigned)level) < 0)) {
    H5Pclose(dcpl);
    dcpl = H5I_INVALID_HID;
  }
  hid_t d = space < 0 || dcpl < 0 ? -1 : H5Dcreate2(group, name, stored, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (space >= 0) H5Sclose(space);
  if (dcpl >= 0) H5Pclose(dcpl);
  if (d < 0) mrn_h5w_fail(w, group, name, 0);
  return d;
}

/* rows [first, first + count) of dataset d from `values` */
static void write_rows(mrn_h5w *w, hid_t d, hid_t type, size_t first, size_t count, int ncomp, const void *values,
                       const char *name) {
  if (w->failed || count == 0) return;
  hsize_t start[2] = {(hsize_t)first, 0}, size[2] = {(hsize_t)count, (hsize_t)ncomp};
  const int rank = ncomp > 1 ? 2 : 1;
  hid_t file_space = H5Dget_space(d), mem_space = H5Screate_simple(rank, size, NULL);
  herr_t rc = file_space < 0 || mem_space < 0 ? -1
                                              : H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, NULL, size, NULL);
  if (rc >= 0) rc = H5Dwrite(d, type, mem_space, file_space, H5P_DEFAULT, values);
  if (rc < 0) mrn_h5w_fail(w, d, name, 0);
  if (mem_space >= 0) H5Sclose(mem_space);
  if (file_space >= 0) H5Sclose(file_space);
}

static hid_t native_type(mrn_vtk_type t) {
  return t == MRN_VTK_INT32 ? H5T_NATIVE_INT32 : t == MRN_VTK_INT64 ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
}

/* the type a Float64 array is stored as: HDF5 rounds the doubles on writing */
static hid_t real_type(const mrn_vtp_options *o) { return o->float32 ? H5T_IEEE_F32LE : H5T_NATIVE_DOUBLE; }

/* one point-data array, held or made chunk by chunk by its fill */
static void w_array(mrn_h5w *w, hid_t group, const mrn_vtk_array *a, size_t n, void *buf, const mrn_vtp_options *o) {
  const hid_t type = native_type(a->type);
  hid_t d = make_dataset(w, group, a->name, a->type == MRN_VTK_FLOAT64 ? real_type(o) : type, n, a->ncomp,
                         o->compress);
  const size_t most = MRN_VTK_FILL_POINTS(a->ncomp), elem = a->type == MRN_VTK_INT32 ? 4 : 8;
  for (size_t first = 0; first < n && !w->failed; first += most) {
    const size_t count = n - first < most ? n - first : most;
    const void *values = (const char *)a->data + first * (size_t)a->ncomp * elem;
    if (!a->data) {
      a->fill(a->ctx, first, count, buf);
      values = buf;
    }
    write_rows(w, d, type, first, count, a->ncomp, values, a->name);
  }
  if (d >= 0) H5Dclose(d);
}

/* The vertex cells, generated chunk by chunk: connectivity 0..n-1, offsets
 * 0..n (n + 1 values), types VTK_VERTEX. */
static void w_cells(mrn_h5w *w, hid_t vtk, size_t n, int64_t *buf, int level) {
  hid_t conn = make_dataset(w, vtk, "Connectivity", H5T_NATIVE_INT64, n, 1, level);
  hid_t offs = make_dataset(w, vtk, "Offsets", H5T_NATIVE_INT64, n + 1, 1, level);
  hid_t types = make_dataset(w, vtk, "Types", H5T_NATIVE_UINT8, n, 1, level);
  for (size_t first = 0; first <= n && !w->failed; first += MRN_VTK_FILL_VALUES) {
    const size_t count = n + 1 - first < MRN_VTK_FILL_VALUES ? n + 1 - first : MRN_VTK_FILL_VALUES;
    for (size_t i = 0; i < count; i++) buf[i] = (int64_t)(first + i);
    write_rows(w, offs, H5T_NATIVE_INT64, first, count, 1, buf, "Offsets");
    const size_t cells = first + count > n ? n - first : count; /* the offsets have one value more */
    write_rows(w, conn, H5T_NATIVE_INT64, first, cells, 1, buf, "Connectivity");
    memset(buf, VTK_VERTEX, cells);
    write_rows(w, types, H5T_NATIVE_UINT8, first, cells, 1, buf, "Types");
  }
  if (conn >= 0) H5Dclose(conn);
  if (offs >= 0) H5Dclose(offs);
  if (types >= 0) H5Dclose(types);
}

/* one value per partition (a single one) */
static void w_count(mrn_h5w *w, hid_t vtk, const char *name, size_t value) {
  const int64_t v = (int64_t)value;
  hid_t d = make_dataset(w, vtk, name, H5T_NATIVE_INT64, 1, 1, 0);
  write_rows(w, d, H5T_NATIVE_INT64, 0, 1, 1, &v, name);
  if (d >= 0) H5Dclose(d);
}

static void w_file(mrn_h5w *w, size_t n, const double *points, const mrn_vtk_array *arrays, int narrays,
                   const mrn_vtp_options *o, int64_t *buf) {
  hid_t vtk = mrn_h5w_group(w, w->file, "VTKHDF");
  const int version[2] = {1, 0};
  mrn_h5w_int32s(w, vtk, "Version", version, 2);
  w_type(w, vtk, "UnstructuredGrid");
  w_count(w, vtk, "NumberOfPoints", n);
  w_count(w, vtk, "NumberOfCells", n);
  w_count(w, vtk, "NumberOfConnectivityIds", n);
  hid_t d = make_dataset(w, vtk, "Points", real_type(o), n, 3, o->compress);
  write_rows(w, d, H5T_NATIVE_DOUBLE, 0, n, 3, points, "Points");
  if (d >= 0) H5Dclose(d);
  w_cells(w, vtk, n, buf, o->compress);
  hid_t pd = mrn_h5w_group(w, vtk, "PointData");
  for (int i = 0; i < narrays && !w->failed; i++) w_array(w, pd, &arrays[i], n, buf, o);
  if (pd >= 0) H5Gclose(pd);
  if (o->has_time) {
    hid_t fd = mrn_h5w_group(w, vtk, "FieldData");
    hid_t t = make_dataset(w, fd, "TimeValue", H5T_NATIVE_DOUBLE, 1, 1, 0);
    write_rows(w, t, H5T_NATIVE_DOUBLE, 0, 1, 1, &o->time, "TimeValue");
    if (t >= 0) H5Dclose(t);
    if (fd >= 0) H5Gclose(fd);
  }
  if (vtk >= 0) H5Gclose(vtk);
}

int mrn_vtkhdf_write(const char *path, size_t npoints, const double *points, const mrn_vtk_array *arrays,
                     int narrays, const mrn_vtp_options *options) {
  if (!path) return mrn_error_code(MRN_ERR_IO, "cannot write a VTKHDF file without a path");
  mrn_vtp_options o = {0};
  if (options) o = *options;
  o.compress = o.compress < 0 ? 0 : o.compress > 9 ? 9 : o.compress; /* as the .vtp writer */
  if (narrays < 0) narrays = 0;
  int rc = mrn_vtk_check_arrays(path, npoints, points, arrays, narrays);
  if (rc != MRN_OK) return rc;
  int64_t *buf = malloc(MRN_VTK_FILL_VALUES * sizeof *buf);
  if (!buf) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", path);
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  mrn_h5w w = {.file = H5I_INVALID_HID};
  mrn_h5_image img;
  errno = 0;
  w.file = mrn_h5_image_create(&img, path, H5P_DEFAULT);
  if (w.file < 0) mrn_h5w_fail(&w, H5I_INVALID_HID, "the file", 0);
  w_file(&w, npoints, points, arrays, narrays, &o, buf);
  void *bytes = NULL;
  size_t size = 0;
  if (w.file >= 0 && mrn_h5_image_close(&img, w.file, &bytes, &size) != 0) {
    mrn_h5w_fail(&w, H5I_INVALID_HID, "the file (closing it)", 0);
    bytes = NULL;
  }
  rc = w.failed ? mrn_h5w_report(&w, path) : mrn_atomic_write_file(path, bytes, size);
  mrn_h5_restore(&quiet);
  free(bytes);
  free(buf);
  return rc;
}
