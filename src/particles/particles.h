/* moraine: material point storage, structure of arrays.
 *
 * Each field is one contiguous array; vector fields hold 3 values per
 * particle (z = 0 in 2D), symmetric tensors 6 in the order xx, yy, zz, xy,
 * yz, xz. The full tensors (F and the affine matrix) hold 9 values per
 * particle in 3D (row-major) and only their in-plane block in 2D, 4 values
 * xx, xy, yx, yy (row-major 2 x 2): in plane strain F's z row and column are
 * those of I and the affine matrix's are zero, so the 2D kernels read and
 * write 32 bytes of each instead of 72 (mrn_tensor_stride; checkpoints and
 * outputs keep all 9 in either dimension, mrn_particle_field_export).
 * Adding a field means adding it to the MRN_PARTICLE_FIELDS list below:
 * allocation, growth, removal and copying all follow from that one list. */
#ifndef MRN_PARTICLES_PARTICLES_H
#define MRN_PARTICLES_PARTICLES_H

#include <stddef.h>
#include <stdint.h>

#include "core/tensor.h"

/* X(name, components, planar, zz, description) -- every double-valued field:
 * `components` per particle in 3D (and in files), `planar` stored per
 * particle in 2D; a planar full tensor's zz entry when expanded is `zz` */
#define MRN_PARTICLE_FIELDS(X)                                                                       \
  X(x, 3, 3, 0.0, "position (m)")                                                                    \
  X(x0, 3, 3, 0.0, "initial position (m), for the displacement")                                     \
  X(v, 3, 3, 0.0, "velocity (m/s)")                                                                  \
  X(mass, 1, 1, 0.0, "mass (kg; kg/m in 2D, per unit thickness)")                                    \
  X(vol0, 1, 1, 0.0, "initial volume")                                                               \
  X(F, 9, 4, 1.0, "deformation gradient")                                                            \
  X(affine, 9, 4, 0.0, "APIC C = B D^-1 (000, Eq. 25) or Taylor grad v (000, Eq. 22) (1/s)")        \
  X(stress, 6, 6, 0.0, "Cauchy stress (Pa), tension positive")                                       \
  X(strain, 6, 6, 0.0, "accumulated small strain (sum of symmetric velocity-gradient increments)")    \
  X(e_elastic, 1, 1, 0.0, "elastic energy stored (J; J/m in 2D)")                                    \
  X(w_plastic, 1, 1, 0.0, "accumulated plastic work (J), negative while dissipating (000, Eq. 65)")

/* A per-particle value registered by a deck (sim:particle_field): `ncomp`
 * doubles per particle at `offset` within each particle's record of the
 * `user` array, starting at `init` for every particle added. */
#define MRN_USER_FIELDS_MAX 16
#define MRN_USER_FIELD_NAME 32
typedef struct mrn_user_field {
  char name[MRN_USER_FIELD_NAME];
  int ncomp;
  int offset;
  double init;
  char unit[16];
} mrn_user_field;

typedef struct mrn_particles {
  size_t n, cap;
  int dim;
#define MRN_DECLARE_FIELD(name, ncomp, planar, zz, desc) double *name;
  MRN_PARTICLE_FIELDS(MRN_DECLARE_FIELD)
#undef MRN_DECLARE_FIELD
  int32_t *material; /* index into the simulation's material list */
  int64_t *id;       /* stable identifier, unique in a simulation */
  double *state;     /* material history variables, `state_stride` per particle */
  int state_stride;
  double *user;      /* values of the registered fields, `user_stride` per particle */
  int user_stride;
  int nuser;
  mrn_user_field user_fields[MRN_USER_FIELDS_MAX];
  int64_t next_id;
} mrn_particles;

void mrn_particles_init(mrn_particles *p, int dim);
void mrn_particles_free(mrn_particles *p);
int mrn_particles_reserve(mrn_particles *p, size_t cap);
/* widen the history-variable storage to at least `stride` values per particle */
int mrn_particles_set_state_stride(mrn_particles *p, int stride);
/* Append one particle at x with mass and volume; every other field starts at
 * rest and unstrained (F = I, zero stress). Returns its index, or -1 on
 * allocation failure (message set). */
long mrn_particles_add(mrn_particles *p, const double x[3], double mass, double vol, int material);
/* Register a per-particle field of ncomp values that every particle, present
 * and future, starts at `init`. 0 or MRN_ERR (name taken, too many fields,
 * memory; message set). */
int mrn_particles_add_user_field(mrn_particles *p, const char *name, int ncomp, double init, const char *unit);
/* the registered field `name`, or NULL */
const mrn_user_field *mrn_particles_user_field(const mrn_particles *p, const char *name);
/* bytes one particle takes in p's arrays: every field of
 * MRN_PARTICLE_FIELDS in p's dimension, material and id, history variables
 * and registered fields */
size_t mrn_particles_record_bytes(const mrn_particles *p);
/* Append a copy of particle i (every field, history variable and registered
 * field) with the id `id`, one not in use (next_id is left to the caller).
 * Returns its index, or -1 on allocation failure (message set). */
long mrn_particles_clone(mrn_particles *p, size_t i, int64_t id);
/* particle i's record (mrn_particles_record_bytes bytes, id included) into
 * buf, and a record appended as a particle with the id it holds: how a
 * particle moves between the processes of a distributed run. Both sets
 * must have the same dimension, history and registered fields. */
void mrn_particles_pack(const mrn_particles *p, size_t i, unsigned char *buf);
long mrn_particles_unpack(mrn_particles *p, const unsigned char *buf);
/* remove particles whose keep[i] == 0, preserving order */
void mrn_particles_compact(mrn_particles *p, const unsigned char *keep);

/* Current volume of particle i (m^3; m^2 in 2D): V = J V0 with J = det F
 * (001, after Eq. 2). In plane strain F's z row and column are those of I,
 * so J is the determinant of the stored in-plane block. Not stored (8 bytes
 * per particle): worked out where it is read. The kernels, whose dimension
 * is a constant, call mrn_particle_volume_dim. */
static inline double mrn_particle_volume_dim(const mrn_particles *p, size_t i, const int dim) {
  const double *F = p->F + (size_t)mrn_tensor_stride(dim) * i;
  return p->vol0[i] * (dim == 2 ? F[0] * F[3] - F[1] * F[2] : mat_det(F));
}

static inline double mrn_particle_volume(const mrn_particles *p, size_t i) {
  return mrn_particle_volume_dim(p, i, p->dim);
}

/* field table, for output and generic access */
typedef struct mrn_particle_field_info {
  const char *name;
  int ncomp;  /* values per particle in 3D, in checkpoints and in outputs */
  int planar; /* values stored per particle in 2D */
  double zz;  /* a planar full tensor's zz entry (mrn_tensor_expand) */
  const char *doc;
  size_t offset; /* offset of the pointer inside mrn_particles */
} mrn_particle_field_info;

int mrn_particle_field_count(void);
const mrn_particle_field_info *mrn_particle_field_at(int i);
const mrn_particle_field_info *mrn_particle_field_find(const char *name);
static inline double *mrn_particle_field_data(const mrn_particles *p, const mrn_particle_field_info *f) {
  return *(double *const *)((const char *)p + f->offset);
}
/* values stored per particle for field f in p's dimension */
static inline int mrn_particle_field_stride(const mrn_particles *p, const mrn_particle_field_info *f) {
  return p->dim == 2 ? f->planar : f->ncomp;
}
/* particles first .. first + count - 1 of field f into out, f->ncomp values
 * each (full tensors expanded in 2D) */
void mrn_particle_field_export(const mrn_particles *p, const mrn_particle_field_info *f, size_t first, size_t count,
                               double *out);
/* the reverse: f->ncomp values per particle from in, stored in p's layout */
void mrn_particle_field_import(mrn_particles *p, const mrn_particle_field_info *f, size_t first, size_t count,
                               const double *in);

#endif
