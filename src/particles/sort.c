#include "particles/sort.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/parallel.h"

/* one component (`width` bytes at `offset` within a record of `record` bytes)
 * gathered into scratch in the new order, then written back */
static void permute_component(char *data, size_t record, size_t offset, size_t width, const uint32_t *order, size_t n,
                              char *scratch) {
  const long count = (long)n;
#pragma omp parallel for schedule(static) if (count > MRN_OMP_MIN_ITEMS)
  for (long i = 0; i < count; i++) memcpy(scratch + (size_t)i * width, data + order[i] * record + offset, width);
#pragma omp parallel for schedule(static) if (count > MRN_OMP_MIN_ITEMS)
  for (long i = 0; i < count; i++) memcpy(data + (size_t)i * record + offset, scratch + (size_t)i * width, width);
}

int mrn_particles_permute(mrn_particles *p, const uint32_t *order) {
  const size_t n = p->n;
  if (n == 0) return MRN_OK;
  char *scratch = malloc(n * sizeof(double));
  if (!scratch) return mrn_error("particles: out of memory reordering %zu particles", n);
  for (int f = 0; f < mrn_particle_field_count(); f++) {
    const mrn_particle_field_info *info = mrn_particle_field_at(f);
    char *data = (char *)mrn_particle_field_data(p, info);
    const int stored = mrn_particle_field_stride(p, info);
    const size_t record = sizeof(double) * (size_t)stored;
    for (int k = 0; k < stored; k++)
      permute_component(data, record, sizeof(double) * (size_t)k, sizeof(double), order, n, scratch);
  }
  permute_component((char *)p->material, sizeof *p->material, 0, sizeof *p->material, order, n, scratch);
  permute_component((char *)p->id, sizeof *p->id, 0, sizeof *p->id, order, n, scratch);
  const size_t stride = (size_t)p->state_stride;
  for (size_t k = 0; k < stride; k++)
    permute_component((char *)p->state, sizeof(double) * stride, sizeof(double) * k, sizeof(double), order, n,
                      scratch);
  const size_t ustride = (size_t)p->user_stride;
  for (size_t k = 0; k < ustride; k++)
    permute_component((char *)p->user, sizeof(double) * ustride, sizeof(double) * k, sizeof(double), order, n,
                      scratch);
  free(scratch);
  return MRN_OK;
}
