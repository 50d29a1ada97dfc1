/* moraine: checkpoints — the complete state of a simulation in one HDF5 file.
 *
 * A checkpoint holds everything a step depends on: the grid definition, the
 * shape function, the strategy, the boundary conditions, gravity, the
 * time-step policy, the clock, the energy accumulators, the materials (type
 * and parameters) and every particle field with its history variables, all
 * doubles stored bit for bit. Loading it and stepping on continues exactly as
 * the saved simulation would have. The layout is in doc/checkpoint-format.md.
 *
 * Loading and importing validate the whole file before anything is built: a
 * missing, truncated, foreign or inconsistent file is refused with a message
 * naming the file and what is wrong, and leaves the caller's simulation as it
 * was. */
#ifndef MRN_IO_CHECKPOINT_H
#define MRN_IO_CHECKPOINT_H

#include "io/stash.h"
#include "solver/simulation.h"

#define MRN_CHECKPOINT_FORMAT "moraine checkpoint"
/* 2: the file starts with a checksum table (doc/checkpoint-format.md);
 * files of version 1 have none and still load, with a warning */
#define MRN_CHECKPOINT_VERSION 2

/* What a load found besides the simulation itself. */
typedef struct mrn_checkpoint_info {
  int version;               /* format version of the file */
  char moraine_version[64];  /* the moraine that wrote it, "0.1.0 (abc1234)" */
  long particles;
  int checksums;             /* 1: every byte was checked against the file's checksums */
  /* The saved time-step policy was a function (a Lua callback), which a file
   * cannot hold: the loaded simulation steps with a fixed dt equal to the last
   * dt until the deck sets its function again. `note` says so in words. */
  int dt_function_dropped;
  char note[256];
} mrn_checkpoint_info;

/* Write the complete state to `path`, crash-safe: the file is written under a
 * temporary name in the same directory and renamed into place when complete.
 * 0, or MRN_ERR_IO with the path and reason (no partial file is left). */
int mrn_checkpoint_save(const mrn_sim *sim, const char *path);
/* the same with the values of `stash` (may be NULL) in the group /resume:
 * what a resumed run needs beyond the state (io/stash.h) */
int mrn_checkpoint_save_stash(const mrn_sim *sim, const mrn_stash *stash, const char *path);
/* The /resume values of the checkpoint at `path` (its checksums checked
 * first) into a stash for loading; a file without the group gives an empty
 * one. 0, or MRN_ERR_IO with a message naming the file. */
int mrn_checkpoint_read_stash(const char *path, mrn_stash *stash);

/* Read a checkpoint into a new simulation; materials are re-created from the
 * registry by type name with their saved parameters. NULL with a message
 * naming the file and the problem on any failure. */
mrn_sim *mrn_checkpoint_load(const char *path);
/* the same, also filling `info` (may be NULL) */
mrn_sim *mrn_checkpoint_load_info(const char *path, mrn_checkpoint_info *info);

/* Write the checksum table of a checkpoint anew, for a file changed on
 * purpose with another program (h5py, the HDF5 C API) after moraine wrote
 * it: the loader refuses a file whose bytes differ from its table. The file
 * must have been written by moraine with checksums (its user block holds the
 * table); it is read whole into memory. 0, or MRN_ERR_IO with the path and
 * the reason. */
int mrn_checkpoint_sign(const char *path);

/* Append the particles of a checkpoint to an existing simulation of the same
 * dimension (its grid may differ), keeping every particle field and the
 * history variables. `override` (may be NULL) is a material given to every
 * imported particle, registered with mrn_sim_add_material; without it the
 * checkpoint's materials are re-created (or reused when the simulation has an
 * identical one). History variables carry over to particles that keep the
 * same model and start at zero otherwise; masses are kept. `offset` (may be NULL) is added to the positions (and the
 * initial positions, so displacements carry over). Imported particles get new
 * ids. Every particle must land inside the grid. On success *count (may be
 * NULL) receives the number imported; on failure the simulation is untouched
 * and an error code is returned with the message set. */
int mrn_checkpoint_import(mrn_sim *sim, const char *path, mrn_material *override, const double offset[3],
                          long *count);

#endif
