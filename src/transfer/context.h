/* moraine: what a particle <-> grid transfer works on.
 *
 * Every entry point of transfer/ takes a mrn_transfer instead of the whole
 * simulation: the grid and the particles it reads and writes, the scheme and
 * the options that choose the kernel, the binning of the particles by block,
 * and nothing of the materials, the clock or the outputs. The simulation
 * builds one for each step (mrn_sim_transfer, solver/simulation.h); a C
 * program or a test can build one by hand around its own grid and particles
 * (with blocks from mrn_blocks_new). */
#ifndef MRN_TRANSFER_CONTEXT_H
#define MRN_TRANSFER_CONTEXT_H

#include "grid/boundary.h"
#include "grid/grid.h"
#include "particles/particles.h"
#include "shape/shape.h"
#include "transfer/blocks.h"
#include "transfer/scheme.h"

typedef struct mrn_transfer {
  int dim;                      /* 2 or 3 */
  mrn_grid *grid;               /* nodal arrays; its shape and face treatment choose the kernel */
  mrn_particles *particles;
  const mrn_scheme *scheme;     /* grid velocity, velocity and position update rules (000 Table 1) */
  const mrn_boundary *boundary; /* face kinds: periodic faces change the binning */
  mrn_kernel_options kernel;    /* shape, face treatment, MLS gradient, periodic axes */
  double mass_floor;            /* nodes lighter than this are treated as empty (kg) */
  mrn_blocks *blocks;           /* the particles binned by block (transfer/blocks.h), kept between steps */
  int sort_now;                 /* reorder the particles by block at the next binning; cleared once done */
  const double *domain;         /* CPDI, cpGIMP: each particle's domain A = F U0 (9 values), CPDI2: its
                                 * corners' positions (8 values), as the step froze them; or NULL: formed
                                 * from F or the stored corners at each use (transfer/cpdi.h, cpdi2.h,
                                 * cpgimp.h) */
  /* after a scatter into a nodal array of ncomp values per node (XPIC's
   * passes), its owner may complete the sums: a distributed run adds its
   * neighbours' part (solver/dist.h). NULL: nothing to add */
  void (*sum_nodal)(void *ctx, double *values, int ncomp);
  /* the largest of n values over the same processes, in place (a
   * convergence test that every process must end alike). NULL: nothing */
  void (*max_over)(void *ctx, double *values, int n);
  /* the owner's conditions on a nodal velocity field (faces, walls,
   * constraints, inlets), applied to a field a transfer made (XPIC's
   * smoothed passes); `weight` is the coefficient with which that field
   * enters the particles' velocities, so that the walls book the momentum
   * their holds pass on. NULL: the face conditions of `boundary` */
  void (*hold)(void *ctx, double *vel, double weight);
  void *sum_ctx; /* of all three */
} mrn_transfer;

#endif
