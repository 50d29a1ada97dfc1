/* moraine: transfer properties of 002 §3 and 000 §3.
 *  - one particle, no forces: PIC and FLIP keep v_p and lose grad v (002,
 *    Eq. 44); APIC keeps v_p (002, Eq. 46); TPIC keeps v_p and grad v (002,
 *    Eqs. 49-50);
 *  - many particles in an affine velocity field: APIC and TPIC reproduce it
 *    exactly (velocities and gradients), PIC does not, with every shape
 *    function, also with particles on grid lines and nodes (where the
 *    multilinear kernel's D is singular);
 *  - a lone particle on a node (linear shapes) keeps v and a finite C;
 *  - XPIC(1) gives the PIC velocities to round-off (000, Eq. 40 vs Eq. 31);
 *  - the initial grad v of a rigid rotation is recovered (000 §3.2). */
#include <math.h>
#include <string.h>

#include "check.h"
#include "solver/simulation.h"
#include "transfer/kernels.h"
#include "transfer/xpic.h"

static mrn_material *elastic(void) {
  mrn_material *m = mrn_material_new(&mrn_material_linear_elastic);
  mrn_material_set(m, "density", 1000);
  mrn_material_set(m, "E", 1e6);
  mrn_material_set(m, "nu", 0.3);
  mrn_material_prepare(m);
  return m;
}

static mrn_sim *make_sim(int dim, const char *preset, mrn_shape_kind shape) {
  mrn_sim_config cfg = {.dim = dim, .size = {2, 2, 2}, .cell = 0.25, .shape = shape};
  mrn_sim *sim = mrn_sim_new(&cfg);
  mrn_scheme_from_preset(preset, &sim->scheme);
  return sim;
}

/* the particles' grad v from the last transfer_once, 9 per particle */
static double gradv[9 * 4096];

static long keep_gradient(void *ctx, size_t lo, size_t hi, const double *L) {
  (void)ctx;
  memcpy(gradv + 9 * lo, L, 9 * (hi - lo) * sizeof(double));
  return -1;
}

/* one transfer with no force: P2G, V~ = V, G2P; then grad v from the grid */
static void transfer_once(mrn_sim *sim) {
  mrn_grid *g = &sim->grid;
  mrn_transfer tr = mrn_sim_transfer(sim);
  mrn_p2g(&tr, 1, 0);
  for (size_t i = 0; i < g->n; i++)
    for (int d = 0; d < 3; d++) {
      g->vel[3 * i + d] = g->mass[i] > sim->mass_floor ? g->mom[3 * i + d] / g->mass[i] : 0.0;
      g->vel_new[3 * i + d] = g->vel[3 * i + d];
    }
  if (sim->scheme.velocity_update == MRN_VUPDATE_XPIC) {
    static double scratch[3 * 4096];
    mrn_xpic_smooth(&tr, scratch);
  }
  const mrn_gradient_sink sink = {keep_gradient, NULL, MRN_PHASE_G2P};
  mrn_gradient(&tr, g->vel_new, &sink); /* before the particles move, into gradv */
  static double dx[3 * 4096]; /* the particles stay where they are */
  mrn_g2p(&tr, 1e-3, dx);
}

static void single_particle(const char *preset, int keeps_gradient) {
  mrn_sim *sim = make_sim(2, preset, MRN_SHAPE_QUADRATIC_BSPLINE);
  mrn_material *m = elastic();
  int mi = mrn_sim_add_material(sim, m);
  double x[3] = {1.03, 0.91, 0};
  long p = mrn_particles_add(&sim->particles, x, 1.0, 1e-3, mi);
  mrn_sim_particles_changed(sim);
  const double v0[2] = {0.3, -0.2};
  const double L0[4] = {0.5, -1.0, 2.0, 0.25}; /* d v_a / d x_b */
  sim->particles.v[3 * p] = v0[0];
  sim->particles.v[3 * p + 1] = v0[1];
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2; b++) sim->particles.affine[4 * p + 2 * a + b] = L0[2 * a + b]; /* 2D: in-plane block */
  transfer_once(sim);
  CHECK_CLOSE(sim->particles.v[3 * p], v0[0], 1e-13);
  CHECK_CLOSE(sim->particles.v[3 * p + 1], v0[1], 1e-13);
  double gmax = 0, gerr = 0;
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2; b++) {
      gmax = fmax(gmax, fabs(gradv[9 * p + 3 * a + b]));
      gerr = fmax(gerr, fabs(gradv[9 * p + 3 * a + b] - L0[2 * a + b]));
    }
  if (keeps_gradient) {
    CHECK(gerr < 1e-12); /* (002, Eq. 50) */
  } else if (strcmp(preset, "APIC") != 0) {
    CHECK(gmax < 1e-12); /* (002, Eq. 44): the gradient is lost */
  }
  printf("single particle %-5s: |v - v0| = %.1e, |grad v| = %.3g, |grad v - L0| = %.3g\n", preset,
         fabs(sim->particles.v[3 * p] - v0[0]) + fabs(sim->particles.v[3 * p + 1] - v0[1]), gmax, gerr);
  mrn_material_unref(m);
  mrn_sim_free(sim);
}

/* the larger of err and |d|, infinite when d is not a number */
static double worse(double err, double d) { return isnan(d) ? INFINITY : fmax(err, fabs(d)); }

/* particles filling a block with v = v0 + L x, from `start` every half cell
 * along each axis (start 0.5: every other particle on grid lines, some on
 * nodes): affine transfers keep it exactly */
static double affine_field(int dim, const char *preset, mrn_shape_kind shape, double start) {
  mrn_sim *sim = make_sim(dim, preset, shape);
  mrn_material *m = elastic();
  int mi = mrn_sim_add_material(sim, m);
  double L[3][3] = {{0.1, -0.7, 0.2}, {0.7, 0.05, -0.3}, {0.4, 0.3, -0.15}};
  double v0[3] = {0.2, -0.1, 0.05};
  for (double px = start; px < 1.5; px += 0.125)
    for (double py = start; py < 1.5; py += 0.125)
      for (double pz = dim == 3 ? start : 0; pz < (dim == 3 ? 1.5 : 0.1); pz += 0.125) {
        double x[3] = {px, py, pz};
        long p = mrn_particles_add(&sim->particles, x, 1.0, 1e-3, mi);
        for (int a = 0; a < dim; a++) {
          double v = v0[a];
          for (int b = 0; b < dim; b++) v += L[a][b] * x[b];
          sim->particles.v[3 * p + a] = v;
        }
      }
  mrn_sim_particles_changed(sim);
  mrn_sim_init_affine(sim);
  double err = 0;
  for (int it = 0; it < 3; it++) transfer_once(sim);
  for (size_t p = 0; p < sim->particles.n; p++) {
    const double *x = sim->particles.x + 3 * p;
    for (int a = 0; a < dim; a++) {
      double v = v0[a];
      for (int b = 0; b < dim; b++) v += L[a][b] * x[b];
      err = worse(err, sim->particles.v[3 * p + a] - v);
      for (int b = 0; b < dim; b++)
        err = worse(err, sim->particles.affine[(size_t)mrn_tensor_stride(dim) * p + dim * a + b] - L[a][b]);
    }
  }
  mrn_material_unref(m);
  mrn_sim_free(sim);
  return err;
}

static void xpic1_is_pic(void) {
  mrn_sim *a = make_sim(2, "PIC", MRN_SHAPE_CUBIC_BSPLINE), *b = make_sim(2, "XPIC(1)", MRN_SHAPE_CUBIC_BSPLINE);
  mrn_material *m = elastic();
  mrn_sim *both[2] = {a, b};
  for (int k = 0; k < 2; k++) {
    int mi = mrn_sim_add_material(both[k], m);
    unsigned s = 99;
    for (int i = 0; i < 300; i++) {
      s = s * 1664525u + 1013904223u;
      double x[3] = {0.3 + 1.4 * ((s >> 8) & 1023) / 1023.0, 0.3 + 1.4 * ((s >> 18) & 1023) / 1023.0, 0};
      long p = mrn_particles_add(&both[k]->particles, x, 1.0 + (i % 3), 1e-3, mi);
      both[k]->particles.v[3 * p] = sin(3 * x[0] + x[1]);
      both[k]->particles.v[3 * p + 1] = cos(2 * x[1] - x[0]);
    }
    mrn_sim_particles_changed(both[k]);
    transfer_once(both[k]);
  }
  double err = 0;
  for (size_t p = 0; p < a->particles.n; p++)
    for (int d = 0; d < 2; d++) err = fmax(err, fabs(a->particles.v[3 * p + d] - b->particles.v[3 * p + d]));
  printf("XPIC(1) vs PIC velocities: max difference %.2e\n", err);
  CHECK(err < 1e-14);
  mrn_material_unref(m);
  mrn_sim_free(a);
  mrn_sim_free(b);
}

/* a lone particle exactly on a node, linear shape functions: no node but its
 * own has mass, so no gradient can be told; APIC's C must be finite (B D^-1
 * is 0/0 there), and v is kept */
static void lone_particle_on_node(int dim) {
  mrn_sim *sim = make_sim(dim, "APIC", MRN_SHAPE_LINEAR);
  mrn_material *m = elastic();
  int mi = mrn_sim_add_material(sim, m);
  double x[3] = {1.0, 0.75, dim == 3 ? 1.25 : 0};
  long p = mrn_particles_add(&sim->particles, x, 1.0, 1e-3, mi);
  mrn_sim_particles_changed(sim);
  const size_t ts = (size_t)mrn_tensor_stride(dim);
  for (int a = 0; a < dim; a++) {
    sim->particles.v[3 * p + a] = 0.1 * (a + 1);
    for (int b = 0; b < dim; b++) sim->particles.affine[ts * p + (size_t)(dim * a + b)] = 0.3 * (a - b);
  }
  transfer_once(sim);
  for (int a = 0; a < dim; a++) {
    CHECK_CLOSE(sim->particles.v[3 * p + a], 0.1 * (a + 1), 1e-14);
    for (int b = 0; b < dim; b++) CHECK(isfinite(sim->particles.affine[ts * p + (size_t)(dim * a + b)]));
  }
  mrn_material_unref(m);
  mrn_sim_free(sim);
}

int main(void) {
  single_particle("PIC", 0);
  single_particle("FLIP", 0);
  single_particle("APIC", 0);
  single_particle("TPIC", 1);
  for (int dim = 2; dim <= 3; dim++) {
    for (int shape = 0; shape < MRN_SHAPE_KIND_COUNT; shape++)
      for (double start = 0.5; start < 0.6 && mrn_shape_takes_dim(shape, dim); start += 0.05) {
        double e_apic = affine_field(dim, "APIC", shape, start), e_tpic = affine_field(dim, "TPIC", shape, start);
        double e_pic = affine_field(dim, "PIC", shape, start);
        printf("%dD %-17s from %.2f affine field: APIC error %.2e, TPIC error %.2e, PIC error %.2e\n", dim,
               mrn_shape_info_of(shape)->name, start, e_apic, e_tpic, e_pic);
        CHECK(e_apic < 1e-12);
        CHECK(e_tpic < 1e-12);
        CHECK(e_pic > 1e-3);
      }
    lone_particle_on_node(dim);
  }
  xpic1_is_pic();
  CHECK_DONE();
}
