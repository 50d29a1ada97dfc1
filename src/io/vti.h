/* moraine: the background grid as VTK ImageData (.vti) for ParaView.
 *
 * Only the domain nodes are written (node i = 0..ncell along each axis, no
 * ghost layers), x fastest, as the grid stores them. The image has the grid's
 * origin and its cell size as spacing; a 2D grid is an image of
 * (ncell_x + 1) x (ncell_y + 1) x 1 points at z = 0 with a z spacing of 1, so
 * ParaView shows it as a flat sheet. Nodal vectors have 3 components (z = 0
 * in 2D), as the grid keeps them.
 *
 * Arrays are raw binary in an appended section with UInt64 block headers
 * (large grids are fine), or ASCII for debugging. The file is written under a
 * temporary name and renamed when complete (io/atomic_file.h), so a reader or
 * a crash only ever sees a whole file. A series of them is listed in a .pvd
 * with mrn_pvd_add() (io/vtk.h), like the particle files. */
#ifndef MRN_IO_VTI_H
#define MRN_IO_VTI_H

#include "grid/grid.h"
#include "io/vtk.h"

/* Write node arrays of grid `g` to `path`. Each array's `data` (held: the
 * .vti writer does not take arrays made on demand) covers every
 * node of the grid in its own layout, ghosts included (g->n * ncomp values of
 * the array's type, like g->mass or g->vel); only the domain nodes reach the
 * file. `time` is stored as the image's TimeValue (what ParaView shows for a
 * lone file); give NAN to leave it out. Returns 0 or MRN_ERR_IO with the path
 * in the message. */
int mrn_vti_write(const char *path, const mrn_grid *g, double time, const mrn_vtk_array *arrays, int narrays,
                  mrn_vtk_encoding encoding);

/* The usual grid file: "mass" (g->mass), "velocity" (g->vel, the nodal
 * velocity V^i mapped from the particles, after the boundary conditions) and
 * "force" (g->force, the nodal force the last step assembled). */
int mrn_vti_write_grid(const char *path, const mrn_grid *g, double time, mrn_vtk_encoding encoding);

#endif
