/* moraine: HDF5 checkpoints.
 *
 *  - restart: N steps, save, load, N more steps gives particle state
 *    bitwise identical to 2N steps straight (2D FLIP + USF, 2D PIC + USL
 *    with a friction floor, 3D MUSL with linear shapes);
 *  - the loaded simulation has every setting of the saved one;
 *  - bad files: missing, empty, truncated, foreign HDF5, and a series of
 *    damaged checkpoints (wrong shape, type, kind names, values) are refused
 *    with a message naming the file and the problem; an import that fails
 *    leaves the target simulation as it was;
 *  - checksums: one damaged byte anywhere in a checkpoint (every k-th byte
 *    and a byte of every dataset) is refused, naming the dataset or the part
 *    of the file; refusing leaks nothing, load after load; a file of format
 *    version 1 (no checksums) still loads, with a warning;
 *  - import onto a 6x wider grid keeps positions and stresses exactly. */
#include <hdf5.h>
#include <malloc.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "testfs.h"
#include "core/error.h"
#include "core/warn.h"
#include "io/checkpoint.h"
#include "solver/simulation.h"

static char tmpdir[40];

static char *tmp_path(const char *name) {
  static char buf[8][320];
  static int next = 0;
  char *p = buf[next++ % 8];
  snprintf(p, sizeof buf[0], "%s/%s", tmpdir, name);
  return p;
}

/* the message must start with the quoted file name and contain `part` */
static int message_says(const char *path, const char *part) {
  char prefix[300];
  snprintf(prefix, sizeof prefix, "'%s': ", path);
  const char *msg = mrn_error_message();
  int ok = strncmp(msg, prefix, strlen(prefix)) == 0 && strstr(msg, part) != NULL;
  if (!ok) fprintf(stderr, "  unexpected message: %s\n  (wanted '%s' and \"%s\")\n", msg, prefix, part);
  return ok;
}

/* ---- building simulations ----------------------------------------------- */

static mrn_material *material(const mrn_material_type *type, double E) {
  mrn_material *m = mrn_material_new(type);
  CHECK(mrn_material_set(m, "density", 2000) == MRN_OK);
  CHECK(mrn_material_set(m, "E", E) == MRN_OK);
  CHECK(mrn_material_set(m, "nu", 0.3) == MRN_OK);
  if (type == &mrn_material_mohr_coulomb) {
    /* weak enough to yield under its own weight: history variables in play */
    CHECK(mrn_material_set(m, "phi", 20) == MRN_OK);
    CHECK(mrn_material_set(m, "cohesion", 50) == MRN_OK);
  }
  CHECK(mrn_material_prepare(m) == MRN_OK);
  return m;
}

static mrn_material *elastic(double E) { return material(&mrn_material_linear_elastic, E); }

typedef struct case_def {
  const char *label;
  int dim;
  mrn_shape_kind shape;
  const char *preset;
  mrn_stress_update_kind stress;
  mrn_bc_kind floor;
  const mrn_material_type *type; /* NULL: linear elastic */
  double damping;                /* Cundall's D; > 0 also switches to the particle CFL policy */
} case_def;

/* a block resting on the floor of a box, sliding sideways under gravity */
static mrn_sim *make_sim(const case_def *c) {
  mrn_sim_config cfg = {.dim = c->dim, .origin = {0, 0, 0}, .size = {1, 1, 1}, .cell = 0.1, .shape = c->shape,
                        .gravity = {0, -9.81, 0}};
  if (c->dim == 3) cfg.size[0] = cfg.size[1] = cfg.size[2] = 0.5;
  mrn_sim *sim = mrn_sim_new(&cfg);
  CHECK(sim != NULL);
  mrn_material *m = material(c->type ? c->type : &mrn_material_linear_elastic, 1e6);
  int mi = mrn_sim_add_material(sim, m);
  mrn_material_unref(m);
  double hi = c->dim == 3 ? 0.3 : 0.6;
  double zlo = c->dim == 3 ? 0.1 : 0, zhi = c->dim == 3 ? 0.3 : 0;
  mrn_region *box = mrn_region_box((double[3]){0.1, 0.0, zlo}, (double[3]){hi, hi - 0.1, zhi});
  size_t first;
  long count;
  if (mrn_sim_seed(sim, box, mi, 2, MRN_SEED_GAUSS, &first, &count) != MRN_OK) {
    fprintf(stderr, "seeding failed: %s\n", mrn_error_message());
    CHECK(0);
  }
  mrn_region_unref(box);
  for (size_t p = 0; p < sim->particles.n; p++) sim->particles.v[3 * p] = 0.4;
  for (int f = 0; f < 2 * c->dim; f++) sim->boundary.face[f].kind = MRN_BC_SLIP;
  sim->boundary.face[MRN_FACE_YMIN].kind = c->floor;
  sim->boundary.face[MRN_FACE_YMIN].mu = c->floor == MRN_BC_FRICTION ? 0.3 : 0.0;
  /* "FLIP/particles": the preset, and where FLIP's increment takes the holds of V */
  char preset[32];
  snprintf(preset, sizeof preset, "%s", c->preset);
  char *holds = strchr(preset, '/');
  if (holds) *holds++ = '\0';
  CHECK(mrn_scheme_from_preset(preset, &sim->scheme) == MRN_OK);
  sim->scheme.stress_update = c->stress;
  if (holds) sim->scheme.holds = (mrn_holds_kind)mrn_name_index(mrn_holds_names(), holds);
  mrn_dt_policy_fixed(&sim->dt_policy, 4e-4);
  if (c->damping > 0) {
    sim->damping_cundall = c->damping;
    sim->damping_viscous = 0.5;
    mrn_dt_policy_cfl(&sim->dt_policy, MRN_DT_CFL, 0.4);
    mrn_sim_energy_balance_start(sim); /* W_MPM from here on */
  } else {
    sim->dt_policy.max = 1e-3;
  }
  return sim;
}

static int run(mrn_sim *sim, int steps) {
  for (int i = 0; i < steps; i++) {
    int rc = mrn_sim_step(sim);
    if (rc) {
      fprintf(stderr, "step failed: %s\n", mrn_error_message());
      return rc;
    }
  }
  return MRN_OK;
}

/* ---- comparing simulations ---------------------------------------------- */

static int same_bits(const void *a, const void *b, size_t bytes) { return bytes == 0 || memcmp(a, b, bytes) == 0; }

/* every particle field, index, id and history variable, bit for bit */
static int same_particles(const mrn_particles *a, const mrn_particles *b) {
  if (a->n != b->n || a->next_id != b->next_id || a->state_stride != b->state_stride) return 0;
  for (int i = 0; i < mrn_particle_field_count(); i++) {
    const mrn_particle_field_info *f = mrn_particle_field_at(i);
    if (!same_bits(mrn_particle_field_data(a, f), mrn_particle_field_data(b, f), a->n * (size_t)mrn_particle_field_stride(a, f) * sizeof(double))) {
      fprintf(stderr, "  particle field %s differs\n", f->name);
      return 0;
    }
  }
  return same_bits(a->material, b->material, a->n * sizeof *a->material) &&
         same_bits(a->id, b->id, a->n * sizeof *a->id) &&
         same_bits(a->state, b->state, a->n * (size_t)a->state_stride * sizeof(double));
}

static int same_clock(const mrn_sim *a, const mrn_sim *b) {
  return a->step == b->step && same_bits(&a->time, &b->time, sizeof a->time) &&
         same_bits(&a->dt, &b->dt, sizeof a->dt) && same_bits(&a->work_friction, &b->work_friction, sizeof(double)) &&
         same_bits(&a->mass_floor, &b->mass_floor, sizeof(double));
}

static void check_same_settings(const mrn_sim *a, const mrn_sim *b) {
  CHECK(a->dim == b->dim && a->shape == b->shape);
  CHECK(same_bits(a->grid.origin, b->grid.origin, sizeof a->grid.origin));
  CHECK(same_bits(a->grid.size, b->grid.size, sizeof a->grid.size));
  CHECK(a->grid.cell == b->grid.cell && a->grid.n == b->grid.n);
  CHECK(same_bits(a->grid.ncell, b->grid.ncell, sizeof a->grid.ncell));
  CHECK(same_bits(a->gravity, b->gravity, sizeof a->gravity));
  CHECK(a->scheme.grid_velocity == b->scheme.grid_velocity);
  CHECK(a->scheme.velocity_update == b->scheme.velocity_update);
  CHECK(a->scheme.position_update == b->scheme.position_update);
  CHECK(a->scheme.stress_update == b->scheme.stress_update);
  CHECK(a->scheme.holds == b->scheme.holds);
  CHECK(same_bits(&a->scheme.flip_fraction, &b->scheme.flip_fraction, sizeof(double)));
  CHECK(strcmp(a->scheme.name, b->scheme.name) == 0);
  for (int f = 0; f < MRN_FACE_COUNT; f++)
    CHECK(a->boundary.face[f].kind == b->boundary.face[f].kind && a->boundary.face[f].mu == b->boundary.face[f].mu);
  CHECK(a->dt_policy.kind == b->dt_policy.kind && a->dt_policy.value == b->dt_policy.value);
  CHECK(a->dt_policy.min == b->dt_policy.min && a->dt_policy.max == b->dt_policy.max);
  CHECK(a->nmaterials == b->nmaterials);
  for (int i = 0; i < a->nmaterials && i < b->nmaterials; i++) {
    const mrn_material *ma = a->materials[i], *mb = b->materials[i];
    CHECK(ma->type == mb->type && strcmp(ma->name, mb->name) == 0);
    CHECK(same_bits(ma->param, mb->param, sizeof ma->param));
    CHECK(same_bits(ma->derived, mb->derived, sizeof ma->derived));
  }
}

/* ---- restart ------------------------------------------------------------- */

static void test_restart(const case_def *c, int steps) {
  mrn_sim *a = make_sim(c);
  CHECK(run(a, steps) == MRN_OK);
  char name[64];
  snprintf(name, sizeof name, "restart_%s.h5", c->label);
  const char *path = tmp_path(name);
  CHECK(mrn_checkpoint_save(a, path) == MRN_OK);
  mrn_sim *b = mrn_checkpoint_load(path);
  CHECK(b != NULL);
  if (!b) {
    fprintf(stderr, "  load failed: %s\n", mrn_error_message());
    mrn_sim_free(a);
    return;
  }
  check_same_settings(a, b);
  CHECK(same_particles(&a->particles, &b->particles));
  CHECK(same_clock(a, b));
  /* a keeps going: it is the straight 2N-step run */
  CHECK(run(a, steps) == MRN_OK);
  CHECK(run(b, steps) == MRN_OK);
  int identical = same_particles(&a->particles, &b->particles) && same_clock(a, b);
  CHECK(identical);
  mrn_diagnostics da, db;
  mrn_sim_diagnostics(a, &da);
  mrn_sim_diagnostics(b, &db);
  CHECK(same_bits(&da, &db, sizeof da));
  CHECK(same_bits(&a->work_damping, &b->work_damping, sizeof(double)));
  double eps_p = 0; /* the history variables are exercised when plasticity happened */
  for (size_t p = 0; p < a->particles.n && a->particles.state_stride; p++)
    eps_p += fabs(a->particles.state[p * (size_t)a->particles.state_stride]);
  printf("restart %-10s %zu particles, %ld + %d steps, t = %.4f s, E_k = %.4g J, W_frict = %.4g J, "
         "W_damp = %.4g J, sum |state[0]| = %.3g: %s\n",
         c->label, a->particles.n, a->step - steps, steps, a->time, da.kinetic, da.friction, a->work_damping, eps_p,
         identical ? "bitwise identical" : "DIFFERENT");
  mrn_sim_free(a);
  mrn_sim_free(b);
}

/* an empty simulation (no material, no particle) survives a round trip */
static void test_empty(void) {
  mrn_sim_config cfg = {.dim = 3, .origin = {-1, 2, 3}, .size = {1, 2, 3}, .cell = 0.5, .shape = MRN_SHAPE_LINEAR};
  mrn_sim *a = mrn_sim_new(&cfg);
  const char *path = tmp_path("empty.h5");
  CHECK(mrn_checkpoint_save(a, path) == MRN_OK);
  mrn_sim *b = mrn_checkpoint_load(path);
  CHECK(b != NULL);
  if (b) {
    check_same_settings(a, b);
    CHECK(same_particles(&a->particles, &b->particles));
  }
  mrn_sim_free(a);
  mrn_sim_free(b);
}

/* ---- time-step function ---------------------------------------------------- */

static int half_ms(void *ctx, mrn_sim *sim, double *dt) {
  *dt = 5e-4;
  return 0;
}

static void test_dt_function(void) {
  case_def c = {"function", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_SLIP, NULL, 0};
  mrn_sim *a = make_sim(&c);
  a->dt_policy.kind = MRN_DT_CALLBACK;
  a->dt_policy.callback = half_ms;
  CHECK(run(a, 3) == MRN_OK);
  const char *path = tmp_path("function.h5");
  CHECK(mrn_checkpoint_save(a, path) == MRN_OK);
  mrn_checkpoint_info info;
  mrn_sim *b = mrn_checkpoint_load_info(path, &info);
  CHECK(b != NULL);
  if (b) {
    CHECK(info.dt_function_dropped == 1);
    CHECK(strstr(info.note, "function") != NULL);
    CHECK(b->dt_policy.kind == MRN_DT_FIXED && b->dt_policy.value == 5e-4);
    CHECK(info.version == MRN_CHECKPOINT_VERSION && info.particles == (long)a->particles.n);
    CHECK(strncmp(info.moraine_version, MORAINE_VERSION, strlen(MORAINE_VERSION)) == 0);
    CHECK(run(a, 3) == MRN_OK && run(b, 3) == MRN_OK);
    CHECK(same_particles(&a->particles, &b->particles));
    printf("function dt: %s\n", info.note);
  }
  mrn_sim_free(a);
  mrn_sim_free(b);
}

/* ---- damaged files ------------------------------------------------------------ */

static void copy_file(const char *from, const char *to) {
  FILE *in = fopen(from, "rb"), *out = fopen(to, "wb");
  CHECK(in && out);
  char buf[65536];
  size_t got;
  while (in && out && (got = fread(buf, 1, sizeof buf, in)) > 0) CHECK(fwrite(buf, 1, got, out) == got);
  if (in) fclose(in);
  if (out) fclose(out);
}

/* a 2D checkpoint to damage */
static const char *sample_checkpoint(void) {
  static int made = 0;
  const char *path = tmp_path("sample.h5");
  if (!made) {
    case_def c = {"sample", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_SLIP, NULL, 0};
    mrn_sim *sim = make_sim(&c);
    CHECK(run(sim, 5) == MRN_OK);
    CHECK(mrn_checkpoint_save(sim, path) == MRN_OK);
    mrn_sim_free(sim);
    made = 1;
  }
  return path;
}

static long sample_count(void) {
  mrn_sim *s = mrn_checkpoint_load(sample_checkpoint());
  long n = s ? (long)s->particles.n : -1;
  mrn_sim_free(s);
  return n;
}

/* load must fail with a message that names the file and says `part` */
static void expect_refused(const char *path, const char *part, const char *label) {
  mrn_sim *sim = mrn_checkpoint_load(path);
  CHECK(sim == NULL);
  mrn_sim_free(sim);
  CHECK(message_says(path, part));
  printf("  %-26s %s\n", label, mrn_error_message());
}

static void test_unreadable_files(void) {
  printf("refused files:\n");
  expect_refused(tmp_path("missing.h5"), "No such file", "missing file");

  const char *empty = tmp_path("empty_file.h5");
  make_empty_file(empty);
  expect_refused(empty, "empty file", "empty file");

  const char *text = tmp_path("text.h5");
  FILE *fp = fopen(text, "w");
  fprintf(fp, "this is not HDF5\n");
  fclose(fp);
  expect_refused(text, "not an HDF5 file", "text file");

  const char *cut = tmp_path("truncated.h5");
  copy_file(sample_checkpoint(), cut);
  struct stat st;
  CHECK(stat(cut, &st) == 0);
  CHECK(truncate(cut, st.st_size / 2) == 0);
  expect_refused(cut, "truncated or corrupted HDF5 file", "truncated to half");

  /* an HDF5 file of something else */
  const char *foreign = tmp_path("foreign.h5");
  hid_t f = H5Fcreate(foreign, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hsize_t dims[1] = {4};
  double t[4] = {280, 281, 282, 283};
  hid_t s = H5Screate_simple(1, dims, NULL);
  hid_t d = H5Dcreate2(f, "temperature", H5T_NATIVE_DOUBLE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t);
  H5Dclose(d);
  H5Sclose(s);
  H5Fclose(f);
  expect_refused(foreign, "not a moraine checkpoint (no 'format' attribute", "foreign HDF5 file");
}

/* ---- targeted damage: edit a copy of the sample with plain HDF5 calls ---- */

typedef void (*damage_fn)(hid_t file, long n);

static void set_string_attr(hid_t file, const char *obj, const char *name, const char *value) {
  H5Adelete_by_name(file, obj, name, H5P_DEFAULT);
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  hid_t s = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate_by_name(file, obj, name, t, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, t, &value);
  H5Aclose(a);
  H5Sclose(s);
  H5Tclose(t);
}

static void set_number_attr(hid_t file, const char *obj, const char *name, hid_t type, const void *value) {
  H5Adelete_by_name(file, obj, name, H5P_DEFAULT);
  hid_t s = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate_by_name(file, obj, name, type, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, value);
  H5Aclose(a);
  H5Sclose(s);
}

static void set_int_attr(hid_t file, const char *obj, const char *name, long long v) {
  set_number_attr(file, obj, name, H5T_NATIVE_LLONG, &v);
}

static void set_double_attr(hid_t file, const char *obj, const char *name, double v) {
  set_number_attr(file, obj, name, H5T_NATIVE_DOUBLE, &v);
}

/* replace a dataset by rows x cols values of `type` (cols 0: rank 1) */
static void replace_dataset(hid_t file, const char *path, hid_t type, const void *data, hsize_t rows, hsize_t cols) {
  H5Ldelete(file, path, H5P_DEFAULT);
  hsize_t dims[2] = {rows, cols};
  hid_t s = H5Screate_simple(cols ? 2 : 1, dims, NULL);
  hid_t d = H5Dcreate2(file, path, type, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  H5Dclose(d);
  H5Sclose(s);
}

/* change one value of a double or int dataset in place */
static void poke(hid_t file, const char *path, hid_t memtype, size_t elem, long index, const void *value) {
  hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  hid_t s = H5Dget_space(d);
  hssize_t n = H5Sget_simple_extent_npoints(s);
  char *buf = malloc((size_t)n * elem);
  H5Dread(d, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
  memcpy(buf + (size_t)index * elem, value, elem);
  H5Dwrite(d, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
  free(buf);
  H5Sclose(s);
  H5Dclose(d);
}

static void poke_double(hid_t file, const char *path, long index, double v) {
  poke(file, path, H5T_NATIVE_DOUBLE, sizeof v, index, &v);
}

static void d_format(hid_t f, long n) { set_string_attr(f, "/", "format", "spreadsheet"); }
static void d_version(hid_t f, long n) { set_int_attr(f, "/", "version", MRN_CHECKPOINT_VERSION + 1); }
static void d_version_type(hid_t f, long n) { set_string_attr(f, "/", "version", "one"); }
static void d_dim(hid_t f, long n) { set_int_attr(f, "/simulation", "dim", 4); }
static void d_time(hid_t f, long n) { set_double_attr(f, "/simulation", "time", NAN); }
/* every file of version 2 holds the rows added during version 1 (sim_scalars.h `since`) */
static void d_no_load_factor(hid_t f, long n) { H5Adelete_by_name(f, "/simulation", "load_factor", H5P_DEFAULT); }
static void d_shape(hid_t f, long n) { set_string_attr(f, "/simulation", "shape", "cubic"); }
static void d_grid_missing(hid_t f, long n) { H5Ldelete(f, "/grid", H5P_DEFAULT); }
static void d_grid_cell(hid_t f, long n) { set_double_attr(f, "/grid", "cell", 0.3); }
static void d_stress_update(hid_t f, long n) { set_string_attr(f, "/scheme", "stress_update", "XYZ"); }
static void d_flip(hid_t f, long n) { set_double_attr(f, "/scheme", "flip_fraction", 1.5); }
static void d_bc_kind(hid_t f, long n) { set_string_attr(f, "/boundary/xmin", "kind", "sticky"); }
static void d_bc_mu(hid_t f, long n) { set_double_attr(f, "/boundary/ymin", "mu", -0.1); }
static void d_dt_kind(hid_t f, long n) { set_string_attr(f, "/dt_policy", "kind", "adaptive"); }
static void d_mat_type(hid_t f, long n) { set_string_attr(f, "/materials/0", "type", "granite"); }
static void d_mat_param(hid_t f, long n) { set_double_attr(f, "/materials/0/parameters", "E", -5); }
static void d_mat_extra(hid_t f, long n) { set_double_attr(f, "/materials/0/parameters", "phi", 30); }
static void d_mat_count(hid_t f, long n) { set_int_attr(f, "/materials", "count", 2); }
static void d_count(hid_t f, long n) { set_int_attr(f, "/particles", "count", n + 1); }
static void d_state_missing(hid_t f, long n) { H5Ldelete(f, "/particles/state", H5P_DEFAULT); }
static void d_x_nan(hid_t f, long n) { poke_double(f, "/particles/x", 3 * 2 + 1, NAN); }
static void d_x_outside(hid_t f, long n) { poke_double(f, "/particles/x", 3 * 4, 1.5); }
static void d_mass_zero(hid_t f, long n) { poke_double(f, "/particles/mass", 1, 0.0); }
/* F_xx = -1 with F near I: det F < 0, the volume vol0 det F would be negative */
static void d_F_inverted(hid_t f, long n) { poke_double(f, "/particles/F", 9 * 3, -1.0); }
/* the sample is 2D: F_xz of particle 2 and the affine matrix's zz of
 * particle 5 are off the plane-strain values a 2D run stores implicitly */
static void d_F_out_of_plane(hid_t f, long n) { poke_double(f, "/particles/F", 9 * 2 + 2, 0.25); }
static void d_affine_zz(hid_t f, long n) { poke_double(f, "/particles/affine", 9 * 5 + 8, 3.0); }

/* contacts: a row naming a node beyond the grid, no face, a bit that is not
 * a face's (the bodies' are kept apart), a body contact beyond the grid */
static void d_contact_node(hid_t f, long n) {
  const long long rows[2] = {1000000000LL, 4};
  set_int_attr(f, "/grid", "contact_count", 1);
  replace_dataset(f, "/grid/contact", H5T_NATIVE_LLONG, rows, 1, 2);
}
static void d_contact_bits(hid_t f, long n) {
  const long long rows[2] = {0, 0};
  set_int_attr(f, "/grid", "contact_count", 1);
  replace_dataset(f, "/grid/contact", H5T_NATIVE_LLONG, rows, 1, 2);
}
static void d_contact_unknown_bit(hid_t f, long n) {
  const long long rows[2] = {0, 64};
  set_int_attr(f, "/grid", "contact_count", 1);
  replace_dataset(f, "/grid/contact", H5T_NATIVE_LLONG, rows, 1, 2);
}
static void d_bodies_held_node(hid_t f, long n) {
  const long long rows[1] = {1000000000LL};
  set_int_attr(f, "/grid", "bodies_held_count", 1);
  replace_dataset(f, "/grid/bodies_held", H5T_NATIVE_LLONG, rows, 1, 0);
}
static void d_material_index(hid_t f, long n) {
  int32_t seven = 7;
  poke(f, "/particles/material", H5T_NATIVE_INT32, sizeof seven, 3, &seven);
}

static void d_duplicate_id(hid_t f, long n) {
  int64_t one = 1;
  poke(f, "/particles/id", H5T_NATIVE_INT64, sizeof one, 2, &one);
}

static void d_stress_shape(hid_t f, long n) {
  double *zeros = calloc((size_t)n * 5, sizeof(double));
  replace_dataset(f, "/particles/stress", H5T_NATIVE_DOUBLE, zeros, (hsize_t)n, 5);
  free(zeros);
}

static void d_x_float32(hid_t f, long n) {
  float *zeros = calloc((size_t)n * 3, sizeof(float));
  replace_dataset(f, "/particles/x", H5T_NATIVE_FLOAT, zeros, (hsize_t)n, 3);
  free(zeros);
}

static void d_mass_rank2(hid_t f, long n) {
  double *ones = malloc((size_t)n * sizeof(double));
  for (long i = 0; i < n; i++) ones[i] = 1;
  replace_dataset(f, "/particles/mass", H5T_NATIVE_DOUBLE, ones, (hsize_t)n, 1);
  free(ones);
}

static void d_external_link(hid_t f, long n) {
  H5Ldelete(f, "/particles/v", H5P_DEFAULT);
  H5Lcreate_external("other.h5", "/v", f, "/particles/v", H5P_DEFAULT, H5P_DEFAULT);
  (void)n;
}

/* a copy of the sample damaged by fn; the expected message part, with %ld for n */
static const char *damaged(const char *name, damage_fn fn, long n) {
  const char *path = tmp_path(name);
  copy_file(sample_checkpoint(), path);
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  CHECK(f >= 0);
  fn(f, n);
  CHECK(H5Fclose(f) >= 0);
  /* checksums that fit the edit, so the loader's own checks are reached */
  CHECK(mrn_checkpoint_sign(path) == MRN_OK);
  return path;
}

typedef struct damage_case {
  const char *label;
  damage_fn fn;
  const char *expect; /* may hold two %ld for the particle count */
} damage_case;

static void test_damaged_files(void) {
  long n = sample_count();
  CHECK(n > 10);
  static const damage_case cases[] = {
      {"other format", d_format, "not a moraine checkpoint (format is 'spreadsheet')"},
      {"newer version", d_version, "newer moraine (format version 3; this moraine reads version 2)"},
      {"version as text", d_version_type, "attribute 'version' of / is a string, expected an integer"},
      {"dimension 4", d_dim, "attribute 'dim' of /simulation is 4, expected 2 to 3"},
      {"time NaN", d_time, "attribute 'time' of /simulation is NaN"},
      {"version 2 without load_factor", d_no_load_factor, "/simulation has no attribute 'load_factor'"},
      {"unknown shape", d_shape, "attribute 'shape' of /simulation is 'cubic', expected one of: linear"},
      {"no /grid", d_grid_missing, "missing group /grid"},
      {"cell vs ncell", d_grid_cell, "but ncell[1] is 10"},
      {"stress update", d_stress_update, "'XYZ', expected one of: USF, USL, MUSL"},
      {"flip fraction", d_flip, "flip_fraction' of /scheme is 1.5, expected 0 to 1"},
      {"boundary kind", d_bc_kind, "'sticky', expected one of: free, fixed, slip, friction"},
      {"negative mu", d_bc_mu, "attribute 'mu' of /boundary/ymin is -0.1, expected at least 0"},
      {"dt policy kind", d_dt_kind, "'adaptive', expected one of: fixed, a_tau, "},
      {"material type", d_mat_type, "/materials/0: unknown material type 'granite'"},
      {"material E < 0", d_mat_param, "/materials/0: material linear_elastic: E = -5 is out of range"},
      {"unknown parameter", d_mat_extra, "material type linear_elastic has no parameter 'phi'"},
      {"material count", d_mat_count, "missing group /materials/1"},
      {"stress 5 columns", d_stress_shape, "/particles/stress has shape %ld x 5, expected %ld x 6"},
      {"float32 positions", d_x_float32, "/particles/x holds 32-bit float values, expected 64-bit float values"},
      {"mass as N x 1", d_mass_rank2, "/particles/mass has shape %ld x 1, expected %ld"},
      {"no state", d_state_missing, "missing dataset /particles/state"},
      {"NaN position", d_x_nan, "/particles/x: particle 2 (id 3) has a non-finite value NaN"},
      {"outside the grid", d_x_outside, "particle 4 (id 5) at (1.5, "},
      {"zero mass", d_mass_zero, "particle 1 (id 2) has mass = 0, expected > 0"},
      {"det F < 0", d_F_inverted, "/particles/F: particle 3 (id 4) has det F = -"},
      {"2D F out of plane", d_F_out_of_plane,
       "/particles/F: particle 2 (id 3) has z components (0.25, 0, 0, 0, zz 1) in a 2D file, expected 0, 0, 0, 0 and zz 1"},
      {"2D affine zz", d_affine_zz, "/particles/affine: particle 5 (id 6) has z components (0, 0, 0, 0, zz 3) in a 2D file"},
      {"contact beyond the grid", d_contact_node, "/grid/contact: row 1 (node 1000000000, bits 4) is not a node"},
      {"contact with no face", d_contact_bits, "/grid/contact: row 1 (node 0, bits 0) is not a node"},
      {"contact with a bit not a face's", d_contact_unknown_bit, "/grid/contact: row 1 (node 0, bits 64) is not a node"},
      {"body contact beyond the grid", d_bodies_held_node, "/grid/bodies_held: row 1 (node 1000000000) is not a node"},
      {"material index", d_material_index, "particle 3 (id 4) has material 7, but the file defines 1 material"},
      {"duplicate id", d_duplicate_id, "/particles/id: id 1 appears more than once"},
      {"external link", d_external_link, "/particles/v is a soft or external link"},
  };
  printf("refused checkpoints:\n");
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char name[64], expect[256];
    snprintf(name, sizeof name, "damaged_%zu.h5", i);
    snprintf(expect, sizeof expect, cases[i].expect, n, n);
    expect_refused(damaged(name, cases[i].fn, n), expect, cases[i].label);
  }
  /* the count attribute disagrees with the datasets */
  char expect[128];
  snprintf(expect, sizeof expect, "/particles/x has shape %ld x 3, expected %ld x 3", n, n + 1);
  expect_refused(damaged("damaged_count.h5", d_count, n), expect, "particle count");
}

/* A file written while the current volume was a field of its own holds
 * /particles/vol (N): it still loads, the dataset unread, to the same state. */
static void test_file_with_vol(void) {
  const char *path = tmp_path("with_vol.h5");
  copy_file(sample_checkpoint(), path);
  mrn_sim *ref = mrn_checkpoint_load(sample_checkpoint());
  CHECK(ref != NULL);
  if (!ref) return;
  const size_t n = ref->particles.n;
  double *vol = malloc(n * sizeof *vol);
  for (size_t p = 0; p < n; p++) vol[p] = mrn_particle_volume(&ref->particles, p);
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  CHECK(f >= 0);
  replace_dataset(f, "/particles/vol", H5T_NATIVE_DOUBLE, vol, (hsize_t)n, 0);
  CHECK(H5Fclose(f) >= 0);
  CHECK(mrn_checkpoint_sign(path) == MRN_OK);
  free(vol);
  mrn_sim *old = mrn_checkpoint_load(path);
  CHECK(old != NULL);
  if (old) CHECK(same_particles(&ref->particles, &old->particles));
  printf("a file with /particles/vol (%zu particles) loads: %s\n", n, old ? "yes" : mrn_error_message());
  mrn_sim_free(old);
  mrn_sim_free(ref);
}

/* ---- checksums ----------------------------------------------------------------- */

typedef struct region {
  long long offset, bytes;
  char path[160];
} region;

typedef struct regions {
  region r[64];
  int n;
} regions;

/* where each dataset's values lie, asked of HDF5 itself (not of moraine's table) */
static herr_t add_region(hid_t root, const char *name, const H5O_info_t *info, void *data) {
  regions *rs = data;
  if (info->type != H5O_TYPE_DATASET || rs->n == 64) return 0;
  hid_t d = H5Oopen(root, name, H5P_DEFAULT);
  haddr_t offset = H5Dget_offset(d);
  hsize_t bytes = H5Dget_storage_size(d);
  H5Oclose(d);
  if (offset == HADDR_UNDEF || bytes == 0) return 0;
  region *r = &rs->r[rs->n++];
  r->offset = (long long)offset;
  r->bytes = (long long)bytes;
  snprintf(r->path, sizeof r->path, "/%s", name);
  return 0;
}

static void file_regions(const char *path, regions *rs, hsize_t *userblock) {
  rs->n = 0;
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  CHECK(f >= 0);
  hid_t fcpl = H5Fget_create_plist(f);
  CHECK(H5Pget_userblock(fcpl, userblock) >= 0);
  H5Pclose(fcpl);
  CHECK(H5Ovisit2(f, H5_INDEX_NAME, H5_ITER_INC, add_region, rs, H5O_INFO_BASIC) >= 0);
  H5Fclose(f);
}

static const region *region_of(const regions *rs, long long offset) {
  for (int i = 0; i < rs->n; i++)
    if (offset >= rs->r[i].offset && offset < rs->r[i].offset + rs->r[i].bytes) return &rs->r[i];
  return NULL;
}

/* a checkpoint with every kind of dataset: history variables, friction
 * contacts, a registered field */
static const char *checksum_sample(void) {
  const char *path = tmp_path("checksum_sample.h5");
  case_def c = {"checksums", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_FRICTION,
                &mrn_material_mohr_coulomb, 0};
  mrn_sim *sim = make_sim(&c);
  CHECK(mrn_particles_add_user_field(&sim->particles, "tag", 2, 0.5, "m") == MRN_OK);
  CHECK(run(sim, 10) == MRN_OK);
  CHECK(mrn_checkpoint_save(sim, path) == MRN_OK);
  mrn_sim_free(sim);
  return path;
}

static void write_bytes(const char *path, const unsigned char *bytes, size_t size) {
  FILE *fp = fopen(path, "wb");
  CHECK(fp && fwrite(bytes, 1, size, fp) == size);
  if (fp) fclose(fp);
}

/* a copy of `bytes` with byte `offset` changed by xor `mask`, loaded: the
 * message, which must name the file, goes to `msg` (NULL: it loaded) */
static const char *load_damaged(const char *path, unsigned char *bytes, size_t size, long long offset,
                                unsigned char mask) {
  bytes[offset] ^= mask;
  write_bytes(path, bytes, size);
  bytes[offset] ^= mask;
  mrn_sim *sim = mrn_checkpoint_load(path);
  if (sim) {
    mrn_sim_free(sim);
    return NULL;
  }
  return mrn_error_message();
}

/* One damaged byte anywhere is refused: in a dataset's values the message
 * names the dataset, in HDF5's metadata (the attributes among it) or in the
 * checksum table it says so. Every k-th byte of the file, with masks from a
 * single bit to the whole byte, and a byte in the middle of every dataset. */
static void test_single_byte_damage(void) {
  const char *sample = checksum_sample(), *path = tmp_path("one_byte.h5");
  size_t size = 0;
  unsigned char *bytes = (unsigned char *)read_all(sample, &size);
  CHECK(bytes != NULL);
  if (!bytes) return;
  regions rs;
  hsize_t userblock = 0;
  file_regions(sample, &rs, &userblock);
  CHECK(rs.n >= 18 && userblock >= 512);
  static const unsigned char masks[] = {0x01, 0x80, 0xff, 0x5a, 0x10};
  long long offsets[2048];
  int n = 0;
  const long long stride = (long long)size / 600 + 1;
  for (long long at = 0; at < (long long)size && n < 1900; at += stride) offsets[n++] = at;
  offsets[n++] = (long long)size - 1;
  for (int i = 0; i < rs.n; i++) offsets[n++] = rs.r[i].offset + rs.r[i].bytes / 2;
  int loaded = 0, in_table = 0, in_metadata = 0, in_data = 0, hit[64] = {0};
  for (int k = 0; k < n; k++) {
    const char *msg = load_damaged(path, bytes, size, offsets[k], masks[k % 5]);
    const region *r = region_of(&rs, offsets[k]);
    char want[256];
    if (offsets[k] < (long long)userblock)
      snprintf(want, sizeof want, "checksum table");
    else if (r)
      snprintf(want, sizeof want, "%s fails its checksum: its values are damaged", r->path);
    else
      snprintf(want, sizeof want, "the HDF5 metadata (groups, attributes, dataset layouts) fails its checksum");
    int ok = msg && message_says(path, want);
    CHECK(ok);
    if (!ok) fprintf(stderr, "  byte %lld ^ 0x%02x: %s\n", offsets[k], masks[k % 5], msg ? msg : "loaded");
    loaded += !msg;
    in_table += offsets[k] < (long long)userblock;
    in_metadata += offsets[k] >= (long long)userblock && !r;
    if (r) {
      in_data++;
      hit[r - rs.r] = 1;
    }
  }
  int datasets = 0;
  for (int i = 0; i < rs.n; i++) datasets += hit[i];
  CHECK(loaded == 0 && datasets == rs.n);
  printf("one damaged byte: %d of %d offsets of a %zu-byte checkpoint refused (%d in the values of %d of its %d "
         "datasets, %d in HDF5 metadata, %d in the checksum table); %d loaded\n",
         n - loaded, n, size, in_data, datasets, rs.n, in_metadata, in_table, loaded);
  free(bytes);
}

/* the case of the report: one byte of a particle's vol0, 6.25e-4 -> 6.6e179 */
static void test_vol0_byte(void) {
  const char *sample = sample_checkpoint(), *path = tmp_path("vol0_byte.h5");
  size_t size = 0;
  unsigned char *bytes = (unsigned char *)read_all(sample, &size);
  regions rs;
  hsize_t userblock = 0;
  file_regions(sample, &rs, &userblock);
  const region *vol0 = NULL;
  for (int i = 0; i < rs.n; i++)
    if (strcmp(rs.r[i].path, "/particles/vol0") == 0) vol0 = &rs.r[i];
  CHECK(bytes && vol0);
  if (!bytes || !vol0) return;
  /* the top byte of particle 3's value (little-endian): sign and exponent */
  long long at = vol0->offset + 3 * 8 + 7;
  double before, after;
  memcpy(&before, bytes + vol0->offset + 3 * 8, 8);
  unsigned char mask = bytes[at] ^ 0x65;
  bytes[at] ^= mask;
  memcpy(&after, bytes + vol0->offset + 3 * 8, 8);
  bytes[at] ^= mask;
  const char *msg = load_damaged(path, bytes, size, at, mask);
  CHECK(msg && message_says(path, "/particles/vol0 fails its checksum"));
  printf("vol0 of particle 3, %g -> %g: %s\n", before, after, msg ? msg : "loaded");
  free(bytes);
}

/* The first bytes wiped: HDF5 still reads the file, but a file of version 2
 * without its table is refused; editing a checkpoint with HDF5 and signing
 * it makes it load again. */
static void test_table_rules(void) {
  const char *sample = sample_checkpoint(), *path = tmp_path("no_table.h5");
  size_t size = 0;
  unsigned char *bytes = (unsigned char *)read_all(sample, &size);
  CHECK(bytes != NULL);
  if (!bytes) return;
  memset(bytes, 0, 512);
  write_bytes(path, bytes, size);
  free(bytes);
  expect_refused(path, "format version 2, but no checksum table in its first bytes", "table wiped");

  const char *edited = tmp_path("edited.h5");
  copy_file(sample, edited);
  hid_t f = H5Fopen(edited, H5F_ACC_RDWR, H5P_DEFAULT);
  set_double_attr(f, "/simulation", "time", 42.0);
  H5Fclose(f);
  expect_refused(edited, "fails its checksum: the file is damaged or was changed by another program",
                 "edited, not signed");
  CHECK(mrn_checkpoint_sign(edited) == MRN_OK);
  mrn_checkpoint_info info;
  mrn_sim *sim = mrn_checkpoint_load_info(edited, &info);
  CHECK(sim && sim->time == 42.0 && info.checksums == 1 && info.version == MRN_CHECKPOINT_VERSION);
  mrn_sim_free(sim);
}

/* the committed older checkpoint (format version 1, no checksums), beside this file's directory */
static const char *older_checkpoint(void) {
  static char path[600];
  snprintf(path, sizeof path, "%s", __FILE__);
  char *slash = strrchr(path, '/');
  if (!slash) return "";
  snprintf(slash, sizeof path - (size_t)(slash - path), "/../fuzz/corpus/checkpoint/valid_2d.h5");
  return path;
}

/* a file of version 1 loads as before, with one warning naming it; saved
 * again it has checksums */
static void test_older_file(void) {
  const char *older = older_checkpoint();
  mrn_warning_reset();
  mrn_checkpoint_info info;
  mrn_sim *sim = mrn_checkpoint_load_info(older, &info);
  CHECK(sim != NULL);
  if (!sim) {
    fprintf(stderr, "  %s\n", mrn_error_message());
    return;
  }
  CHECK(info.version == 1 && info.checksums == 0 && mrn_warning_count() == 1);
  /* written before point forces and the outflow book: their initial values */
  CHECK(sim->load_factor == 1.0 && sim->work_external == 0.0 && sim->on_leave == MRN_LEAVE_STOP &&
        sim->outflow_particles == 0 && sim->outflow_mass == 0.0 && sim->energy_outflow == 0.0);
  printf("older file: version %d, %ld particles, checksums %d, warnings %d\n", info.version, info.particles,
         info.checksums, mrn_warning_count());
  const char *again = tmp_path("older_saved.h5");
  CHECK(mrn_checkpoint_save(sim, again) == MRN_OK);
  mrn_sim *back = mrn_checkpoint_load_info(again, &info);
  CHECK(back && info.version == MRN_CHECKPOINT_VERSION && info.checksums == 1);
  if (back) CHECK(same_particles(&sim->particles, &back->particles));
  CHECK(mrn_checkpoint_sign(older) != MRN_OK && strstr(mrn_error_message(), "has no user block"));
  mrn_warning_reset();
  mrn_sim_free(back);
  mrn_sim_free(sim);
}

static size_t heap_in_use(void) { return mallinfo2().uordblks; }

/* Loading a damaged file again and again keeps the heap as it was: nothing
 * is left behind by a refusal (under the sanitizers LeakSanitizer checks
 * the same at exit). */
static void test_refusals_leak_nothing(void) {
  const char *sample = sample_checkpoint(), *path = tmp_path("refused_again.h5");
  regions rs;
  hsize_t userblock = 0;
  file_regions(sample, &rs, &userblock);
  CHECK(rs.n > 0);
  /* a byte of HDF5's first object header, of a dataset, of the table, and the table wiped */
  const long long at[4] = {(long long)userblock + 74, rs.n ? rs.r[0].offset : 0, 100, 0};
  const char *what[4] = {"HDF5 metadata", "dataset values", "checksum table", "no table"};
  for (int k = 0; k < 4; k++) {
    size_t size = 0;
    unsigned char *bytes = (unsigned char *)read_all(sample, &size);
    CHECK(bytes != NULL);
    if (!bytes) return;
    bytes[at[k]] ^= 0x5a;
    if (k == 3) memset(bytes, 0, 512);
    write_bytes(path, bytes, size);
    free(bytes);
    /* HDF5 keeps freed blocks in its own free lists, whose size settles over
     * the first refusals and then cycles by a few hundred bytes */
    for (int i = 0; i < 20; i++) CHECK(mrn_checkpoint_load(path) == NULL);
    size_t before = heap_in_use();
    for (int i = 0; i < 200; i++) CHECK(mrn_checkpoint_load(path) == NULL);
    long grown = (long)heap_in_use() - (long)before;
    printf("200 refusals, damaged %-14s: heap in use %+ld bytes (%s)\n", what[k], grown, mrn_error_message());
    /* a block left behind by each refusal would add at least 32 bytes
     * (glibc's smallest chunk) per refusal: 6,400 over 200 */
    CHECK(grown < 200 * 16);
  }
}

/* ---- import ---------------------------------------------------------------------- */

static mrn_sim *wide_sim(void) {
  /* six times wider, shifted, finer cells */
  mrn_sim_config cfg = {.dim = 2, .origin = {-0.5, 0, 0}, .size = {6, 1, 0}, .cell = 0.05,
                        .shape = MRN_SHAPE_QUADRATIC_BSPLINE, .gravity = {0, -9.81, 0}};
  return mrn_sim_new(&cfg);
}

static int fields_equal(const mrn_particles *a, size_t ia, const mrn_particles *b, size_t ib, size_t n,
                        const char *name) {
  const mrn_particle_field_info *f = mrn_particle_field_find(name);
  const size_t stride = (size_t)mrn_particle_field_stride(a, f);
  return same_bits(mrn_particle_field_data(a, f) + ia * stride, mrn_particle_field_data(b, f) + ib * stride,
                   n * stride * sizeof(double));
}

static void test_import(void) {
  case_def c = {"import", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_FRICTION, NULL, 0};
  mrn_sim *src = make_sim(&c);
  CHECK(run(src, 40) == MRN_OK);
  const char *path = tmp_path("settled.h5");
  CHECK(mrn_checkpoint_save(src, path) == MRN_OK);
  const mrn_particles *sp = &src->particles;

  mrn_sim *dst = wide_sim();
  /* one particle already there: imported ones come after it with new ids */
  mrn_material *other = elastic(5e6);
  int oi = mrn_sim_add_material(dst, other);
  mrn_particles_add(&dst->particles, (double[3]){4, 0.5, 0}, 1.0, 1e-3, oi);
  mrn_sim_particles_changed(dst);

  long count = -1;
  CHECK(mrn_checkpoint_import(dst, path, NULL, NULL, &count) == MRN_OK);
  CHECK(count == (long)sp->n && dst->particles.n == sp->n + 1);
  int all_equal = 1;
  for (int i = 0; i < mrn_particle_field_count(); i++)
    all_equal &= fields_equal(&dst->particles, 1, sp, 0, sp->n, mrn_particle_field_at(i)->name);
  CHECK(all_equal);
  CHECK(fields_equal(&dst->particles, 1, sp, 0, sp->n, "x"));
  CHECK(fields_equal(&dst->particles, 1, sp, 0, sp->n, "stress"));
  CHECK(dst->nmaterials == 2 && dst->particles.material[1] == 1 && dst->materials[1]->type == src->materials[0]->type);
  CHECK(dst->particles.id[1] == 2 && dst->particles.id[sp->n] == (int64_t)sp->n + 1);
  printf("import onto a 6x wider grid: %ld particles, positions and stresses %s\n", count,
         all_equal ? "bitwise identical" : "DIFFERENT");

  /* a second import reuses the identical material; an offset moves x and x0 */
  size_t before = dst->particles.n;
  CHECK(mrn_checkpoint_import(dst, path, NULL, (double[3]){2.5, 0, 99}, &count) == MRN_OK);
  CHECK(dst->nmaterials == 2 && dst->particles.material[before] == 1);
  int shifted = 1;
  for (size_t p = 0; p < sp->n; p++) {
    shifted &= dst->particles.x[3 * (before + p)] == sp->x[3 * p] + 2.5;
    shifted &= dst->particles.x0[3 * (before + p)] == sp->x0[3 * p] + 2.5;
    shifted &= dst->particles.x[3 * (before + p) + 1] == sp->x[3 * p + 1];
    shifted &= dst->particles.x[3 * (before + p) + 2] == sp->x[3 * p + 2]; /* z untouched in 2D */
  }
  CHECK(shifted);
  CHECK(fields_equal(&dst->particles, before, sp, 0, sp->n, "stress"));

  /* an override material takes every imported particle */
  before = dst->particles.n;
  mrn_material *stiff = elastic(2e7);
  CHECK(mrn_checkpoint_import(dst, path, stiff, (double[3]){4.5, 0, 0}, &count) == MRN_OK);
  CHECK(dst->nmaterials == 3 && dst->materials[2] == stiff);
  int all_stiff = 1;
  for (size_t p = before; p < dst->particles.n; p++) all_stiff &= dst->particles.material[p] == 2;
  CHECK(all_stiff);
  CHECK(fields_equal(&dst->particles, before, sp, 0, sp->n, "stress"));
  CHECK(run(dst, 5) == MRN_OK);

  /* refused imports leave the target as it was */
  size_t n_before = dst->particles.n;
  int mats_before = dst->nmaterials;
  int64_t next_before = dst->particles.next_id;
  printf("refused imports:\n");
  CHECK(mrn_checkpoint_import(dst, path, NULL, (double[3]){5.4, 0, 0}, &count) != MRN_OK);
  CHECK(message_says(path, "would land at") && count == 0);
  printf("  %-26s %s\n", "offset off the grid", mrn_error_message());
  const char *bad = damaged("damaged_stress.h5", d_stress_shape, (long)sp->n);
  CHECK(mrn_checkpoint_import(dst, bad, NULL, NULL, &count) != MRN_OK);
  CHECK(message_says(bad, "/particles/stress has shape"));
  printf("  %-26s %s\n", "wrong-shaped stress", mrn_error_message());
  CHECK(mrn_checkpoint_import(dst, tmp_path("missing.h5"), stiff, NULL, &count) != MRN_OK);
  printf("  %-26s %s\n", "missing file", mrn_error_message());
  CHECK(dst->particles.n == n_before && dst->nmaterials == mats_before && dst->particles.next_id == next_before);

  /* a 2D checkpoint cannot go into a 3D simulation */
  case_def c3 = {"3d", 3, MRN_SHAPE_LINEAR, "FLIP", MRN_STRESS_USF, MRN_BC_SLIP, NULL, 0};
  mrn_sim *three = make_sim(&c3);
  size_t n3 = three->particles.n;
  CHECK(mrn_checkpoint_import(three, path, NULL, NULL, &count) != MRN_OK);
  CHECK(message_says(path, "the checkpoint is 2D but the simulation is 3D"));
  CHECK(three->particles.n == n3 && three->nmaterials == 1);
  printf("  %-26s %s\n", "2D file into a 3D sim", mrn_error_message());

  mrn_material_unref(other);
  mrn_material_unref(stiff);
  mrn_sim_free(three);
  mrn_sim_free(src);
  mrn_sim_free(dst);
}

/* ---- writing ------------------------------------------------------------------ */

static void test_save_errors(void) {
  case_def c = {"save", 2, MRN_SHAPE_LINEAR, "PIC", MRN_STRESS_USL, MRN_BC_SLIP, NULL, 0};
  mrn_sim *sim = make_sim(&c);
  const char *path = "/nonexistent-moraine-dir/out.h5";
  CHECK(mrn_checkpoint_save(sim, path) == MRN_ERR_IO);
  CHECK(strstr(mrn_error_message(), path) != NULL);
  printf("save into a missing directory: %s\n", mrn_error_message());
  /* overwriting an existing checkpoint replaces it whole */
  const char *again = tmp_path("again.h5");
  CHECK(mrn_checkpoint_save(sim, again) == MRN_OK);
  CHECK(run(sim, 2) == MRN_OK);
  CHECK(mrn_checkpoint_save(sim, again) == MRN_OK);
  mrn_sim *back = mrn_checkpoint_load(again);
  CHECK(back && back->step == 2);
  CHECK(count_temp_files(tmpdir) == 0);
  mrn_sim_free(back);
  mrn_sim_free(sim);
}

/* A file-size limit (like a full disk) makes the write fail: the message
 * names the file and the reason, and neither the file nor a temporary one is
 * left. Run in a child process so the limit does not touch the others. */
static void test_file_too_large(void) {
  case_def c = {"limit", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_SLIP, NULL, 0};
  mrn_sim *sim = make_sim(&c);
  const char *path = tmp_path("limited.h5");
  fflush(stdout);
  pid_t child = fork();
  if (child == 0) {
    signal(SIGXFSZ, SIG_IGN); /* write(2) then fails with EFBIG instead of killing */
    struct rlimit lim = {8192, 8192};
    setrlimit(RLIMIT_FSIZE, &lim);
    int rc = mrn_checkpoint_save(sim, path);
    printf("save with an 8 KiB file-size limit: %s\n", rc ? mrn_error_message() : "succeeded?");
    fflush(stdout);
    int ok = rc == MRN_ERR_IO && strstr(mrn_error_message(), path);
    mrn_sim_free(sim); /* the child's copy too, for memcheck */
    _exit(ok ? 0 : 1);
  }
  int status = 0;
  CHECK(child > 0 && waitpid(child, &status, 0) == child);
  CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  CHECK(access(path, F_OK) != 0 && count_temp_files(tmpdir) == 0);
  mrn_sim_free(sim);
}

static void test_import_history(void) {
  case_def c = {"history", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_FRICTION,
                &mrn_material_mohr_coulomb, 0};
  mrn_sim *src = make_sim(&c);
  CHECK(run(src, 60) == MRN_OK);
  const char *path = tmp_path("plastic.h5");
  CHECK(mrn_checkpoint_save(src, path) == MRN_OK);
  const mrn_particles *sp = &src->particles;
  int ns = mrn_material_mohr_coulomb.nstate;

  /* the same model: history variables carry over */
  mrn_sim *dst = wide_sim();
  CHECK(mrn_checkpoint_import(dst, path, NULL, NULL, NULL) == MRN_OK);
  int kept = dst->particles.n == sp->n && dst->particles.state_stride >= ns, nonzero = 0;
  for (size_t p = 0; kept && p < sp->n; p++) {
    kept &= same_bits(dst->particles.state + p * dst->particles.state_stride, sp->state + p * sp->state_stride,
                      sizeof(double) * ns);
    nonzero |= sp->state[p * sp->state_stride] != 0;
  }
  CHECK(kept && nonzero);

  /* another model (elastic override): they start from zero */
  mrn_material *el = elastic(1e6);
  CHECK(mrn_checkpoint_import(dst, path, el, (double[3]){2, 0, 0}, NULL) == MRN_OK);
  int zero = 1;
  for (size_t p = sp->n; p < dst->particles.n; p++)
    for (int k = 0; k < dst->particles.state_stride; k++)
      zero &= dst->particles.state[p * dst->particles.state_stride + k] == 0;
  CHECK(zero);
  CHECK(run(dst, 3) == MRN_OK);
  mrn_material_unref(el);
  mrn_sim_free(dst);
  mrn_sim_free(src);
}

/* ---- main ------------------------------------------------------------------------ */

static void remove_tmpdir(void) {
  if (getenv("MORAINE_KEEP_TEST_FILES")) {
    printf("files kept in %s\n", tmpdir);
    return;
  }
  remove_tree(tmpdir);
}

int main(void) {
  if (make_temp_dir(tmpdir, sizeof tmpdir, "/tmp/moraine_checkpoint") != 0) return 1;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* the damaging helpers delete what may not exist */

  const mrn_material_type *MC = &mrn_material_mohr_coulomb;
  const case_def cases[] = {
      {"flip-usf", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_SLIP, NULL, 0},
      {"pic-usl", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "PIC", MRN_STRESS_USL, MRN_BC_FRICTION, NULL, 0},
      {"mc-flip", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_FRICTION, MC, 0},
      {"mc-damped", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_FRICTION, MC, 0.1},
      {"el-damped", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "PIC", MRN_STRESS_MUSL, MRN_BC_SLIP, NULL, 0.1},
      {"nflip-musl", 2, MRN_SHAPE_LINEAR, "NFLIP0.95", MRN_STRESS_MUSL, MRN_BC_FRICTION, NULL, 0},
      {"apic-usavg", 2, MRN_SHAPE_CUBIC_BSPLINE, "APIC", MRN_STRESS_USAVG, MRN_BC_SLIP, NULL, 0},
      {"xpic-usl", 2, MRN_SHAPE_GIMP, "XPIC(2)", MRN_STRESS_USL, MRN_BC_FRICTION, MC, 0},
      {"3d-musl", 3, MRN_SHAPE_LINEAR, "FLIP0.99", MRN_STRESS_MUSL, MRN_BC_SLIP, NULL, 0},
      {"3d-mc", 3, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP", MRN_STRESS_USF, MRN_BC_FRICTION, MC, 0},
      {"mc-holds", 2, MRN_SHAPE_QUADRATIC_BSPLINE, "FLIP/particles", MRN_STRESS_USF, MRN_BC_FRICTION, MC, 0},
      {"musl-holds", 2, MRN_SHAPE_CUBIC_BSPLINE, "FLIP0.9/particles", MRN_STRESS_MUSL, MRN_BC_FRICTION, NULL, 0},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) test_restart(&cases[i], 60);
  test_empty();
  test_dt_function();
  test_unreadable_files();
  test_damaged_files();
  test_file_with_vol();
  test_single_byte_damage();
  test_vol0_byte();
  test_table_rules();
  test_older_file();
  test_refusals_leak_nothing();
  test_import();
  test_import_history();
  test_save_errors();
  test_file_too_large();
  remove_tmpdir();
  CHECK_DONE();
}
