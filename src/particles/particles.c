#include "particles/particles.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

static const mrn_particle_field_info field_table[] = {
#define MRN_FIELD_INFO(name, ncomp, planar, zz, desc) {#name, ncomp, planar, zz, desc, offsetof(mrn_particles, name)},
    MRN_PARTICLE_FIELDS(MRN_FIELD_INFO)
#undef MRN_FIELD_INFO
};
enum { FIELD_COUNT = sizeof field_table / sizeof field_table[0] };

int mrn_particle_field_count(void) { return FIELD_COUNT; }
const mrn_particle_field_info *mrn_particle_field_at(int i) { return &field_table[i]; }
const mrn_particle_field_info *mrn_particle_field_find(const char *name) {
  for (int i = 0; i < FIELD_COUNT; i++)
    if (strcmp(field_table[i].name, name) == 0) return &field_table[i];
  return NULL;
}

static double **field_ptr(mrn_particles *p, int i) { return (double **)((char *)p + field_table[i].offset); }

/* values stored per particle for field i */
static size_t stride_of(const mrn_particles *p, int i) {
  return (size_t)mrn_particle_field_stride(p, &field_table[i]);
}

void mrn_particle_field_export(const mrn_particles *p, const mrn_particle_field_info *f, size_t first, size_t count,
                               double *out) {
  const double *data = mrn_particle_field_data(p, f);
  const int stored = mrn_particle_field_stride(p, f);
  if (!count) return; /* data may be NULL */
  if (stored == f->ncomp) {
    memcpy(out, data + first * (size_t)stored, count * (size_t)stored * sizeof(double));
    return;
  }
  for (size_t i = 0; i < count; i++)
    mrn_tensor_expand(p->dim, data + (first + i) * (size_t)stored, f->zz, out + i * (size_t)f->ncomp);
}

void mrn_particle_field_import(mrn_particles *p, const mrn_particle_field_info *f, size_t first, size_t count,
                               const double *in) {
  double *data = mrn_particle_field_data(p, f);
  const int stored = mrn_particle_field_stride(p, f);
  if (!count) return;
  if (stored == f->ncomp) {
    memcpy(data + first * (size_t)stored, in, count * (size_t)stored * sizeof(double));
    return;
  }
  for (size_t i = 0; i < count; i++)
    mrn_tensor_pack(p->dim, in + i * (size_t)f->ncomp, data + (first + i) * (size_t)stored);
}

void mrn_particles_init(mrn_particles *p, int dim) {
  memset(p, 0, sizeof *p);
  p->dim = dim;
  p->next_id = 1;
}

void mrn_particles_free(mrn_particles *p) {
  for (int i = 0; i < FIELD_COUNT; i++) {
    free(*field_ptr(p, i));
    *field_ptr(p, i) = NULL;
  }
  free(p->material);
  free(p->id);
  free(p->state);
  free(p->user);
  p->user = NULL;
  p->material = NULL;
  p->id = NULL;
  p->state = NULL;
  p->n = p->cap = 0;
}

static int grow(void **ptr, size_t count, size_t elem) {
  void *q = realloc(*ptr, count * elem);
  if (!q && count) return 0;
  *ptr = q;
  return 1;
}

size_t mrn_particles_record_bytes(const mrn_particles *p) {
  size_t values = (size_t)p->state_stride + (size_t)p->user_stride;
  for (int i = 0; i < FIELD_COUNT; i++) values += stride_of(p, i);
  return values * sizeof(double) + sizeof *p->material + sizeof *p->id;
}

int mrn_particles_reserve(mrn_particles *p, size_t cap) {
  if (cap <= p->cap) return MRN_OK;
  for (int i = 0; i < FIELD_COUNT; i++)
    if (!grow((void **)field_ptr(p, i), cap, sizeof(double) * stride_of(p, i)))
      return mrn_error("particles: out of memory for %zu particles", cap);
  if (!grow((void **)&p->material, cap, sizeof(int32_t)) || !grow((void **)&p->id, cap, sizeof(int64_t)) ||
      (p->state_stride > 0 && !grow((void **)&p->state, cap, sizeof(double) * p->state_stride)) ||
      (p->user_stride > 0 && !grow((void **)&p->user, cap, sizeof(double) * p->user_stride)))
    return mrn_error("particles: out of memory for %zu particles", cap);
  p->cap = cap;
  return MRN_OK;
}

int mrn_particles_set_state_stride(mrn_particles *p, int stride) {
  if (stride <= p->state_stride) return MRN_OK;
  double *s = calloc(p->cap ? p->cap : 1, sizeof(double) * stride);
  if (!s) return mrn_error("particles: out of memory for history variables");
  for (size_t i = 0; i < p->n; i++)
    for (int k = 0; k < p->state_stride; k++) s[i * stride + k] = p->state[i * p->state_stride + k];
  free(p->state);
  p->state = s;
  p->state_stride = stride;
  return MRN_OK;
}

long mrn_particles_add(mrn_particles *p, const double x[3], double mass, double vol, int material) {
  if (p->n == p->cap && mrn_particles_reserve(p, p->cap ? 2 * p->cap : 256) != MRN_OK) return -1;
  size_t i = p->n++;
  for (int f = 0; f < FIELD_COUNT; f++) {
    double *data = *field_ptr(p, f);
    memset(data + i * stride_of(p, f), 0, sizeof(double) * stride_of(p, f));
  }
  for (int d = 0; d < 3; d++) p->x[3 * i + d] = p->x0[3 * i + d] = x[d];
  p->mass[i] = mass;
  p->vol0[i] = vol;
  static const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  mrn_tensor_pack(p->dim, identity, p->F + (size_t)mrn_tensor_stride(p->dim) * i);
  p->material[i] = material;
  p->id[i] = p->next_id++;
  for (int k = 0; k < p->state_stride; k++) p->state[i * p->state_stride + k] = 0.0;
  for (int f = 0; f < p->nuser; f++)
    for (int k = 0; k < p->user_fields[f].ncomp; k++)
      p->user[i * p->user_stride + p->user_fields[f].offset + k] = p->user_fields[f].init;
  return (long)i;
}

long mrn_particles_clone(mrn_particles *p, size_t i, int64_t id) {
  if (p->n == p->cap && mrn_particles_reserve(p, p->cap ? 2 * p->cap : 256) != MRN_OK) return -1;
  const size_t j = p->n++;
  for (int f = 0; f < FIELD_COUNT; f++) {
    const size_t nc = stride_of(p, f);
    double *data = *field_ptr(p, f);
    memcpy(data + j * nc, data + i * nc, sizeof(double) * nc);
  }
  p->material[j] = p->material[i];
  p->id[j] = id;
  if (p->state_stride)
    memcpy(p->state + j * p->state_stride, p->state + i * p->state_stride, sizeof(double) * p->state_stride);
  if (p->user_stride)
    memcpy(p->user + j * p->user_stride, p->user + i * p->user_stride, sizeof(double) * p->user_stride);
  return (long)j;
}

/* the record of a particle: each field's values, the history variables and
 * registered fields, then the material index and the id */
void mrn_particles_pack(const mrn_particles *p, size_t i, unsigned char *buf) {
  for (int f = 0; f < FIELD_COUNT; f++) {
    const size_t nc = stride_of(p, f);
    memcpy(buf, *field_ptr((mrn_particles *)p, f) + i * nc, sizeof(double) * nc);
    buf += sizeof(double) * nc;
  }
  if (p->state_stride) memcpy(buf, p->state + i * p->state_stride, sizeof(double) * p->state_stride);
  buf += sizeof(double) * p->state_stride;
  if (p->user_stride) memcpy(buf, p->user + i * p->user_stride, sizeof(double) * p->user_stride);
  buf += sizeof(double) * p->user_stride;
  memcpy(buf, p->material + i, sizeof *p->material);
  memcpy(buf + sizeof *p->material, p->id + i, sizeof *p->id);
}

long mrn_particles_unpack(mrn_particles *p, const unsigned char *buf) {
  if (p->n == p->cap && mrn_particles_reserve(p, p->cap ? 2 * p->cap : 256) != MRN_OK) return -1;
  const size_t j = p->n++;
  for (int f = 0; f < FIELD_COUNT; f++) {
    const size_t nc = stride_of(p, f);
    memcpy(*field_ptr(p, f) + j * nc, buf, sizeof(double) * nc);
    buf += sizeof(double) * nc;
  }
  if (p->state_stride) memcpy(p->state + j * p->state_stride, buf, sizeof(double) * p->state_stride);
  buf += sizeof(double) * p->state_stride;
  if (p->user_stride) memcpy(p->user + j * p->user_stride, buf, sizeof(double) * p->user_stride);
  buf += sizeof(double) * p->user_stride;
  memcpy(p->material + j, buf, sizeof *p->material);
  memcpy(p->id + j, buf + sizeof *p->material, sizeof *p->id);
  return (long)j;
}

void mrn_particles_compact(mrn_particles *p, const unsigned char *keep) {
  size_t out = 0;
  for (size_t i = 0; i < p->n; i++) {
    if (!keep[i]) continue;
    if (out != i) {
      for (int f = 0; f < FIELD_COUNT; f++) {
        const size_t nc = stride_of(p, f);
        double *data = *field_ptr(p, f);
        memcpy(data + out * nc, data + i * nc, sizeof(double) * nc);
      }
      p->material[out] = p->material[i];
      p->id[out] = p->id[i];
      if (p->state_stride)
        memcpy(p->state + out * p->state_stride, p->state + i * p->state_stride, sizeof(double) * p->state_stride);
      if (p->user_stride)
        memcpy(p->user + out * p->user_stride, p->user + i * p->user_stride, sizeof(double) * p->user_stride);
    }
    out++;
  }
  p->n = out;
}
