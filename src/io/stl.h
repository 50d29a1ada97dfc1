/* moraine: STL files, binary and ASCII, read into triangles.
 *
 * Binary: an 80-byte header, a little-endian uint32 triangle count, then 50
 * bytes per triangle (normal and three corners as float32, a uint16). ASCII:
 * `solid name`, then `facet normal nx ny nz / outer loop / vertex x y z`
 * (three times) `/ endloop / endfacet` per triangle, `endsolid`; several
 * solids may follow each other. A file is ASCII when it starts with `solid`
 * and holds no zero byte (binary headers may start with `solid` too, their
 * float data have zero bytes), binary otherwise. The facets' normals are not
 * read: the orientation comes from the corners' order. */
#ifndef MRN_IO_STL_H
#define MRN_IO_STL_H

#include <stddef.h>

/* the most triangles a file may hold */
#define MRN_STL_MAX_TRIANGLES 4000000

/* The triangles of the STL file at path into *tri (9 numbers each: the
 * corners a, b, c; malloc'd, the caller frees), their number into *n.
 * 0, or MRN_ERR_IO with a message naming the file and what is wrong (the
 * line of an ASCII file). */
int mrn_stl_read(const char *path, double **tri, size_t *n);

#endif
