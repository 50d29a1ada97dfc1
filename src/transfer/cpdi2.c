/* moraine: CPDI2 in 2D (see cpdi2.h). */
#include "transfer/cpdi2.h"

#include <math.h>
#include <string.h>

#include "core/error.h"
#include "core/parallel.h"
#include "particles/domain.h"
#include "transfer/cpdi.h"

const double mrn_cpdi2_xi[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};

static double cross(const double u[2], const double v[2]) { return u[0] * v[1] - u[1] * v[0]; }

double mrn_cpdi2_integrals(const double q[4][2], double w[4], double g[4][2]) {
  double a[2] = {0, 0}, b[2] = {0, 0}, e[2] = {0, 0};
  for (int c = 0; c < 4; c++)
    for (int d = 0; d < 2; d++) {
      a[d] += 0.25 * mrn_cpdi2_xi[c][0] * q[c][d];
      b[d] += 0.25 * mrn_cpdi2_xi[c][1] * q[c][d];
      e[d] += 0.25 * mrn_cpdi2_xi[c][0] * mrn_cpdi2_xi[c][1] * q[c][d];
    }
  const double J0 = cross(a, b), J1 = cross(a, e), J2 = cross(e, b); /* det J = J0 + J1 xi + J2 eta */
  for (int c = 0; c < 4; c++) {
    const int next = (c + 1) % 4, prev = (c + 3) % 4;
    w[c] = J0 + (J1 * mrn_cpdi2_xi[c][0] + J2 * mrn_cpdi2_xi[c][1]) / 3.0;
    g[c][0] = 0.5 * (q[next][1] - q[prev][1]);
    g[c][1] = 0.5 * (q[prev][0] - q[next][0]);
  }
  return 4.0 * J0;
}

/* where the corners sit in a particle's record of ps->user, or -1 */
static int field_offset(const mrn_particles *ps) {
  const mrn_user_field *u = mrn_particles_user_field(ps, MRN_CPDI2_FIELD);
  return u && u->ncomp == 8 ? u->offset : -1;
}

/* CPDI1's parallelogram A xi_c, A = F U0 */
static void parallelogram(const mrn_particles *ps, size_t p, double off[4][2]) {
  double U0[9], A[9];
  mrn_particle_domain(ps, 2, p, mrn_particle_domain_offset(ps), mrn_particle_half_side(ps->vol0[p], 2), U0, A);
  for (int c = 0; c < 4; c++)
    for (int a = 0; a < 2; a++) off[c][a] = A[3 * a] * mrn_cpdi2_xi[c][0] + A[3 * a + 1] * mrn_cpdi2_xi[c][1];
}

/* the stored offsets of particle p (field at `offset`) into off; 0 when unset */
static int stored(const mrn_particles *ps, size_t p, int offset, double off[4][2]) {
  if (offset < 0) return 0;
  const double *u = ps->user + p * (size_t)ps->user_stride + (size_t)offset;
  int set = 0;
  for (int k = 0; k < 8; k++) set |= u[k] != 0.0;
  if (set) memcpy(off, u, 8 * sizeof(double));
  return set;
}

void mrn_cpdi2_offsets(const mrn_particles *ps, size_t p, double off[4][2]) {
  if (!stored(ps, p, field_offset(ps), off)) parallelogram(ps, p, off);
}

int mrn_cpdi2_begin(mrn_particles *ps, double inv_cell, double *corners, double *reach) {
  int offset = field_offset(ps);
  if (offset < 0) {
    if (mrn_particles_user_field(ps, MRN_CPDI2_FIELD))
      return mrn_error("shape = 'cpdi2': the particle field '%s' exists without its 8 components: the name is "
                       "CPDI2's", MRN_CPDI2_FIELD);
    if (mrn_particles_add_user_field(ps, MRN_CPDI2_FIELD, 8, 0.0, "m") != MRN_OK) return MRN_ERR;
    offset = field_offset(ps);
  }
  double most = 0.0;
  for (size_t p = 0; p < ps->n; p++) {
    double off[4][2];
    if (!stored(ps, p, offset, off)) { /* a new particle: CPDI1's parallelogram */
      parallelogram(ps, p, off);
      memcpy(ps->user + p * (size_t)ps->user_stride + (size_t)offset, off, sizeof off);
    }
    for (int c = 0; c < 4; c++)
      for (int a = 0; a < 2; a++) {
        corners[8 * p + 2 * c + a] = ps->x[3 * p + a] + off[c][a];
        most = fmax(most, fabs(off[c][a]));
      }
  }
  *reach = most * inv_cell;
  return MRN_OK;
}

/* particle p's corners moved by dt times the velocity at each, and the new
 * offsets about the moved quadrilateral's centroid sum_c w_c x_c / V_p
 * (int x dx = sum_c w_c x_c, since x = sum_c M_c x_c), into off */
static void move_quad(const mrn_transfer *t, const double *frozen, double dt, double off[4][2]) {
  double mean[2] = {0, 0}; /* the positions about the corners' mean, for the round-off */
  for (int c = 0; c < 4; c++)
    for (int a = 0; a < 2; a++) mean[a] += 0.25 * frozen[2 * c + a];
  for (int c = 0; c < 4; c++) {
    const double xc[3] = {frozen[2 * c], frozen[2 * c + 1], 0.0};
    double v[3];
    mrn_cpdi_point_velocity(t, xc, t->grid->vel_new, v);
    for (int a = 0; a < 2; a++) off[c][a] = xc[a] - mean[a] + dt * v[a];
  }
  double w[4], g[4][2], centroid[2] = {0, 0};
  const double V = mrn_cpdi2_integrals(off, w, g);
  for (int c = 0; c < 4; c++)
    for (int a = 0; a < 2; a++) centroid[a] += w[c] * off[c][a] / V;
  for (int c = 0; c < 4; c++)
    for (int a = 0; a < 2; a++) off[c][a] -= centroid[a];
}

void mrn_cpdi2_move_corners(const mrn_transfer *t, const double *corners, double dt) {
  mrn_particles *ps = t->particles;
  const int offset = field_offset(ps);
  const long n = (long)ps->n;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    double off[4][2];
    move_quad(t, corners + 8 * p, dt, off);
    memcpy(ps->user + (size_t)p * (size_t)ps->user_stride + (size_t)offset, off, sizeof off);
  }
}
