#include "particles/domain.h"

#include <string.h>

#include "core/tensor.h"

int mrn_particle_domain_offset(const mrn_particles *ps) {
  const mrn_user_field *u = mrn_particles_user_field(ps, MRN_DOMAIN_FIELD);
  return u && u->ncomp == 9 ? u->offset : -1;
}

void mrn_particle_domain_now(const mrn_particles *ps, int dim, size_t i, const double *frozen, double A[9]) {
  if (frozen) {
    memcpy(A, frozen + 9 * i, 9 * sizeof(double));
    return;
  }
  double U0[9];
  mrn_particle_domain(ps, dim, i, mrn_particle_domain_offset(ps), mrn_particle_half_side(ps->vol0[i], dim), U0, A);
}

void mrn_particle_domain(const mrn_particles *ps, int dim, size_t i, int offset, double r, double U0[9], double A[9]) {
  int set = 0;
  memset(U0, 0, 9 * sizeof(double));
  if (offset >= 0) {
    memcpy(U0, ps->user + i * (size_t)ps->user_stride + (size_t)offset, 9 * sizeof(double));
    for (int k = 0; k < 9; k++) set |= U0[k] != 0.0;
  }
  if (!set) /* never split: the square (cube, sphere) of half-width r */
    for (int a = 0; a < dim; a++) U0[4 * a] = r;
  double F[9];
  mrn_tensor_expand(dim, ps->F + (size_t)mrn_tensor_stride(dim) * i, 1.0, F);
  if (dim == 2) F[8] = 0.0; /* the in-plane block only */
  mat_mul(F, U0, A);
}
