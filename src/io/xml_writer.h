/* moraine: the file stream the VTK XML writers (.vtp, .vti, .pvd) share.
 *
 * The file is an mrn_atomic_file: written under a temporary name and renamed
 * into place when complete. Its first failing write keeps its errno (ENOSPC,
 * EDQUOT, ...) in file.err for the error message; later calls are skipped
 * because the file is lost anyway. */
#ifndef MRN_IO_XML_WRITER_H
#define MRN_IO_XML_WRITER_H

#include <stddef.h>

#include "io/atomic_file.h"
#include "io/vtk.h"

/* values per buffer fill when a big-endian host swaps bytes */
#define MRN_XW_CHUNK_VALUES 65536

typedef struct mrn_xml_writer {
  mrn_atomic_file file; /* file.err: errno of the first failed write, 0 while all is well */
} mrn_xml_writer;

/* 0, or MRN_ERR_IO with the path in the message */
int mrn_xw_open(mrn_xml_writer *w, const char *path);
/* written by this process in a distributed run too (mrn_atomic_open_own) */
int mrn_xw_open_own(mrn_xml_writer *w, const char *path);
/* commit the file, or drop it and report the first write error */
int mrn_xw_finish(mrn_xml_writer *w);

void mrn_xw_bytes(mrn_xml_writer *w, const void *data, size_t size);
void mrn_xw_printf(mrn_xml_writer *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* an attribute value with the XML special characters escaped */
void mrn_xw_attr(mrn_xml_writer *w, const char *s);
/* `count` values of `elem` bytes each in little-endian order: one fwrite on
 * the usual little-endian hosts; a big-endian host swaps through `scratch`
 * (room for MRN_XW_CHUNK_VALUES values) in chunks */
void mrn_xw_le(mrn_xml_writer *w, const void *data, size_t elem, size_t count, unsigned char *scratch);

/* VTK's name and the size in bytes of a value type */
/* 1 on a little-endian host (the byte order of the VTK files) */
int mrn_host_is_little_endian(void);
const char *mrn_vtk_type_name(mrn_vtk_type t);
size_t mrn_vtk_type_size(mrn_vtk_type t);

#endif
