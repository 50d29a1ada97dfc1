/* moraine: particles as a VTKHDF file (.vtkhdf), for VTK's vtkHDFReader.
 *
 * VTKHDF keeps a VTK dataset in HDF5 (format 1.0, the one VTK 9.1 reads):
 * the particles are an UnstructuredGrid of vertex cells, one per point, in a
 * single partition, with the point-data arrays of mrn_vtk_array (io/vtk.h)
 * under /VTKHDF/PointData and the model time as FieldData/TimeValue. The
 * options of a .vtp apply (io/vtk.h): `compress` 1..9 stores every dataset
 * in chunks through HDF5's shuffle and deflate filters, `float32` stores the
 * Float64 arrays and the points as 32-bit floats; `encoding` is ignored. The
 * file is built in memory and written whole through mrn_atomic_write_file
 * (io/h5image.h), like moraine's other HDF5 files. */
#ifndef MRN_IO_VTKHDF_H
#define MRN_IO_VTKHDF_H

#include <stddef.h>

#include "io/vtk.h"

/* points: 3 doubles per point; options NULL: the plain form (Float64,
 * uncompressed, no time). Returns 0 or MRN_ERR_IO with the path and the
 * object in the message. */
int mrn_vtkhdf_write(const char *path, size_t npoints, const double *points, const mrn_vtk_array *arrays,
                     int narrays, const mrn_vtp_options *options);

#endif
