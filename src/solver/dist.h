/* moraine: a simulation spread over the processes of an MPI run.
 *
 * The grid is cut into slabs along its last axis (y in 2D, z in 3D), one
 * per process, at cell rows chosen so that each slab holds about the same
 * number of particles, and at least MRN_DIST_MIN_CELLS cells thick (2h + 1
 * when CPDI's wider bands need more, below). Every
 * process keeps the whole grid's arrays but only the particles whose cell
 * lies in its slab (the last row of cells and anything beyond belong to
 * the last slab, anything below the first to the first).
 *
 * A step runs as on one process, with three exchanges:
 * - after each P2G (mass, momentum, force) the node rows a neighbour's
 *   particles reach as well, the band [cut - h, cut + h] around each cut,
 *   are summed with that neighbour's: both then hold the same nodal values
 *   there, and the grid update, run by both on those rows, gives both the
 *   same velocities for G2P. h is 1 (a kernel of support up to 4 cells
 *   reaches one row below its cell and two above), or with CPDI as far as
 *   its stretched domains make the shape functions reach, agreed by every
 *   process each step (mrn_dist_halo). A periodic cut axis
 *   makes the last slab and the first neighbours through the wrap: their
 *   band, around cut 0, is the last h node rows and the first h + 1. The
 *   work done on a node (damping, friction) is booked by the process that
 *   owns its row (grid.own_lo, own_hi) so that the sums over processes
 *   count it once.
 * - the touch bits of friction faces are combined the same way (OR), and
 *   before them the marks from which gap_check releases a column (material
 *   on the face, and material above it, over the column's patch);
 * - after the step, particles whose cell left the slab go to the process
 *   that owns it, wherever that is (a particle may cross several slabs, or
 *   wrap around a periodic axis).
 * Every exchange first agrees on the step's outcome: a process that failed
 * (a particle out of the grid, a bad state) makes every process stop with
 * its message, never one process waiting for another.
 *
 * Until the first step or run, every process holds every particle (the
 * deck builds them the same on each); mrn_dist_start then keeps each
 * process's own. The particle sums (diagnostics, energies, the time step)
 * are then summed over processes. Files are written by process 0, with the
 * particles gathered there in the order of their ids. */
#ifndef MRN_SOLVER_DIST_H
#define MRN_SOLVER_DIST_H

#include <stddef.h>

#include "core/comm.h"

struct mrn_sim;
struct mrn_particles;

#define MRN_DIST_MIN_CELLS 4
/* the default re-cut policy (mrn_sim_set_rebalance) */
#define MRN_DIST_REBALANCE_EVERY 100
#define MRN_DIST_IMBALANCE 1.2

typedef struct mrn_dist {
  int rank, size;
  int axis;          /* the cut axis: the grid's last */
  int *cut;          /* size + 1 cell rows: process r holds cells [cut[r], cut[r + 1]) */
  int halo;          /* h: the band around a cut is the node rows [cut - h, cut + h] */
  /* bytes this process sent, since the start: halo sums, particles */
  double halo_bytes, migrate_bytes;
  long migrated;     /* particles sent */
  long rebalances;
  unsigned char *buf; /* exchange buffers */
  size_t buf_cap;
  /* while gathered (mrn_dist_gather_begin): process 0's own particles, and
   * this process's books of work */
  struct mrn_particles *held;
  double held_books[5];
  double *held_mass, *held_vel, *held_force; /* process 0's nodal arrays */
  unsigned char *held_contact;
} mrn_dist;

/* Spread the simulation over the processes if there are several and it
 * has not been yet: refuses, with a message naming the option, what the
 * distributed step does not do yet; cuts the grid by particle count and
 * keeps this process's particles. 0 or an error code. */
int mrn_dist_start(struct mrn_sim *sim);
void mrn_dist_free(mrn_dist *d);
/* of the particles [first, n) just added on every process alike, keep
 * this process's own */
int mrn_dist_adopt(struct mrn_sim *sim, size_t first);

/* The outcome `rc` of this process's part of a collective stage, agreed by
 * all: the first failing process's code, with its message on every
 * process. Called with MRN_OK it is a check that nobody failed. */
int mrn_dist_agree(const struct mrn_sim *sim, int rc);

/* after a P2G into `what` (MRN_CLEAR_MASS_MOM, MRN_CLEAR_FORCE), given the
 * outcome so far: agree, then sum the bands with the neighbours */
int mrn_dist_sum_halo(struct mrn_sim *sim, unsigned what, int rc);
/* the same for one nodal array of ncomp values per node that a transfer
 * scattered into (mrn_transfer.sum_nodal: XPIC's smoothing passes); ctx
 * is the simulation */
void mrn_dist_sum_nodal(void *ctx, double *values, int ncomp);
/* the friction faces' touch bits, OR-ed over the bands */
void mrn_dist_touch(struct mrn_sim *sim);
/* given the outcome so far: agree, then OR `narrays` arrays of one byte per
 * node, one after another at `marks`, over the bands (gap_check's marks:
 * grid/boundary.h, mrn_boundary_touch); ctx is the simulation */
int mrn_dist_or_marks(void *ctx, unsigned char *marks, int narrays, int rc);
/* The band's half width h for this step, given the outcome so far, for
 * shape functions that reach `reach` cells from their particles (this
 * process's; CPDI's grow with the domains the step froze, and the largest
 * is agreed by every process): 1, more for CPDI's stretched domains; an
 * error when a slab is too thin for it. */
int mrn_dist_halo(struct mrn_sim *sim, double reach, int rc);
/* after the step: agree on rc, re-cut if due, send the particles that left */
int mrn_dist_migrate(struct mrn_sim *sim, int rc);
/* re-cut the grid by particle count now and move the particles */
int mrn_dist_rebalance(struct mrn_sim *sim);

/* the error for particles given velocities (APIC's, TPIC's initial affine
 * field) after the run was spread over the processes */
int mrn_dist_refuse_late_affine(const struct mrn_sim *sim);

/* the re-cut policy: every `every` steps (0: never) when the largest
 * particle count exceeds the mean by `imbalance` (>= 1); 0 or an error */
int mrn_sim_set_rebalance(struct mrn_sim *sim, long every, double imbalance);

/* 1 when this process's slab holds the cell of x (always, undistributed) */
int mrn_dist_owns_point(const struct mrn_sim *sim, const double x[3]);

/* v[0 .. n) summed (or min, max) over the processes of a distributed
 * simulation; nothing when it is not (yet) distributed */
void mrn_dist_reduce(const struct mrn_sim *sim, double *v, int n, mrn_comm_op op);

/* the books of work kept per process (friction, damping, the energy that
 * left), summed over the processes */
void mrn_dist_books(const struct mrn_sim *sim, double *friction, double *damping, double *outflow);

/* Process 0 takes every particle, in the order of their ids, in place of
 * its own until mrn_dist_gather_end, so that a writer sees the whole set;
 * the others keep theirs. Collective. 0 or an error code. */
int mrn_dist_gather_begin(const struct mrn_sim *sim);
void mrn_dist_gather_end(const struct mrn_sim *sim);

#endif
