/* moraine: the elastic cantilever of 001 §7.1 (analysis A geometry and
 * material) in free vibration, run with the implicit energy-momentum
 * consistent integrator (dt = 0.6264 s, consistent mass, FLIP, defaults) and with the
 * explicit one (FLIP, USF, particle CFL step), side by side: wall time,
 * energy drift and the period. Both start from the same state: at rest in the
 * reference shape with the velocity of the first bending mode,
 * v_y = V phi_1(x) / phi_1(L), phi_1 = cosh bx - cos bx - s (sinh bx - sin bx),
 * b L = 1.8751, s = 0.7341. The loaded run of both integrators is
 * tests/decks/implicit_cantilever.lua beside tests/decks/explicit_cantilever.lua.
 * Build: cmake --build BUILD --target implicit_cantilever_bench;
 * run: BUILD/moraine-implicit-cantilever [t_end [courant [explicit_only]]].
 * Figures: doc/implicit.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "core/error.h"
#include "implicit/implicit.h"
#include "particles/region.h"
#include "solver/simulation.h"

static const double E = 1e9, NU = 0.2, RHO = 7750e3, L = 10.0;

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static mrn_sim *build(size_t *tip) {
  mrn_sim_config cfg = {.dim = 2, .origin = {-1, 0, 0}, .size = {12, 20, 0}, .cell = 0.5, .shape = MRN_SHAPE_GIMP};
  mrn_sim *sim = mrn_sim_new(&cfg);
  mrn_material *m = mrn_material_new(mrn_material_type_find("hencky"));
  if (!sim || !m || mrn_material_set(m, "density", RHO) || mrn_material_set(m, "E", E) ||
      mrn_material_set(m, "nu", NU) || mrn_material_prepare(m))
    return NULL;
  int mi = mrn_sim_add_material(sim, m);
  mrn_material_unref(m);
  double lo[3] = {0, 9.5, 0}, hi[3] = {L, 10.5, 0};
  mrn_region *beam = mrn_region_box(lo, hi);
  size_t first;
  long count;
  if (mrn_sim_seed(sim, beam, mi, 8, MRN_SEED_REGULAR, &first, &count)) return NULL;
  mrn_region_unref(beam);
  double clo[3] = {-1.01, -1, 0}, chi[3] = {0.01, 21, 0}, zero[3] = {0, 0, 0};
  mrn_region *clamp = mrn_region_box(clo, chi);
  if (mrn_sim_add_constraint(sim, clamp, 3u, zero) < 0) return NULL;
  mrn_region_unref(clamp);
  double best = HUGE_VAL;
  for (size_t p = 0; p < sim->particles.n; p++) {
    const double *x = sim->particles.x + 3 * p;
    double d = (x[0] - L) * (x[0] - L) + (x[1] - 10) * (x[1] - 10);
    if (d < best) best = d, *tip = p;
  }
  /* first-mode velocity, tip speed V = 0.12 m/s (about a 1 m tip amplitude) */
  const double b = 1.8751 / L, sg = 0.7341, V = 0.12;
  double phiL = cosh(b * L) - cos(b * L) - sg * (sinh(b * L) - sin(b * L));
  for (size_t p = 0; p < sim->particles.n; p++) {
    double x = sim->particles.x[3 * p];
    sim->particles.v[3 * p + 1] = V * (cosh(b * x) - cos(b * x) - sg * (sinh(b * x) - sin(b * x))) / phiL;
  }
  return sim;
}


typedef struct {
  double wall, eref, drift, period;
  double failed; /* time at which the run stopped with an error, 0 if none */
  long steps;
} result;

/* energy drift after release and the period from the tip-deflection crossings */
static void track(result *r, double t, double e, double y, double *prev_t, double *prev_y, double *cross, int *nc) {
  if (r->eref == 0.0) r->eref = e;
  r->drift = fmax(r->drift, fabs(e - r->eref) / r->eref);
  if (*nc >= 0 && *prev_y * y < 0) cross[(*nc)++ % 64] = *prev_t + (t - *prev_t) * *prev_y / (*prev_y - y);
  if (*nc < 0) *nc = 0;
  *prev_t = t, *prev_y = y;
}

static int run(int implicit, double tend, double courant, result *r) {
  size_t tip = 0;
  mrn_sim *sim = build(&tip);
  if (!sim) return fprintf(stderr, "setup failed: %s\n", mrn_error_message()), 1;
  const double yrest = sim->particles.x[3 * tip + 1];
  double cross[64], prev_t = 0, prev_y = 0;
  int nc = -1;
  *r = (result){0};
  mrn_implicit *im = NULL;
  if (implicit) {
    mrn_implicit_options o;
    mrn_implicit_options_default(&o);
    o.dt = 0.6264;
    im = mrn_implicit_new(sim, &o);
  } else {
    mrn_scheme_from_preset("FLIP", &sim->scheme);
    sim->scheme.stress_update = MRN_STRESS_USF;
    mrn_dt_policy_cfl(&sim->dt_policy, MRN_DT_CFL, courant);
  }
  double t0 = now();
  while (sim->time < tend - 1e-9) {
    double e;
    if (implicit) {
      if (mrn_implicit_step(im, NULL)) return fprintf(stderr, "implicit: %s\n", mrn_error_message()), 1;
      mrn_implicit_energy en;
      mrn_implicit_energies(im, &en);
      e = en.kinetic + en.strain;
    } else {
      double dt;
      if (mrn_dt_compute(sim, &dt)) return 1;
      if (mrn_sim_step_dt(sim, dt)) {
        fprintf(stderr, "explicit: %s\n", mrn_error_message());
        r->failed = sim->time;
        break;
      }
      mrn_diagnostics d;
      mrn_sim_diagnostics(sim, &d);
      e = d.kinetic + d.elastic;
    }
    r->steps++;
    track(r, sim->time, e, sim->particles.x[3 * tip + 1] - yrest, &prev_t, &prev_y, cross, &nc);
  }
  r->wall = now() - t0;
  r->period = nc >= 3 ? 2.0 * (cross[(nc - 1) % 64] - cross[0]) / (nc - 1) : NAN;
  mrn_implicit_free(im);
  mrn_sim_free(sim);
  return 0;
}

int main(int argc, char **argv) {
  double tend = argc > 1 ? atof(argv[1]) : 125.0;
  double courant = argc > 2 ? atof(argv[2]) : 0.5;
  int only_explicit = argc > 3 && atoi(argv[3]);
  double Ep = E / (1 - NU * NU), f1 = 1.8751 * 1.8751 / (2 * M_PI) * sqrt(Ep / 12.0 / (RHO * L * L * L * L));
  printf("first mode: period %.4f s\n", 1 / f1);
  for (int implicit = !only_explicit; implicit >= 0; implicit--) {
    result r;
    if (run(implicit, tend, courant, &r)) return 1;
    printf("%-8s steps %6ld  wall %7.2f s  energy %.6g J/m  drift %.3e  period %.4f s (%+.2f %%)",
           implicit ? "implicit" : "explicit", r.steps, r.wall, r.eref, r.drift, r.period, 100 * (r.period * f1 - 1));
    if (r.failed > 0) printf("  STOPPED at t = %.2f s", r.failed);
    printf("\n");
    fflush(stdout);
  }
  return 0;
}
