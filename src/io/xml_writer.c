#include "io/xml_writer.h"

#include <stdarg.h>
#include <stdint.h>

int mrn_xw_open(mrn_xml_writer *w, const char *path) { return mrn_atomic_open(&w->file, path); }

int mrn_xw_open_own(mrn_xml_writer *w, const char *path) { return mrn_atomic_open_own(&w->file, path); }

int mrn_xw_finish(mrn_xml_writer *w) { return mrn_atomic_commit(&w->file); }

void mrn_xw_bytes(mrn_xml_writer *w, const void *data, size_t size) { mrn_atomic_write(&w->file, data, size); }

void mrn_xw_printf(mrn_xml_writer *w, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  mrn_atomic_vprintf(&w->file, fmt, ap);
  va_end(ap);
}

void mrn_xw_attr(mrn_xml_writer *w, const char *s) {
  for (; *s && !w->file.err; s++) {
    switch (*s) {
      case '&': mrn_xw_printf(w, "&amp;"); break;
      case '<': mrn_xw_printf(w, "&lt;"); break;
      case '>': mrn_xw_printf(w, "&gt;"); break;
      case '"': mrn_xw_printf(w, "&quot;"); break;
      default: mrn_xw_bytes(w, s, 1);
    }
  }
}

int mrn_host_is_little_endian(void) {
  const uint16_t one = 1;
  return *(const unsigned char *)&one == 1;
}

void mrn_xw_le(mrn_xml_writer *w, const void *data, size_t elem, size_t count, unsigned char *scratch) {
  if (mrn_host_is_little_endian()) {
    mrn_xw_bytes(w, data, elem * count);
    return;
  }
  const unsigned char *src = data;
  while (count > 0 && !w->file.err) {
    size_t m = count < MRN_XW_CHUNK_VALUES ? count : MRN_XW_CHUNK_VALUES;
    for (size_t i = 0; i < m; i++)
      for (size_t b = 0; b < elem; b++) scratch[i * elem + b] = src[i * elem + elem - 1 - b];
    mrn_xw_bytes(w, scratch, m * elem);
    src += m * elem;
    count -= m;
  }
}

const char *mrn_vtk_type_name(mrn_vtk_type t) {
  switch (t) {
    case MRN_VTK_INT32: return "Int32";
    case MRN_VTK_INT64: return "Int64";
    default: return "Float64";
  }
}

size_t mrn_vtk_type_size(mrn_vtk_type t) { return t == MRN_VTK_INT32 ? 4 : 8; }
