/* moraine: checkpoints — writing a simulation, and building one (or adding
 * particles to one) from a validated file. Reading and validation are in
 * checkpoint_read.c; the layout is documented in doc/checkpoint-format.md. */
#include "io/checkpoint.h"
#include "material/user.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/comm.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/h5image.h"
#include "io/checkpoint_internal.h"
#include "io/h5util.h"
#include "solver/dist.h"

/* ---- units of the particle fields ------------------------------------------ */

/* The field table documents units in prose; the files carry them as a
 * separate attribute. 2D simulations are per unit thickness. */
static const struct {
  const char *field, *unit3d, *unit2d;
} field_units[] = {
    {"x", "m", "m"},         {"x0", "m", "m"},          {"v", "m/s", "m/s"},      {"mass", "kg", "kg/m"},
    {"vol0", "m^3", "m^2"},  {"F", "1", "1"},
    {"affine", "1/s", "1/s"}, {"stress", "Pa", "Pa"},   {"strain", "1", "1"},     {"e_elastic", "J", "J/m"},
    {"w_plastic", "J", "J/m"},
};

/* A field added later without an entry here: take the first short "(unit)"
 * of its description ("(000, Eq. 25)" is a reference, not a unit), else leave
 * the unit to the description. */
static const char *unit_from_doc(const char *doc) {
  static _Thread_local char unit[32];
  for (const char *open = strchr(doc, '('); open; open = strchr(open + 1, '(')) {
    size_t len = strcspn(open + 1, ";)");
    if (len == 0 || len >= sizeof unit || memchr(open + 1, ' ', len)) continue;
    memcpy(unit, open + 1, len);
    unit[len] = '\0';
    return unit;
  }
  return "";
}

/* units of a particle field in a `dim`-dimensional simulation ("" unknown) */
static const char *field_units_of(const char *field, int dim) {
  for (size_t i = 0; i < sizeof field_units / sizeof field_units[0]; i++)
    if (strcmp(field_units[i].field, field) == 0) return dim == 2 ? field_units[i].unit2d : field_units[i].unit3d;
  const mrn_particle_field_info *f = mrn_particle_field_find(field);
  return f ? unit_from_doc(f->doc) : "";
}

/* the component order, appended to each field's description */
static const char *component_note(int ncomp) {
  switch (ncomp) {
  case 3: return "; columns x, y, z (z = 0 in 2D)";
  case 6: return "; columns xx, yy, zz, xy, yz, xz";
  case 9: return "; columns xx, xy, xz, yx, yy, yz, zx, zy, zz (row-major 3 x 3)";
  default: return "";
  }
}

/* ---- writing ---------------------------------------------------------------- */

static void save_root(mrn_h5w *w) {
  hid_t root = H5Gopen2(w->file, "/", H5P_DEFAULT);
  if (root < 0) {
    w->failed = 1;
    snprintf(w->what, sizeof w->what, "the root group");
    return;
  }
  mrn_h5w_string(w, root, "format", MRN_CHECKPOINT_FORMAT);
  mrn_h5w_int32(w, root, "version", MRN_CHECKPOINT_VERSION);
  mrn_h5w_string(w, root, "moraine_version", MORAINE_VERSION " (" MORAINE_GIT_COMMIT ")");
  H5Gclose(root);
}

/* one attribute of /simulation per row of solver/sim_scalars.h, in its order */
#define SAVE_SCALAR(ctype, name, kind, check, since, initial, ...) \
  SAVE_##kind(w, g, #name, sim->name, ((mrn_scalar_check){check}));
#define SAVE_F64(w, g, key, v, check) mrn_h5w_double(w, g, key, v)
#define SAVE_F64X3(w, g, key, v, check) mrn_h5w_doubles(w, g, key, v, 3)
#define SAVE_I32(w, g, key, v, check) mrn_h5w_int32(w, g, key, v)
#define SAVE_I64(w, g, key, v, check) mrn_h5w_int64(w, g, key, v)
#define SAVE_NAME(w, g, key, v, check) mrn_h5w_string(w, g, key, (check).names()[v])

static void save_simulation(mrn_h5w *w, const mrn_sim *sim) {
  hid_t g = mrn_h5w_group(w, w->file, "simulation");
  if (g < 0) return;
  MRN_SIM_SCALARS(SAVE_SCALAR)
  H5Gclose(g);
}

/* the nodes whose grid.contact has any of `bits`, as rows of `cols`
 * int64: the node index, then (cols 2) its bits among `bits`; NULL when out
 * of memory (w->failed set) */
static int64_t *contact_rows(mrn_h5w *w, const mrn_grid *grid, unsigned bits, int cols, size_t *count) {
  *count = 0;
  for (size_t n = 0; n < grid->n; n++) *count += (grid->contact[n] & bits) != 0;
  int64_t *rows = malloc((size_t)cols * (*count ? *count : 1) * sizeof *rows);
  if (!rows) {
    w->failed = 1;
    snprintf(w->what, sizeof w->what, "/grid/contact (out of memory)");
    return NULL;
  }
  for (size_t n = 0, k = 0; n < grid->n; n++)
    if (grid->contact[n] & bits) {
      rows[cols * k] = (int64_t)n;
      if (cols == 2) rows[cols * k + 1] = grid->contact[n] & bits;
      k++;
    }
  return rows;
}

/* the friction faces' contact states (grid.contact) as rows (node, bits),
 * and apart the nodes where the contact between bodies held: a reader that
 * knows only the faces' bits still reads the file */
static void save_contacts(mrn_h5w *w, hid_t g, const mrn_grid *grid) {
  size_t count;
  int64_t *rows = contact_rows(w, grid, (1u << MRN_FACE_COUNT) - 1, 2, &count);
  if (!rows) return;
  mrn_h5w_int64(w, g, "contact_count", (int64_t)count);
  mrn_h5w_dataset(w, g, "contact", H5T_NATIVE_INT64, rows, count, 2, "",
                  "friction-face contacts held at the end of the last step: node index, bits 1 << face");
  free(rows);
  if (!(rows = contact_rows(w, grid, MRN_GRID_BODIES_HELD, 1, &count))) return;
  mrn_h5w_int64(w, g, "bodies_held_count", (int64_t)count);
  mrn_h5w_dataset(w, g, "bodies_held", H5T_NATIVE_INT64, rows, count, MRN_H5_RANK1, "",
                  "nodes where the contact between bodies held at the end of the last step");
  free(rows);
}

static void save_grid(mrn_h5w *w, const mrn_grid *grid) {
  hid_t g = mrn_h5w_group(w, w->file, "grid");
  if (g < 0) return;
  mrn_h5w_int32(w, g, "dim", grid->dim);
  mrn_h5w_doubles(w, g, "origin", grid->origin, 3);
  mrn_h5w_doubles(w, g, "size", grid->size, 3);
  mrn_h5w_double(w, g, "cell", grid->cell);
  mrn_h5w_int32s(w, g, "ncell", grid->ncell, 3);
  save_contacts(w, g, grid);
  H5Gclose(g);
}

static void save_scheme(mrn_h5w *w, const mrn_scheme *s) {
  hid_t g = mrn_h5w_group(w, w->file, "scheme");
  if (g < 0) return;
  mrn_h5w_string(w, g, "name", s->name);
  mrn_h5w_string(w, g, "grid_velocity", mrn_grid_velocity_names()[s->grid_velocity]);
  mrn_h5w_string(w, g, "velocity_update", mrn_velocity_update_names()[s->velocity_update]);
  mrn_h5w_string(w, g, "position_update", mrn_position_update_names()[s->position_update]);
  mrn_h5w_double(w, g, "flip_fraction", s->flip_fraction);
  mrn_h5w_int32(w, g, "xpic_order", s->xpic_order);
  mrn_h5w_int32(w, g, "mls_gradient", s->mls_gradient);
  mrn_h5w_string(w, g, "stress_update", mrn_stress_update_names()[s->stress_update]);
  /* only when asked for: a run without it writes the file it wrote before */
  if (s->volumetric != MRN_VOLUMETRIC_STANDARD)
    mrn_h5w_string(w, g, "volumetric", mrn_volumetric_names()[s->volumetric]);
  if (s->holds != MRN_HOLDS_GRID) mrn_h5w_string(w, g, "holds", mrn_holds_names()[s->holds]);
  H5Gclose(g);
}

/* all six faces, also in 2D (the z faces are then unused) */
static void save_boundary(mrn_h5w *w, const mrn_boundary *bc) {
  hid_t g = mrn_h5w_group(w, w->file, "boundary");
  for (int f = 0; f < MRN_FACE_COUNT && g >= 0; f++) {
    hid_t face = mrn_h5w_group(w, g, mrn_face_name(f));
    if (face < 0) break;
    mrn_h5w_string(w, face, "kind", mrn_bc_kind_name(bc->face[f].kind));
    mrn_h5w_double(w, face, "mu", bc->face[f].mu);
    mrn_h5w_int32(w, face, "gap_check", bc->face[f].gap_check);
    mrn_h5w_doubles(w, face, "velocity", bc->face[f].velocity, 3);
    H5Gclose(face);
  }
  if (g >= 0) H5Gclose(g);
}

static void save_dt_policy(mrn_h5w *w, const mrn_dt_policy *p) {
  hid_t g = mrn_h5w_group(w, w->file, "dt_policy");
  if (g < 0) return;
  mrn_h5w_string(w, g, "kind", mrn_dt_kind_name(p->kind));
  mrn_h5w_double(w, g, "value", p->value);
  mrn_h5w_double(w, g, "min", p->min);
  mrn_h5w_double(w, g, "max", p->max);
  if (p->kind == MRN_DT_CALLBACK)
    mrn_h5w_string(w, g, "note",
                   "the time step was computed by a function, which a file cannot hold: a loaded simulation "
                   "steps with a fixed dt equal to /simulation dt until the deck sets its function again");
  H5Gclose(g);
}

static void save_material(mrn_h5w *w, hid_t parent, int index, const mrn_material *m) {
  char name[32];
  snprintf(name, sizeof name, "%d", index);
  hid_t g = mrn_h5w_group(w, parent, name);
  if (g < 0) return;
  mrn_h5w_string(w, g, "type", m->type->name);
  mrn_h5w_string(w, g, "name", m->name);
  hid_t params = mrn_h5w_group(w, g, "parameters");
  for (int i = 0; i < m->type->nparams && params >= 0; i++)
    mrn_h5w_double(w, params, m->type->params[i].key, m->param[i]);
  if (params >= 0) H5Gclose(params);
  if (mrn_material_is_user(m) && m->type->nstate) {
    /* its history variables are named by the deck: the names say what /particles/state holds */
    char names[MRN_USER_MAX_STATE * 33] = "";
    for (int i = 0; i < m->type->nstate; i++) {
      if (i) strcat(names, ",");
      strcat(names, m->type->state_names[i]);
    }
    mrn_h5w_string(w, g, "state_names", names);
  }
  H5Gclose(g);
}

static void save_materials(mrn_h5w *w, const mrn_sim *sim) {
  hid_t g = mrn_h5w_group(w, w->file, "materials");
  if (g < 0) return;
  mrn_h5w_int32(w, g, "count", sim->nmaterials);
  for (int i = 0; i < sim->nmaterials; i++) save_material(w, g, i, sim->materials[i]);
  H5Gclose(g);
}

/* Every field of the particle table, so a field added to the engine is saved
 * without touching this file. */
static void save_particles(mrn_h5w *w, const mrn_sim *sim) {
  const mrn_particles *ps = &sim->particles;
  hid_t g = mrn_h5w_group(w, w->file, "particles");
  if (g < 0) return;
  mrn_h5w_int64(w, g, "count", (int64_t)ps->n);
  mrn_h5w_int64(w, g, "next_id", ps->next_id);
  mrn_h5w_int32(w, g, "state_stride", ps->state_stride);
  for (int i = 0; i < mrn_particle_field_count(); i++) {
    const mrn_particle_field_info *f = mrn_particle_field_at(i);
    char doc[512];
    snprintf(doc, sizeof doc, "%s%s", f->doc, component_note(f->ncomp));
    /* the file keeps every component: a 2D run's full tensors are expanded */
    const double *data = mrn_particle_field_data(ps, f);
    double *full = NULL;
    if (ps->n && mrn_particle_field_stride(ps, f) != f->ncomp) {
      full = malloc(ps->n * (size_t)f->ncomp * sizeof *full);
      if (!full) {
        if (!w->failed) {
          w->failed = 1;
          w->err = ENOMEM;
          snprintf(w->what, sizeof w->what, "/particles/%s (no memory to expand it)", f->name);
        }
        break;
      }
      mrn_particle_field_export(ps, f, 0, ps->n, full);
      data = full;
    }
    mrn_h5w_dataset(w, g, f->name, H5T_NATIVE_DOUBLE, data, ps->n, f->ncomp == 1 ? MRN_H5_RANK1 : f->ncomp,
                    field_units_of(f->name, sim->dim), doc);
    free(full);
  }
  mrn_h5w_dataset(w, g, "material", H5T_NATIVE_INT32, ps->material, ps->n, MRN_H5_RANK1, "1",
                  "material index: the group /materials/<index>");
  mrn_h5w_dataset(w, g, "id", H5T_NATIVE_INT64, ps->id, ps->n, MRN_H5_RANK1, "1",
                  "particle id, unique in the simulation and stable through the run");
  mrn_h5w_dataset(w, g, "state", H5T_NATIVE_DOUBLE, ps->state, ps->n, ps->state_stride, "",
                  "material history variables, state_stride per particle; the first nstate of them belong to "
                  "the particle's material (its type's state_names), units as the model defines them");
  H5Gclose(g);
}

/* The fields a deck registered: /particles/user/<name>, (n) or (n, ncomp),
 * and on the group their order (`names`, comma-separated), `count`,
 * `components` and `init`. */
static void save_user_fields(mrn_h5w *w, const mrn_particles *ps) {
  if (ps->nuser == 0) return;
  hid_t g = mrn_h5w_group(w, w->file, "particles/user");
  if (g < 0) return;
  char names[MRN_USER_FIELDS_MAX * MRN_USER_FIELD_NAME] = "";
  int comps[MRN_USER_FIELDS_MAX];
  double init[MRN_USER_FIELDS_MAX];
  double *buf = malloc(sizeof(double) * (ps->n ? ps->n : 1) * (size_t)(ps->user_stride ? ps->user_stride : 1));
  for (int i = 0; i < ps->nuser; i++) {
    const mrn_user_field *f = &ps->user_fields[i];
    if (i) strcat(names, ",");
    strcat(names, f->name);
    comps[i] = f->ncomp;
    init[i] = f->init;
    if (!buf) continue;
    for (size_t p = 0; p < ps->n; p++)
      memcpy(buf + p * f->ncomp, ps->user + p * ps->user_stride + f->offset, sizeof(double) * f->ncomp);
    mrn_h5w_dataset(w, g, f->name, H5T_NATIVE_DOUBLE, buf, ps->n, f->ncomp == 1 ? MRN_H5_RANK1 : f->ncomp, f->unit,
                    "per-particle value registered by the deck (sim:particle_field), in particle order");
  }
  if (!buf && !w->failed) {
    w->failed = 1;
    snprintf(w->what, sizeof w->what, "/particles/user (out of memory)");
  }
  free(buf);
  mrn_h5w_int32(w, g, "count", ps->nuser);
  mrn_h5w_string(w, g, "names", names);
  mrn_h5w_int32s(w, g, "components", comps, ps->nuser);
  mrn_h5w_doubles(w, g, "init", init, ps->nuser);
  H5Gclose(g);
}

/* The nodal values of the last step, as the .vti snapshots hold them: for
 * post-processing only (a load does not read them; the next step recomputes
 * every nodal value), over every node including the ghost layers, x fastest. */
static void save_grid_nodes(mrn_h5w *w, const mrn_grid *grid) {
  hid_t g = mrn_h5w_group(w, w->file, "grid/nodes");
  if (g < 0) return;
  mrn_h5w_int32s(w, g, "nnode", grid->nnode, 3);
  mrn_h5w_dataset(w, g, "mass", H5T_NATIVE_DOUBLE, grid->mass, grid->n, MRN_H5_RANK1, "kg",
                  "nodal mass of the last step (kg/m in 2D)");
  mrn_h5w_dataset(w, g, "velocity", H5T_NATIVE_DOUBLE, grid->vel, grid->n, 3, "m/s",
                  "nodal velocity V of the last step, after the boundary conditions");
  mrn_h5w_dataset(w, g, "force", H5T_NATIVE_DOUBLE, grid->force, grid->n, 3, "N",
                  "total nodal force of the last step (N/m in 2D)");
  H5Gclose(g);
}

/* one source's state under /sources/<i> */
static void save_source(mrn_h5w *w, hid_t parent, int index, const mrn_source_state *st) {
  char name[32];
  snprintf(name, sizeof name, "%d", index);
  hid_t g = mrn_h5w_group(w, parent, name);
  if (g < 0) return;
  mrn_h5w_string(w, g, "name", st->name);
  mrn_h5w_double(w, g, "progress", st->progress);
  mrn_h5w_int64(w, g, "layers", st->layers);
  mrn_h5w_int64(w, g, "particles", st->particles);
  mrn_h5w_double(w, g, "mass", st->mass);
  mrn_h5w_double(w, g, "energy", st->energy);
  mrn_h5w_double(w, g, "work", st->work);
  H5Gclose(g);
}

/* the sources' states, and those a loaded file kept for sources not added
 * again: none, no group */
static void save_sources(mrn_h5w *w, const mrn_sim *sim) {
  const int count = sim->nsources + sim->nsource_states;
  if (count == 0) return;
  hid_t g = mrn_h5w_group(w, w->file, "sources");
  if (g < 0) return;
  mrn_h5w_int32(w, g, "count", count);
  for (int i = 0; i < sim->nsources; i++) save_source(w, g, i, &sim->sources[i].st);
  for (int i = 0; i < sim->nsource_states; i++) save_source(w, g, sim->nsources + i, &sim->source_states[i]);
  H5Gclose(g);
}

static void save_all(mrn_h5w *w, const mrn_sim *sim, const mrn_stash *stash) {
  save_root(w);
  save_simulation(w, sim);
  save_grid(w, &sim->grid);
  save_scheme(w, &sim->scheme);
  save_boundary(w, &sim->boundary);
  ck_save_walls(w, sim);
  save_dt_policy(w, &sim->dt_policy);
  save_materials(w, sim);
  save_particles(w, sim);
  save_user_fields(w, &sim->particles);
  save_grid_nodes(w, &sim->grid);
  save_sources(w, sim);
  ck_save_stash(w, stash);
}

/* datasets a checkpoint of `sim` holds at most: the particle fields,
 * material, id, state, the contacts, the registered fields, the grid nodes */
static int dataset_count(const mrn_sim *sim) { return mrn_particle_field_count() + 3 + 1 + sim->particles.nuser + 3; }

/* the file starts with a user block that will hold the checksum table */
static hid_t image_fcpl(uint64_t userblock) {
  hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
  if (fcpl >= 0 && H5Pset_userblock(fcpl, (hsize_t)userblock) < 0) {
    H5Pclose(fcpl);
    return H5I_INVALID_HID;
  }
  return fcpl;
}

/* The file is built in memory and written whole through the crash-safe
 * file (io/h5image.h): a crash leaves the old checkpoint or the new one, and
 * a full disk fails an ordinary write() reported with the path and reason.
 * The image starts with a user block HDF5 leaves alone; once the file is
 * complete the checksum table of its bytes goes there (checkpoint_sum.c). */
static int build_image(const mrn_sim *sim, const mrn_stash *stash, const char *final_path, void **image,
                       size_t *size) {
  mrn_h5w w = {.file = H5I_INVALID_HID};
  mrn_h5_image img;
  const uint64_t userblock = ck_sum_userblock(dataset_count(sim));
  hid_t fcpl = image_fcpl(userblock);
  if (fcpl >= 0) {
    w.file = mrn_h5_image_create(&img, final_path, fcpl);
    H5Pclose(fcpl);
  }
  *image = NULL;
  *size = 0;
  if (w.file < 0) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': HDF5 could not create the file", final_path);
  save_all(&w, sim, stash);
  /* where each dataset's values lie is settled once they are flushed */
  ck_ranges ranges = {0};
  if (H5Fflush(w.file, H5F_SCOPE_GLOBAL) < 0 || ck_sum_collect(w.file, &ranges)) w.failed = 1;
  if (mrn_h5_image_close(&img, w.file, image, size) == 0 && !w.failed &&
      ck_sum_write_image(*image, *size, userblock, &ranges) == 0) {
    ck_ranges_free(&ranges);
    return MRN_OK;
  }
  ck_ranges_free(&ranges);
  free(*image);
  *image = NULL;
  if (w.failed && w.what[0])
    return mrn_error_code(MRN_ERR_IO, "cannot write '%s': HDF5 could not write %s", final_path, w.what);
  return mrn_error_code(MRN_ERR_IO, "cannot write '%s': HDF5 could not build the file in memory", final_path);
}

int mrn_checkpoint_save(const mrn_sim *sim, const char *path) { return mrn_checkpoint_save_stash(sim, NULL, path); }

static int save_whole(const mrn_sim *sim, const mrn_stash *stash, const char *path);

/* In a distributed run process 0 writes the checkpoint with every particle
 * gathered to it, in the order of their ids: a file like a one-process
 * run's, which a run on any number of processes loads (solver/dist.h). */
int mrn_checkpoint_save_stash(const mrn_sim *sim, const mrn_stash *stash, const char *path) {
  int rc = mrn_dist_gather_begin(sim);
  if (rc == MRN_OK && mrn_comm_writes()) rc = save_whole(sim, stash, path);
  mrn_dist_gather_end(sim);
  return mrn_dist_agree(sim, rc);
}

static int save_whole(const mrn_sim *sim, const mrn_stash *stash, const char *path) {
  void *image;
  size_t size;
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  int rc = build_image(sim, stash, path, &image, &size);
  mrn_h5_restore(&quiet);
  if (rc == MRN_OK) rc = mrn_atomic_write_file(path, image, size);
  free(image);
  return rc;
}

/* ---- loading ------------------------------------------------------------------ */

static void take_dt_policy(mrn_sim *sim, const ck_data *d, mrn_checkpoint_info *info) {
  if (d->dt_kind != MRN_DT_CALLBACK) {
    /* every policy but a function is its kind and value */
    mrn_dt_policy_release(&sim->dt_policy);
    sim->dt_policy.kind = d->dt_kind;
    sim->dt_policy.value = d->dt_value;
  } else {
    /* a function cannot be saved: keep stepping with the last dt it gave */
    mrn_dt_policy_fixed(&sim->dt_policy, d->dt);
    info->dt_function_dropped = 1;
    snprintf(info->note, sizeof info->note,
             "the time step was set by a function, which a checkpoint cannot hold; the loaded simulation uses a "
             "fixed dt = %.17g s (the last step's) until the function is set again",
             d->dt);
  }
  sim->dt_policy.min = d->dt_min;
  sim->dt_policy.max = d->dt_max;
}

static int take_particles(mrn_sim *sim, const ck_data *d) {
  mrn_particles *ps = &sim->particles;
  if (mrn_particles_set_state_stride(ps, d->state_stride) || mrn_particles_reserve(ps, (size_t)d->n))
    return MRN_ERR;
  for (int i = 0; i < mrn_particle_field_count(); i++) {
    const mrn_particle_field_info *f = mrn_particle_field_at(i);
    mrn_particle_field_import(ps, f, 0, (size_t)d->n, d->field[i]);
  }
  if (d->n) {
    memcpy(ps->material, d->material, (size_t)d->n * sizeof *ps->material);
    memcpy(ps->id, d->id, (size_t)d->n * sizeof *ps->id);
  }
  if (d->n && d->state_stride) memcpy(ps->state, d->state, (size_t)d->n * d->state_stride * sizeof(double));
  /* the registered fields: all of them first (each widens the storage), then their values */
  for (int i = 0; i < d->nuser; i++)
    if (mrn_particles_add_user_field(ps, d->user[i].name, d->user[i].ncomp, d->user[i].init, d->user[i].unit))
      return MRN_ERR;
  for (int i = 0; i < d->nuser; i++) {
    const mrn_user_field *f = &ps->user_fields[i];
    for (int64_t p = 0; p < d->n; p++)
      memcpy(ps->user + p * ps->user_stride + f->offset, d->user_values[i] + p * f->ncomp, sizeof(double) * f->ncomp);
  }
  ps->n = (size_t)d->n;
  ps->next_id = d->next_id;
  return MRN_OK;
}

/* a row of solver/sim_scalars.h, as read */
#define TAKE_SCALAR(ctype, name, kind, check, since, initial, ...) \
  memcpy(&sim->name, &d->name, sizeof d->name);

/* everything in d has been checked; what can still fail is memory */
static mrn_sim *build_sim(const ck_data *d, mrn_checkpoint_info *info) {
  mrn_sim_config cfg = {.dim = d->dim, .cell = d->cell, .shape = d->shape, .kernel_boundary = d->kernel_boundary};
  memcpy(cfg.origin, d->origin, sizeof cfg.origin);
  memcpy(cfg.size, d->size, sizeof cfg.size);
  memcpy(cfg.gravity, d->gravity, sizeof cfg.gravity);
  mrn_sim *sim = mrn_sim_new(&cfg);
  if (!sim) return NULL;
  sim->scheme = d->scheme;
  sim->boundary = d->boundary;
  sim->boundary.walls = NULL;
  if (ck_take_walls(sim, d)) goto fail;
  take_dt_policy(sim, d, info);
  for (int64_t k = 0; k < d->ncontact; k++) sim->grid.contact[d->contact[2 * k]] = (unsigned char)d->contact[2 * k + 1];
  for (int64_t k = 0; k < d->nbodies_held; k++) sim->grid.contact[d->bodies_held[k]] |= MRN_GRID_BODIES_HELD;
  for (int i = 0; i < d->nmaterials; i++)
    if (mrn_sim_add_material(sim, d->materials[i]) < 0) goto fail;
  if (take_particles(sim, d)) goto fail;
  if (mrn_sim_keep_source_states(sim, d->sources, d->nsources)) goto fail;
  mrn_sim_particles_changed(sim);
  /* last: mass_floor as saved, whatever rule computed it */
  MRN_SIM_SCALARS(TAKE_SCALAR)
  return sim;
fail:
  mrn_sim_free(sim);
  return NULL;
}

mrn_sim *mrn_checkpoint_load_info(const char *path, mrn_checkpoint_info *info) {
  mrn_checkpoint_info scratch;
  if (!info) info = &scratch;
  memset(info, 0, sizeof *info);
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  ck_data d;
  int rc = ck_read(path, &d);
  mrn_h5_restore(&quiet);
  if (rc) return NULL;
  mrn_sim *sim = build_sim(&d, info);
  if (!sim) {
    char inner[1024];
    snprintf(inner, sizeof inner, "%s", mrn_error_message());
    mrn_error_code(MRN_ERR_IO, "'%s': %s", path, inner);
  } else {
    info->version = d.version;
    info->checksums = d.checksums;
    snprintf(info->moraine_version, sizeof info->moraine_version, "%s", d.moraine_version);
    info->particles = (long)d.n;
  }
  ck_free(&d);
  return sim;
}

mrn_sim *mrn_checkpoint_load(const char *path) { return mrn_checkpoint_load_info(path, NULL); }

/* ---- importing ------------------------------------------------------------------ */

/* where the imported particles' materials go in the target simulation */
typedef struct import_plan {
  int target[MRN_MAX_MATERIALS];        /* checkpoint material -> target index, -1 unused */
  mrn_material *add[MRN_MAX_MATERIALS]; /* materials to register, in order */
  int nadd;
  int stride; /* history storage the target needs */
} import_plan;

static int same_material(const mrn_material *a, const mrn_material *b) {
  return a->type == b->type && strcmp(a->name, b->name) == 0 &&
         memcmp(a->param, b->param, sizeof(double) * (size_t)a->type->nparams) == 0;
}

/* index a material will have in the target: its present one, or the next free */
static int plan_material(import_plan *plan, const mrn_sim *sim, mrn_material *m, int reuse_equal) {
  for (int j = 0; j < sim->nmaterials; j++)
    if (sim->materials[j] == m || (reuse_equal && same_material(sim->materials[j], m))) return j;
  for (int k = 0; k < plan->nadd; k++)
    if (plan->add[k] == m) return sim->nmaterials + k;
  if (m->type->nstate > plan->stride) plan->stride = m->type->nstate;
  plan->add[plan->nadd] = m;
  return sim->nmaterials + plan->nadd++;
}

static int make_plan(import_plan *plan, const mrn_sim *sim, const ck_data *d, mrn_material *override,
                     const char *path) {
  memset(plan, 0, sizeof *plan);
  plan->stride = sim->particles.state_stride;
  for (int i = 0; i < MRN_MAX_MATERIALS; i++) plan->target[i] = -1;
  int used[MRN_MAX_MATERIALS] = {0};
  for (int64_t p = 0; p < d->n; p++) used[d->material[p]] = 1;
  /* the additions cannot exceed the table: each is a distinct checkpoint material or the override */
  for (int i = 0; i < d->nmaterials; i++) {
    if (!used[i]) continue;
    if (override) {
      plan->target[i] = plan_material(plan, sim, override, 0);
    } else {
      plan->target[i] = plan_material(plan, sim, d->materials[i], 1);
    }
  }
  if (sim->nmaterials + plan->nadd > MRN_MAX_MATERIALS)
    return mrn_error_code(MRN_ERR_IO, "'%s': importing needs %d more material%s, the simulation has room for %d",
                          path, plan->nadd, plan->nadd == 1 ? "" : "s", MRN_MAX_MATERIALS - sim->nmaterials);
  return MRN_OK;
}

static int check_landing(const mrn_sim *sim, const ck_data *d, const double offset[3], const char *path) {
  const double *x = ck_field(d, "x");
  const mrn_grid *g = &sim->grid;
  for (int64_t p = 0; p < d->n; p++) {
    double y[3];
    for (int k = 0; k < 3; k++) y[k] = x[3 * p + k] + (k < d->dim ? offset[k] : 0.0);
    if (mrn_grid_contains(g, y)) continue;
    char box[160];
    int used = snprintf(box, sizeof box, "[%g, %g] x [%g, %g]", g->origin[0], g->origin[0] + g->size[0],
                        g->origin[1], g->origin[1] + g->size[1]);
    if (g->dim == 3)
      snprintf(box + used, sizeof box - (size_t)used, " x [%g, %g]", g->origin[2], g->origin[2] + g->size[2]);
    return mrn_error_code(MRN_ERR_IO,
                          "'%s': particle %lld (id %lld) would land at (%g, %g, %g), outside the grid %s",
                          path, (long long)p, (long long)d->id[p], y[0], y[1], y[2], box);
  }
  return MRN_OK;
}

/* copy one imported particle q of the checkpoint to slot i of the target */
static void import_one(mrn_sim *sim, const ck_data *d, const import_plan *plan, const double offset[3],
                       size_t i, int64_t q) {
  mrn_particles *ps = &sim->particles;
  for (int k = 0; k < mrn_particle_field_count(); k++) {
    const mrn_particle_field_info *f = mrn_particle_field_at(k);
    mrn_particle_field_import(ps, f, i, 1, d->field[k] + q * f->ncomp);
  }
  for (int k = 0; k < d->dim && offset; k++) {
    ps->x[3 * i + k] += offset[k];
    ps->x0[3 * i + k] += offset[k];
  }
  int target = plan->target[d->material[q]];
  ps->material[i] = target;
  ps->id[i] = ps->next_id++;
  /* the deck's registered fields start at their initial values (a checkpoint's own are not carried over) */
  for (int f = 0; f < ps->nuser; f++)
    for (int k = 0; k < ps->user_fields[f].ncomp; k++)
      ps->user[i * ps->user_stride + ps->user_fields[f].offset + k] = ps->user_fields[f].init;
  if (!ps->state_stride) return;
  /* history variables belong to a model: they carry over only to the same model */
  double *state = ps->state + i * (size_t)ps->state_stride;
  memset(state, 0, sizeof(double) * (size_t)ps->state_stride);
  const mrn_material_type *from = d->materials[d->material[q]]->type;
  if (sim->materials[target]->type == from && from->nstate > 0)
    memcpy(state, d->state + q * d->state_stride, sizeof(double) * (size_t)from->nstate);
}

static int import_data(mrn_sim *sim, const ck_data *d, mrn_material *override, const double offset[3],
                       const char *path, long *count) {
  if (d->dim != sim->dim)
    return mrn_error_code(MRN_ERR_IO, "'%s': the checkpoint is %dD but the simulation is %dD", path, d->dim,
                          sim->dim);
  static const double no_offset[3] = {0, 0, 0};
  for (int k = 0; k < 3 && offset; k++)
    if (!isfinite(offset[k]))
      return mrn_error("import '%s': offset[%d] is %s, expected a finite number", path, k + 1, mrn_num(offset[k]).s);
  import_plan plan;
  int rc = check_landing(sim, d, offset ? offset : no_offset, path);
  if (!rc) rc = make_plan(&plan, sim, d, override, path);
  if (rc) return rc;
  /* set aside all memory first: once particles are copied nothing can fail */
  mrn_particles *ps = &sim->particles;
  if (mrn_particles_set_state_stride(ps, plan.stride) || mrn_particles_reserve(ps, ps->n + (size_t)d->n))
    return MRN_ERR;
  for (int k = 0; k < plan.nadd; k++)
    if (mrn_sim_add_material(sim, plan.add[k]) < 0) return MRN_ERR;
  size_t first = ps->n;
  for (int64_t q = 0; q < d->n; q++) import_one(sim, d, &plan, offset, first + (size_t)q, q);
  ps->n = first + (size_t)d->n;
  /* a simulation already spread keeps this process's share */
  if (sim->dist && mrn_dist_adopt(sim, first) != MRN_OK) return MRN_ERR;
  mrn_sim_particles_changed(sim);
  if (count) *count = (long)d->n;
  return MRN_OK;
}

int mrn_checkpoint_import(mrn_sim *sim, const char *path, mrn_material *override, const double offset[3],
                          long *count) {
  if (count) *count = 0;
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  ck_data d;
  int rc = ck_read(path, &d);
  mrn_h5_restore(&quiet);
  if (rc) return rc;
  rc = import_data(sim, &d, override, offset, path, count);
  ck_free(&d);
  return rc;
}
