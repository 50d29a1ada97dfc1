/* moraine: what a particle <-> grid transfer works on.
 *
 * Every entry point of transfer/ takes a mrn_transfer instead of the whole
 * simulation: the grid and the particles it reads and writes, the scheme and
 * the options that choose the kernel, and nothing of the materials, the
 * clock or the outputs. The simulation builds one for each step
 * (mrn_sim_transfer, solver/simulation.h); a C program or a test can build
 * one by hand around its own grid and particles. */
#ifndef MRN_TRANSFER_CONTEXT_H
#define MRN_TRANSFER_CONTEXT_H

#include "grid/boundary.h"
#include "grid/grid.h"
#include "particles/particles.h"
#include "transfer/scheme.h"

typedef struct mrn_transfer {
  int dim;                      /* 2 or 3 */
  mrn_grid *grid;               /* nodal arrays; its shape and face treatment choose the kernel */
  mrn_particles *particles;
  const mrn_scheme *scheme;     /* grid velocity, velocity and position update rules (000 Table 1) */
  const mrn_boundary *boundary; /* face kinds: periodic faces change the binning */
  double mass_floor;            /* nodes lighter than this are treated as empty (kg) */
  int sort_now;                 /* reorder the particles by block at this step's first P2G */
} mrn_transfer;

#endif
