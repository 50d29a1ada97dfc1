/* moraine: HDF5 files built in memory, to be written whole.
 *
 * moraine's HDF5 files (checkpoints, the time series) are built in memory
 * (HDF5's core driver without a backing store) and their bytes are then
 * written by mrn_atomic_write_file (io/atomic_file.h), which fsyncs a
 * temporary file and renames it into place: a crash leaves the old file or
 * the new one, never half of one, and a full disk, a quota, a file-size limit
 * or an I/O error fails an ordinary write() that is reported with the path
 * and the reason. HDF5 never meets the failure itself: HDF5 1.10 keeps a file
 * whose write or flush failed half-closed and crashes on it when the library
 * shuts down at exit. */
#ifndef MRN_IO_H5IMAGE_H
#define MRN_IO_H5IMAGE_H

#include <hdf5.h>
#include <stddef.h>

/* where the core driver's buffers are followed; lives until the file is closed */
typedef struct mrn_h5_image {
  void *buf;      /* the buffer allocated last */
  size_t size;
  void *kept_buf; /* the buffer of the last image closed */
  int kept;
} mrn_h5_image;

/* A new, empty file in memory in the HDF5 1.8 format (checksummed metadata,
 * readable by every HDF5 since 1.8 and h5py), closed strongly (every object
 * with it). `name` only names it; `fcpl` is a file creation property list or
 * H5P_DEFAULT. The file, or H5I_INVALID_HID. */
hid_t mrn_h5_image_create(mrn_h5_image *img, const char *name, hid_t fcpl);

/* Close `file` (from mrn_h5_image_create with the same img) and take its
 * bytes, the user block of its fcpl included: 0 with *bytes (malloc'd, for
 * free()) and *size, or -1 when HDF5 could not complete the file (nothing to
 * free). */
int mrn_h5_image_close(mrn_h5_image *img, hid_t file, void **bytes, size_t *size);

#endif
