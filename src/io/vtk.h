/* moraine: VTK XML writers for ParaView.
 *
 *  - particles as PolyData (.vtp): points plus one vertex cell per point,
 *    point-data arrays in appended binary form, raw or zlib-compressed
 *    (header_type UInt64, so arrays larger than 4 GiB are fine), in Float64
 *    or Float32, or ASCII for debugging; the model time as TimeValue;
 *  - a distributed snapshot as a parallel PolyData file (.pvtp) listing the
 *    .vtp pieces its processes wrote;
 *  - collections listing each file with its model time, rewritten
 *    atomically after every new file so ParaView can open a running series:
 *    a .pvd (VTK XML), or ParaView's JSON file series (NAME.vtkhdf.series)
 *    for files a .pvd cannot list (VTK 9.1 reads only XML files from one).
 * All files are written through mrn_atomic_file (temporary name + rename). */
#ifndef MRN_IO_VTK_H
#define MRN_IO_VTK_H

#include <stddef.h>
#include <stdint.h>

typedef enum { MRN_VTK_FLOAT64 = 0, MRN_VTK_INT32, MRN_VTK_INT64 } mrn_vtk_type;

/* One point-data array: `ncomp` values per point, interleaved, either held
 * in `data` or, when data is NULL, made on demand: `fill` writes the values
 * of points [first, first + count) into out (count * ncomp values, count at
 * most MRN_VTK_FILL_POINTS(ncomp)), so that a file can be written without
 * holding a whole array in memory. */
typedef struct mrn_vtk_array {
  const char *name;
  int ncomp;
  mrn_vtk_type type;
  const void *data;
  void (*fill)(const void *ctx, size_t first, size_t count, void *out);
  const void *ctx;
} mrn_vtk_array;

/* 0, or MRN_ERR_IO when the arrays could not be described in a file
 * (no name, no data, an unknown type, too many components) */
int mrn_vtk_check_arrays(const char *path, size_t npoints, const double *points, const mrn_vtk_array *arrays,
                         int narrays);

/* values asked of a `fill` at a time (a 512 KB buffer of 8-byte values) */
#define MRN_VTK_FILL_VALUES 65536
#define MRN_VTK_FILL_POINTS(ncomp) (MRN_VTK_FILL_VALUES / (size_t)(ncomp))

typedef enum { MRN_VTK_BINARY = 0, MRN_VTK_ASCII } mrn_vtk_encoding;

/* How a .vtp is written. The zero value is the plain form: appended raw
 * binary, Float64 kept, no time. */
typedef struct mrn_vtp_options {
  mrn_vtk_encoding encoding;
  /* 1..9: zlib level of the appended data (vtkZLibDataCompressor, blocks of
   * MRN_VTK_ZLIB_BLOCK bytes); 0: raw. The compressed arrays are held in
   * memory until the file is written (the offsets precede the data).
   * Ignored for ASCII. */
  int compress;
  int float32;  /* write the Float64 arrays and the points as Float32 */
  int has_time; /* add `time` (s) as the TimeValue field data ParaView reads */
  double time;
  /* 1: a piece of a distributed snapshot, written by this process whichever
   * it is; 0: written by process 0 alone (io/atomic_file.h). .vtp only. */
  int piece;
} mrn_vtp_options;

/* uncompressed bytes per zlib block */
#define MRN_VTK_ZLIB_BLOCK 65536

/* points: 3 doubles per point (z = 0 in 2D). Returns 0 or MRN_ERR_IO. */
int mrn_vtp_write_with(const char *path, size_t npoints, const double *points, const mrn_vtk_array *arrays,
                       int narrays, const mrn_vtp_options *options);
/* the plain form in `encoding` */
int mrn_vtp_write(const char *path, size_t npoints, const double *points, const mrn_vtk_array *arrays,
                  int narrays, mrn_vtk_encoding encoding);

/* A parallel PolyData file (.pvtp) listing `npieces` .vtp files (`pieces`,
 * relative to the .pvtp's directory) that were written with these arrays and
 * options: their point-data arrays and points declared with the names,
 * components and types the pieces hold them in. Written by process 0 of a
 * distributed run. 0 or MRN_ERR_IO. */
int mrn_pvtp_write(const char *path, const mrn_vtk_array *arrays, int narrays, const mrn_vtp_options *options,
                   const char *const *pieces, int npieces);

/* a collection kept in memory and rewritten on each addition */
typedef struct mrn_pvd {
  char *path;
  int json; /* ParaView's file series: {"file-series-version": "1.0", "files": [{"name", "time"}]} */
  int count, cap;
  double *times;
  char **files; /* relative to the .pvd's directory */
} mrn_pvd;

void mrn_pvd_init(mrn_pvd *pvd, const char *path);
/* the same collection as a ParaView .series JSON file */
void mrn_file_series_init(mrn_pvd *pvd, const char *path);
void mrn_pvd_free(mrn_pvd *pvd);
/* append (time, file) and rewrite the collection atomically; 0 or MRN_ERR_IO */
int mrn_pvd_add(mrn_pvd *pvd, double time, const char *relative_file);

#endif
