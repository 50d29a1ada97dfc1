/* The block drop of examples/block_drop/deck.lua, through moraine's C API
 * alone (doc/c-api.md): a 2D elastic block (plane strain) thrown onto a
 * rough floor falls, lands, bounces and slides, and Coulomb friction
 * (mu = 0.3) takes energy out. It writes what the deck writes, into OUTDIR,
 * and matches the deck's run bit for bit.
 *
 *   cc drop.c -o drop $(pkg-config --cflags --libs moraine)
 *   ./drop OUTDIR [TIME]        (TIME: model time in s, default 1.5; the
 *                                deck's --set time=TIME)
 */
#include <stdio.h>
#include <stdlib.h>

#include <moraine/moraine.h>

/* the block's centre of mass every 0.1 s, printed at the end as the deck does */
typedef struct front {
  double time[64], com_x[64];
  int n;
} front;

static int record_front(void *ctx, mrn_sim *sim) {
  front *f = ctx;
  if (f->n == 64) return 0;
  mrn_diagnostics d;
  mrn_sim_diagnostics(sim, &d);
  f->time[f->n] = sim->time;
  f->com_x[f->n++] = d.com[0];
  return 0;
}

/* mpm.simulation{ dim = 2, grid = ..., gravity = ..., scheme = ..., boundary = ..., dt = ... } */
static mrn_sim *make_simulation(void) {
  mrn_sim_config cfg = {
      .dim = 2,
      .size = {4, 2},
      .cell = 0.05,
      .shape = MRN_SHAPE_QUADRATIC_BSPLINE,
      .kernel_boundary = MRN_KERNEL_EXTENDED,
      .gravity = {0, -9.81},
  };
  mrn_sim *sim = mrn_sim_new(&cfg);
  if (!sim) return NULL;
  /* scheme = { transfer = "FLIP0.99", stress_update = "USF" } */
  mrn_scheme s = sim->scheme;
  s.stress_update = MRN_STRESS_USF;
  if (mrn_scheme_from_preset("FLIP0.99", &s) != MRN_OK || mrn_scheme_validate(&s) != MRN_OK) {
    mrn_sim_free(sim);
    return NULL;
  }
  sim->scheme = s;
  /* boundary = { left = "slip", right = "slip", top = "free", bottom = { "friction", mu = 0.3 } } */
  sim->boundary.face[MRN_FACE_XMIN].kind = MRN_BC_SLIP;
  sim->boundary.face[MRN_FACE_XMAX].kind = MRN_BC_SLIP;
  sim->boundary.face[MRN_FACE_YMAX].kind = MRN_BC_FREE;
  sim->boundary.face[MRN_FACE_YMIN] = (mrn_face_bc){.kind = MRN_BC_FRICTION, .mu = 0.3};
  /* dt = { a_tau = 0.2 } */
  mrn_dt_policy_a_tau(&sim->dt_policy, 0.2);
  return sim;
}

/* sim:add_particles(mpm.box{ min = { 0.3, 0.8 }, max = { 0.9, 1.2 } },
 *                   { material = block, per_axis = 2, velocity = { 3.0, 0 } }) */
static int add_block(mrn_sim *sim) {
  mrn_material *block = mrn_material_new(&mrn_material_linear_elastic);
  if (!block || mrn_material_set(block, "density", 1000) != MRN_OK || mrn_material_set(block, "E", 2e6) != MRN_OK ||
      mrn_material_set(block, "nu", 0.3) != MRN_OK || mrn_material_prepare(block) != MRN_OK) {
    if (block) mrn_material_unref(block);
    return MRN_ERR;
  }
  int index = mrn_sim_add_material(sim, block);
  mrn_material_unref(block); /* the simulation holds its own reference */
  if (index < 0) return MRN_ERR;
  mrn_region *box = mrn_region_box((const double[3]){0.3, 0.8, 0}, (const double[3]){0.9, 1.2, 0});
  if (!box) return MRN_ERR;
  size_t first;
  long count;
  int rc = mrn_sim_seed(sim, box, index, 2, MRN_SEED_GAUSS, &first, &count);
  mrn_region_unref(box);
  if (rc != MRN_OK) return rc;
  for (long i = 0; i < count; i++) sim->particles.v[3 * (first + i)] = 3.0;
  sim->affine_pending = 1; /* the run starts grad v (and APIC's C) from these velocities (000 §3.2) */
  return MRN_OK;
}

/* output = { vtk = "block", every = 0.02 }, thermo = 1000, and the hook; then run{ time = ... } */
static int run(mrn_sim *sim, const char *outdir, double time, front *f) {
  mrn_output out;
  mrn_output_init(&out, outdir);
  int rc = mrn_output_set_vtk(&out, "block", 0.02, 0);
  if (rc == MRN_OK) rc = mrn_output_set_csv(&out, "diagnostics.csv", 10);
  if (rc == MRN_OK) rc = mrn_output_set_series(&out, "diagnostics.h5");
  mrn_hook hook = {.every_time = 0.1, .fn = record_front, .ctx = f};
  mrn_run_observer writers = mrn_output_observer(&out);
  mrn_run_options opt = {.time = time, .thermo_every = 1000, .hooks = &hook, .nhooks = 1,
                         .observers = &writers, .nobservers = 1};
  if (rc == MRN_OK) rc = mrn_run(sim, &opt);
  int closed = mrn_output_free(&out); /* the last rows of the series and the CSV */
  return rc != MRN_OK ? rc : closed;
}

int main(int argc, char **argv) {
  if (argc < 2 || argc > 3) {
    fprintf(stderr, "usage: %s OUTDIR [TIME]\n", argv[0]);
    return 2;
  }
  double time = argc == 3 ? atof(argv[2]) : 1.5;
  front f = {.n = 0};
  mrn_sim *sim = make_simulation();
  int rc = sim ? add_block(sim) : MRN_ERR;
  if (rc == MRN_OK) rc = run(sim, argv[1], time, &f);
  if (rc != MRN_OK) {
    fprintf(stderr, "drop: %s\n", mrn_error_message());
    mrn_sim_free(sim);
    return 1;
  }
  for (int i = 0; i < f.n; i += 5) printf("%.2f s: centre of mass at x = %.3f m\n", f.time[i], f.com_x[i]);
  mrn_diagnostics d;
  mrn_sim_diagnostics(sim, &d);
  printf("block drop: E_total = %.4g J/m, friction work W_friction = %.4g J/m\n", d.total, d.friction);
  mrn_sim_free(sim);
  return 0;
}
