/* moraine: what the checkpoint writer and reader share.
 *
 * The reader turns a file into a ck_data (every value checked) before a
 * simulation is touched; load and import then build from it. */
#ifndef MRN_IO_CHECKPOINT_INTERNAL_H
#define MRN_IO_CHECKPOINT_INTERNAL_H

#include <hdf5.h>
#include <stdint.h>

#include "io/h5util.h"
#include "grid/wall.h"
#include "io/stash.h"
#include "solver/simulation.h"

/* upper bound on history variables per particle, against absurd files */
#define CK_MAX_STATE_STRIDE 4096
/* the next particle id, a counter as the step (solver/sim_scalars.h) */
#define CK_MAX_COUNTER MRN_MAX_COUNTER

typedef struct ck_data {
  /* / */
  int version;
  int checksums; /* 1: the file's checksum table was verified (checkpoint_sum.c) */
  char moraine_version[64];
  /* /simulation: the rows of solver/sim_scalars.h, as the members of mrn_sim */
  struct {
    MRN_SIM_SCALARS(MRN_SIM_DECLARE)
  };
  /* /grid */
  double origin[3], size[3], cell;
  int ncell[3];
  int64_t ncontact; /* rows (node, bits) of the friction faces' contacts (grid.contact) */
  int64_t *contact;
  int64_t nbodies_held; /* nodes where the contact between bodies held (MRN_GRID_BODIES_HELD) */
  int64_t *bodies_held;
  /* /scheme, /boundary */
  mrn_scheme scheme;
  mrn_boundary boundary;
  /* /walls: each wall's spec (vertices malloc'd), its state and contacts */
  int nwalls;
  struct ck_wall *walls;
  /* /dt_policy */
  mrn_dt_kind dt_kind;
  double dt_value, dt_min, dt_max;
  /* /materials: prepared materials, one reference each */
  int nmaterials;
  mrn_material *materials[MRN_MAX_MATERIALS];
  /* /particles */
  int64_t n, next_id;
  int state_stride;
  double **field; /* one array per mrn_particle_field_at(i), n * ncomp values */
  /* /particles/user: fields the deck registered (name, ncomp, init, unit; offset unused) */
  int nuser;
  mrn_user_field user[MRN_USER_FIELDS_MAX];
  double *user_values[MRN_USER_FIELDS_MAX];
  int32_t *material;
  int64_t *id;
  double *state; /* n * state_stride */
  /* /sources: the sources' states (optional) */
  int nsources;
  mrn_source_state sources[2 * MRN_MAX_SOURCES];
} ck_data;

/* a wall as read (checkpoint_walls.c) */
typedef struct ck_wall {
  mrn_wall_spec spec;
  double ref[3], rot[9], force[3], moment[3], total_impulse[3], work, work_friction, body_work;
  int64_t ncontact;
  int64_t *contact;
} ck_wall;
void ck_save_walls(mrn_h5w *w, const mrn_sim *sim);
void ck_read_walls(mrn_h5r *r, ck_data *d, int64_t nodes);
int ck_take_walls(mrn_sim *sim, const ck_data *d);
void ck_free_walls(ck_data *d);

/* the array of the particle field `name` (one of the table's) */
static inline double *ck_field(const ck_data *d, const char *name) {
  return d->field[mrn_particle_field_find(name) - mrn_particle_field_at(0)];
}

/* Read and validate the whole checkpoint at `path`. 0, or MRN_ERR_IO with a
 * message naming the file (nothing to free then). */
int ck_read(const char *path, ck_data *d);
void ck_free(ck_data *d);

/* ---- the checksum table (checkpoint_sum.c) ---- */

#define CK_SUM_PATH 160 /* longest dataset path in the table, with its NUL */

/* a dataset's values: bytes [offset, offset + bytes) of the file */
typedef struct ck_range {
  uint64_t offset, bytes;
  uint32_t crc;
  char path[CK_SUM_PATH];
} ck_range;

typedef struct ck_ranges {
  ck_range *r; /* sorted by offset */
  int n, cap;
} ck_ranges;

/* the user block a file of `ndatasets` datasets reserves for its table */
uint64_t ck_sum_userblock(int ndatasets);
/* the ranges of the datasets of an open file; 0, or -1 (nothing to free) */
int ck_sum_collect(hid_t file, ck_ranges *ranges);
void ck_ranges_free(ck_ranges *ranges);
/* Fill the first `userblock` bytes of the file image `image` (`size` bytes,
 * the user block included) with the table of `ranges`; 0, or -1 when it
 * does not fit. */
int ck_sum_write_image(unsigned char *image, uint64_t size, uint64_t userblock, ck_ranges *ranges);
/* Check the file at `path` against its table before HDF5 reads it: 0 when
 * every checksum holds (*present = 1) or the file has no table (*present =
 * 0: older files, or not a checkpoint); else MRN_ERR_IO with a message
 * naming the file and the damaged dataset or part. */
int ck_sum_verify(const char *path, int *present);

/* the group /resume of the values of `stash` (NULL or empty: none; checkpoint_stash.c) */
void ck_save_stash(mrn_h5w *w, const mrn_stash *stash);

/* NULL-terminated names of the time-step policy kinds, in enum order */
const char *const *ck_dt_kind_names(void);

#endif
