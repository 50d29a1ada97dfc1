#include "core/crc32.h"

#include <zlib.h>

uint32_t mrn_crc32(uint32_t crc, const void *data, size_t n) {
  /* zlib's own, with a size_t length (crc32_z, zlib 1.2.9 and later) */
  return (uint32_t)crc32_z((uLong)crc, data, (z_size_t)n);
}
