/* moraine: a simulation spread over the processes of an MPI run.
 *
 * The grid is cut into slabs along its last axis (y in 2D, z in 3D), one
 * per process, at cell rows chosen so that each slab holds about the same
 * number of particles, and at least MRN_DIST_MIN_CELLS cells thick (2h + 1
 * when CPDI's or cpGIMP's wider bands need more, below). Every
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
 *   reaches one row below its cell and two above), or with CPDI or cpGIMP
 *   as far as their stretched domains make the shape functions reach, agreed by every
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
 * Walls (dist_walls.c): a wall's contact columns may reach beyond a band,
 * so every process works on the columns of all, whose sums are taken over
 * the processes (each node by its row's owner), and the reactions are summed
 * at the end of the step, so that every process moves a rigid body alike.
 * Contact between bodies halo-sums each body's fields like the single one.
 * Every exchange first agrees on the step's outcome: a process that failed
 * (a particle out of the grid, a bad state) makes every process stop with
 * its message, never one process waiting for another.
 *
 * Until the first step or run, every process holds every particle (the
 * deck builds them the same on each); mrn_dist_start then keeps each
 * process's own. The particle sums (diagnostics, energies, the time step)
 * are then summed over processes, and so are the books each keeps
 * (mrn_books). Files are written by process 0, with the particles gathered
 * there in the order of their ids, but for the particle snapshots, written
 * as a piece per process (io/output.h).
 *
 * Ids stay those of a run on one process: next_id is the same on every
 * process. Particles made during a run alike on every process (an inflow
 * source's layers, add_particles) are adopted (mrn_dist_adopt) by the
 * process whose slab holds them; the children of split particles take ids
 * in the order of their parents' ids over every process
 * (mrn_dist_key_places). Point forces are spread to the nodes before the
 * internal force's halo sum. */
#ifndef MRN_SOLVER_DIST_H
#define MRN_SOLVER_DIST_H

#include <stddef.h>
#include <stdint.h>

#include "core/comm.h"
#include "grid/wall.h"

struct mrn_sim;
struct mrn_particles;

#define MRN_DIST_MIN_CELLS 4
/* the default re-cut policy (mrn_sim_set_rebalance) */
#define MRN_DIST_REBALANCE_EVERY 100
#define MRN_DIST_IMBALANCE 1.2

/* The books kept per process: the work done on the nodes of its rows
 * (friction, damping, the sources' inlets), that of the point forces on
 * its particles, and what its particles brought in (sources, particles
 * added during a run) and took out (deleted on leaving). All doubles: the
 * counts too, so that the struct is summed as one array. */
typedef struct mrn_books {
  double friction, damping, external, inflow, inflow_work, inflow_mass, inflow_particles, outflow, outflow_mass,
      outflow_particles;
} mrn_books;

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
  mrn_books held_books;
  double *held_mass, *held_vel, *held_force; /* process 0's nodal arrays */
  unsigned char *held_contact;
  unsigned char **held_walls; /* process 0's walls' node states, while gathered */
  mrn_walls_share walls;      /* the walls' sums over the processes (grid/wall.h) */
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
/* after a P2G of the bodies' fields (solver/contact.h): every body's mass,
 * momentum and mass gradient (MRN_CLEAR_MASS_MOM) and force
 * (MRN_CLEAR_FORCE), as mrn_dist_sum_halo */
int mrn_dist_sum_bodies(struct mrn_sim *sim, unsigned what, int rc);
/* the friction faces' touch bits, OR-ed over the bands */
void mrn_dist_touch(struct mrn_sim *sim);
/* the `mask` bits of a byte per node OR-ed with the neighbours' over the
 * bands; fresh(arg, node), when not NULL, for every node that gains a bit
 * (its first error is returned). Collective; 0 or an error. */
int mrn_dist_or_bands(struct mrn_sim *sim, unsigned char *bits, unsigned char mask,
                      int (*fresh)(void *arg, size_t node), void *arg);
/* a value every process holds alike, as a book of this process's (summed
 * over the processes, mrn_dist_books): itself on process 0, else 0 */
double mrn_dist_once(const struct mrn_sim *sim, double value);

/* The walls of a distributed run (solver/dist_walls.c, grid/wall.h): their
 * sums over the processes, attached before each step's touch; after a
 * re-cut, every process takes the contacts of all; for a checkpoint,
 * process 0 holds them (mrn_dist_gather_begin, _end) */
void mrn_dist_walls_attach(struct mrn_sim *sim);
int mrn_dist_walls_recut(struct mrn_sim *sim);
int mrn_dist_walls_gather(struct mrn_sim *sim);
void mrn_dist_walls_gather_end(struct mrn_sim *sim);
/* given the outcome so far: agree, then OR `narrays` arrays of one byte per
 * node, one after another at `marks`, over the bands (gap_check's marks:
 * grid/boundary.h, mrn_boundary_touch); ctx is the simulation */
int mrn_dist_or_marks(void *ctx, unsigned char *marks, int narrays, int rc);
/* The band's half width h for this step, given the outcome so far, for
 * shape functions that reach `reach` cells from their particles (this
 * process's; CPDI's and cpGIMP's grow with the domains the step froze, and
 * the largest is agreed by every process): 1, more for stretched domains; an
 * error when a slab is too thin for it. */
int mrn_dist_halo(struct mrn_sim *sim, double reach, int rc);
/* after the step: agree on rc, re-cut if due, send the particles that left */
int mrn_dist_migrate(struct mrn_sim *sim, int rc);
/* re-cut the grid by particle count now and move the particles */
int mrn_dist_rebalance(struct mrn_sim *sim);

/* n values replaced by their maxima over the processes (mrn_transfer.max_over);
 * ctx is the simulation */
void mrn_dist_max_over(void *ctx, double *values, int n);

/* the re-cut policy: every `every` steps (0: never) when the largest
 * particle count exceeds the mean by `imbalance` (>= 1); 0 or an error */
int mrn_sim_set_rebalance(struct mrn_sim *sim, long every, double imbalance);

/* 1 when this process's slab holds the cell of x (always, undistributed) */
int mrn_dist_owns_point(const struct mrn_sim *sim, const double x[3]);

/* v[0 .. n) summed (or min, max) over the processes of a distributed
 * simulation; nothing when it is not (yet) distributed */
void mrn_dist_reduce(const struct mrn_sim *sim, double *v, int n, mrn_comm_op op);

/* the books (mrn_books) summed over the processes: the same on each */
void mrn_dist_books(const struct mrn_sim *sim, mrn_books *b);

/* Keys increasing on each process and distinct over all of them: the
 * place of each among every process's keys, place[k] (k on one process),
 * and their number, *total. Agrees on rc first (the outcome so far);
 * collective. 0 or an error code. */
int mrn_dist_key_places(const struct mrn_sim *sim, const int64_t *keys, size_t n, int64_t *place, int64_t *total,
                        int rc);

/* Process 0 takes every particle, in the order of their ids, in place of
 * its own until mrn_dist_gather_end, so that a writer sees the whole set;
 * the others keep theirs. Collective. 0 or an error code. */
int mrn_dist_gather_begin(const struct mrn_sim *sim);
void mrn_dist_gather_end(const struct mrn_sim *sim);
/* The grid alone: process 0's nodal mass, velocity, force and contact bits
 * hold every node's values, each row from the process that owns it, until
 * mrn_dist_gather_grid_end. Collective. 0 or an error code, agreed. */
int mrn_dist_gather_grid_begin(const struct mrn_sim *sim);
void mrn_dist_gather_grid_end(const struct mrn_sim *sim);

/* Every process's `bytes` of `mine` on every process, in the order of the
 * ranks: *all (to free) holds *total bytes. Agrees on rc (the outcome so
 * far) first, and on having the room; collective. 0 or an error code. */
int mrn_dist_allgather(const struct mrn_sim *sim, const void *mine, size_t bytes, unsigned char **all, size_t *total,
                       int rc);
/* Every process's n records of rec bytes (`mine`), each ending with the
 * int64 id of its particle, on every process in the order of the ids:
 * *all (to free) holds *total records. Undistributed, this process's alone,
 * sorted. Collective. 0 or an error code. */
int mrn_dist_gather_by_id(const struct mrn_sim *sim, const unsigned char *mine, size_t n, size_t rec,
                          unsigned char **all, size_t *total);

#endif
