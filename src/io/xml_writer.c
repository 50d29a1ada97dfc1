#include "io/xml_writer.h"

#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"

static void fail(mrn_xml_writer *w) {
  if (!w->err) w->err = errno ? errno : EIO;
}

int mrn_xw_open(mrn_xml_writer *w, const char *path) {
  w->err = 0;
  return mrn_atomic_open(&w->file, path);
}

int mrn_xw_finish(mrn_xml_writer *w) {
  if (w->err) {
    int rc = mrn_error_code(MRN_ERR_IO, "cannot write '%s': %s", w->file.final_path, strerror(w->err));
    mrn_atomic_abort(&w->file);
    return rc;
  }
  return mrn_atomic_commit(&w->file);
}

void mrn_xw_bytes(mrn_xml_writer *w, const void *data, size_t size) {
  if (w->err || size == 0) return;
  errno = 0;
  if (fwrite(data, 1, size, w->file.fp) != size) fail(w);
}

void mrn_xw_printf(mrn_xml_writer *w, const char *fmt, ...) {
  if (w->err) return;
  va_list ap;
  va_start(ap, fmt);
  errno = 0;
  if (vfprintf(w->file.fp, fmt, ap) < 0) fail(w);
  va_end(ap);
}

void mrn_xw_attr(mrn_xml_writer *w, const char *s) {
  for (; *s && !w->err; s++) {
    switch (*s) {
      case '&': mrn_xw_printf(w, "&amp;"); break;
      case '<': mrn_xw_printf(w, "&lt;"); break;
      case '>': mrn_xw_printf(w, "&gt;"); break;
      case '"': mrn_xw_printf(w, "&quot;"); break;
      default:
        errno = 0;
        if (putc(*s, w->file.fp) == EOF) fail(w);
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
  while (count > 0 && !w->err) {
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
