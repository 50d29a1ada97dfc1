/* moraine: CRC-32, the checksum of zlib, gzip and PNG (reflected polynomial
 * 0xEDB88320), computed by zlib: a value moraine stores can be checked with
 * Python's zlib.crc32 or any other implementation of it. It detects every error
 * confined to 32 consecutive bits, so every damaged byte. */
#ifndef MRN_CORE_CRC32_H
#define MRN_CORE_CRC32_H

#include <stddef.h>
#include <stdint.h>

/* The CRC of `crc`'s data followed by n more bytes; start with 0:
 * mrn_crc32(mrn_crc32(0, a, na), b, nb) == mrn_crc32(0, ab, na + nb). */
uint32_t mrn_crc32(uint32_t crc, const void *data, size_t n);

#endif
