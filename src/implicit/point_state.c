/* moraine: the implicit integrator's per-point history kept in particle
 * fields, so that checkpoints hold it and a run restarted from one goes on
 * exactly as the run that wrote it.
 *
 * The energy-consistent stress of a step (emc_stress.h) needs, besides F_t,
 * the start-of-step elastic left Cauchy-Green tensor b_e, Kirchhoff stress
 * tau, stored energy psi and hardening variable xi. F_t is the particle field
 * F and the accumulated dissipation is minus the field w_plastic; the other
 * four live in registered particle fields (particles.h), which checkpoints
 * save and restore and outputs write like any other:
 *   implicit_be   9  b_e, row-major (dimensionless)
 *   implicit_tau  9  Kirchhoff stress tau = J sigma, row-major (Pa)
 *   implicit_psi  1  stored energy per reference volume, psi (J/m^3)
 *   implicit_xi   1  equivalent plastic strain xi (dimensionless)
 * b_e all zero marks a point without history yet (fields just registered):
 * it starts from b_e = F F^T, xi = 0. */
#include <string.h>

#include "core/error.h"
#include "implicit/implicit_internal.h"

static const struct {
  const char *name;
  int ncomp;
  const char *unit;
} fields[4] = {{"implicit_be", 9, ""}, {"implicit_tau", 9, "Pa"}, {"implicit_psi", 1, "J/m^3"}, {"implicit_xi", 1, ""}};

/* the four fields in f, registered if absent; 0, or an error (message set) */
static int find_fields(mrn_particles *ps, const mrn_user_field *f[4]) {
  for (int i = 0; i < 4; i++) {
    f[i] = mrn_particles_user_field(ps, fields[i].name);
    if (!f[i]) {
      if (mrn_particles_add_user_field(ps, fields[i].name, fields[i].ncomp, 0.0, fields[i].unit)) return MRN_ERR;
      f[i] = mrn_particles_user_field(ps, fields[i].name);
    }
    if (f[i]->ncomp != fields[i].ncomp)
      return mrn_error_code(MRN_ERR, "implicit: particle field '%s' has %d components; the implicit integrator keeps "
                                     "its point history there and needs %d",
                            fields[i].name, f[i]->ncomp, fields[i].ncomp);
  }
  return 0;
}

int mrn_implicit_state_load(mrn_implicit *im) {
  mrn_particles *ps = &im->sim->particles;
  const mrn_user_field *f[4];
  int rc = find_fields(ps, f);
  if (rc) return rc;
  for (size_t p = 0; p < im->np; p++) {
    mrn_emc_state *s = &im->st[p];
    const double *rec = ps->user + p * (size_t)ps->user_stride;
    double F[9];
    mrn_tensor_expand(ps->dim, ps->F + (size_t)mrn_tensor_stride(ps->dim) * p, 1.0, F);
    const double *be = rec + f[0]->offset;
    int fresh = 1;
    for (int k = 0; k < 9; k++) fresh &= be[k] == 0.0;
    memcpy(s->Ft, F, sizeof s->Ft);
    if (fresh) {
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++)
          s->be[3 * a + c] = F[3 * a] * F[3 * c] + F[3 * a + 1] * F[3 * c + 1] + F[3 * a + 2] * F[3 * c + 2];
      mrn_emc_hencky(&im->mat[ps->material[p]], s->be, s->tau, &s->psi);
      s->xi = 0.0;
    } else {
      memcpy(s->be, be, sizeof s->be);
      memcpy(s->tau, rec + f[1]->offset, sizeof s->tau);
      s->psi = rec[f[2]->offset];
      s->xi = rec[f[3]->offset];
    }
    im->diss[p] = -ps->w_plastic[p];
  }
  mrn_implicit_state_store(im);
  return 0;
}

void mrn_implicit_state_store(mrn_implicit *im) {
  mrn_particles *ps = &im->sim->particles;
  const mrn_user_field *f[4];
  for (int i = 0; i < 4; i++) f[i] = mrn_particles_user_field(ps, fields[i].name);
  if (!f[0] || !f[1] || !f[2] || !f[3]) return; /* made by mrn_implicit_state_load, which the integrator ran */
  for (size_t p = 0; p < im->np; p++) {
    const mrn_emc_state *s = &im->st[p];
    double *rec = ps->user + p * (size_t)ps->user_stride;
    memcpy(rec + f[0]->offset, s->be, sizeof s->be);
    memcpy(rec + f[1]->offset, s->tau, sizeof s->tau);
    rec[f[2]->offset] = s->psi;
    rec[f[3]->offset] = s->xi;
  }
}
