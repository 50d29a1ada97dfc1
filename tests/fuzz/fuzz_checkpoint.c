/* moraine fuzzing: the checkpoint loader (mrn_checkpoint_load).
 *
 * An input is one of two things:
 *  - raw mode: bytes starting with 0x89 (the first byte of the HDF5
 *    signature) or 'm' (of the checksum table that starts a checkpoint) are
 *    written to a file as they are and loaded: truncated, bit-flipped and
 *    foreign files, with the checksum table's reader and the HDF5 library's
 *    own parser in the path;
 *  - edit mode: any other first byte picks a valid template checkpoint (2D or
 *    3D, built at start-up through the engine's C API) and the remaining bytes
 *    are a script of edits made through the HDF5 API: delete a dataset or an
 *    attribute, overwrite an element with NaN, infinity, a negative or huge
 *    value, replace an object by one of another type, rank or length, add a
 *    stray object. These files are well-formed HDF5 whose contents are
 *    hostile, which is what moraine's own validation has to catch. The
 *    edited file is then signed (its checksum table written anew,
 *    mrn_checkpoint_sign) so that the edits get past the checksums to that
 *    validation; with bit 0x40 of the first byte set it is not, and the
 *    checksums refuse it.
 * Either way the loader must refuse with a message or accept, and an accepted
 * file must give a simulation that can be freed; a crash, a hang or a
 * sanitizer report is a finding. */
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/error.h"
#include "io/checkpoint.h"
#include "particles/region.h"
#include "solver/simulation.h"

#include "fuzz_common.h"

static char workdir[64];
static char template_path[2][128];
static char case_path[128];

/* ---- the templates -------------------------------------------------------------- */

static mrn_material *template_material(const mrn_material_type *type) {
  mrn_material *m = mrn_material_new(type);
  mrn_material_set(m, "density", 2000);
  mrn_material_set(m, "E", 1e6);
  mrn_material_set(m, "nu", 0.3);
  if (type == &mrn_material_mohr_coulomb) {
    mrn_material_set(m, "phi", 20);
    mrn_material_set(m, "cohesion", 50);
  }
  if (mrn_material_prepare(m) != MRN_OK) fuzz_die("template material: %s", mrn_error_message());
  return m;
}

/* two materials (one with history variables), a few steps under gravity */
static void write_template(int dim, const char *path) {
  mrn_sim_config cfg = {.dim = dim, .size = {0.4, 0.4, dim == 3 ? 0.4 : 0}, .cell = 0.1,
                        .shape = MRN_SHAPE_QUADRATIC_BSPLINE, .gravity = {0, dim == 2 ? -9.81 : 0, dim == 3 ? -9.81 : 0}};
  mrn_sim *sim = mrn_sim_new(&cfg);
  if (!sim) fuzz_die("template simulation: %s", mrn_error_message());
  const mrn_material_type *types[2] = {&mrn_material_mohr_coulomb, &mrn_material_linear_elastic};
  for (int k = 0; k < 2; k++) {
    mrn_material *m = template_material(types[k]);
    int index = mrn_sim_add_material(sim, m);
    mrn_material_unref(m);
    double lo[3] = {0.1 + 0.1 * k, 0.1, 0.1}, hi[3] = {0.2 + 0.1 * k, 0.2, 0.2};
    mrn_region *box = mrn_region_box(lo, hi);
    size_t first;
    long count;
    if (index < 0 || mrn_sim_seed(sim, box, index, 1, MRN_SEED_GAUSS, &first, &count) != MRN_OK)
      fuzz_die("template particles: %s", mrn_error_message());
    mrn_region_unref(box);
  }
  for (int s = 0; s < 3; s++)
    if (mrn_sim_step(sim) != MRN_OK) fuzz_die("template step: %s", mrn_error_message());
  if (mrn_checkpoint_save(sim, path) != MRN_OK) fuzz_die("template save: %s", mrn_error_message());
  mrn_sim_free(sim);
}

static void cleanup(void) {
  unlink(case_path);
  for (int k = 0; k < 2; k++) unlink(template_path[k]);
  rmdir(workdir);
  H5close(); /* HDF5's caches and free lists, so a leak check sees only real leaks */
}

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
  fuzz_make_workdir(workdir, sizeof workdir, "ckpt");
  for (int k = 0; k < 2; k++) {
    snprintf(template_path[k], sizeof template_path[k], "%s/template%dd.h5", workdir, k + 2);
    write_template(k + 2, template_path[k]);
  }
  snprintf(case_path, sizeof case_path, "%s/case.h5", workdir);
  atexit(cleanup);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  return 0;
}

/* ---- the edits ----------------------------------------------------------------- */

/* every dataset and attribute of the file, by path */
#define MAX_TARGETS 512
typedef struct target {
  char object[160]; /* the group or dataset */
  char attr[64];    /* "" for the object itself */
  int is_dataset;
} target;

typedef struct targets {
  target t[MAX_TARGETS];
  int n;
  const char *parent; /* the object whose attributes are being listed */
} targets;

static herr_t add_attr(hid_t loc, const char *name, const H5A_info_t *info, void *data) {
  (void)loc;
  (void)info;
  targets *ts = data;
  if (ts->n >= MAX_TARGETS) return 1;
  target *t = &ts->t[ts->n++];
  snprintf(t->object, sizeof t->object, "%s", ts->parent);
  snprintf(t->attr, sizeof t->attr, "%s", name);
  t->is_dataset = 0;
  return 0;
}

static herr_t add_object(hid_t root, const char *name, const H5O_info_t *info, void *data) {
  targets *ts = data;
  if (ts->n >= MAX_TARGETS) return 1;
  char path[160];
  snprintf(path, sizeof path, "/%s", strcmp(name, ".") ? name : "");
  if (info->type == H5O_TYPE_DATASET) {
    target *t = &ts->t[ts->n++];
    snprintf(t->object, sizeof t->object, "%s", path);
    t->attr[0] = '\0';
    t->is_dataset = 1;
  }
  hid_t obj = H5Oopen(root, path, H5P_DEFAULT);
  if (obj >= 0) {
    hsize_t idx = 0;
    ts->parent = path;
    H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_NATIVE, &idx, add_attr, ts);
    H5Oclose(obj);
  }
  return 0;
}

/* a hostile number: a code from the input selects one */
static double special_value(fuzz_bytes *in) {
  static const double table[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 3.0, 1e-300, 5e-324, 1e308, -1e308,
                                 2147483647.0, 2147483648.0, -2147483649.0, 9.3e18, -9.3e18, 64, 65, 1e6};
  unsigned code = fuzz_u8(in);
  int n = (int)(sizeof table / sizeof table[0]);
  if (code < (unsigned)n) return table[code];
  if (code == 250) return NAN;
  if (code == 251) return INFINITY;
  if (code == 252) return -INFINITY;
  if (code >= 240) { /* raw bits */
    uint64_t bits = 0;
    for (int i = 0; i < 8; i++) bits = bits << 8 | fuzz_u8(in);
    double v;
    memcpy(&v, &bits, sizeof v);
    return v;
  }
  return (double)(int)(code - 128);
}

static int64_t to_int64(double v) {
  if (!(v == v)) return INT64_MIN;
  if (v >= 9.2e18) return INT64_MAX;
  if (v <= -9.2e18) return INT64_MIN;
  return (int64_t)v;
}

/* overwrite one element of a numeric dataset or attribute (read, change, write back) */
static void edit_element(hid_t file, const target *t, fuzz_bytes *in) {
  hid_t obj = t->attr[0] ? H5Aopen_by_name(file, t->object, t->attr, H5P_DEFAULT, H5P_DEFAULT)
                         : H5Dopen2(file, t->object, H5P_DEFAULT);
  if (obj < 0) return;
  hid_t space = t->attr[0] ? H5Aget_space(obj) : H5Dget_space(obj);
  hid_t type = t->attr[0] ? H5Aget_type(obj) : H5Dget_type(obj);
  hssize_t n = H5Sget_simple_extent_npoints(space);
  H5T_class_t cls = H5Tget_class(type);
  if (n > 0 && n < 1000000 && (cls == H5T_FLOAT || cls == H5T_INTEGER)) {
    int is_float = cls == H5T_FLOAT;
    hid_t mem = is_float ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
    void *buf = calloc((size_t)n, 8);
    herr_t ok = t->attr[0] ? H5Aread(obj, mem, buf) : H5Dread(obj, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
    if (ok >= 0) {
      size_t i = (size_t)fuzz_u16(in) % (size_t)n;
      double v = special_value(in);
      if (is_float) ((double *)buf)[i] = v;
      else ((int64_t *)buf)[i] = to_int64(v);
      if (t->attr[0]) {
        /* an attribute is written anew rather than in place: HDF5 1.10 can
         * overrun its own buffer rewriting an attribute created in the same
         * session, and that is not what is being tested here */
        H5Aclose(obj);
        obj = H5I_INVALID_HID;
        hid_t parent = H5Oopen(file, t->object, H5P_DEFAULT);
        if (parent >= 0) {
          H5Adelete(parent, t->attr);
          hid_t a = H5Acreate2(parent, t->attr, type, space, H5P_DEFAULT, H5P_DEFAULT);
          if (a >= 0) {
            H5Awrite(a, mem, buf);
            H5Aclose(a);
          }
          H5Oclose(parent);
        }
      } else {
        H5Dwrite(obj, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
      }
    }
    free(buf);
  } else if (cls == H5T_STRING && t->attr[0]) {
    /* a string attribute: replace by bytes of the input (kind and model names) */
    H5Aclose(obj);
    obj = H5I_INVALID_HID;
    char text[33];
    size_t len = fuzz_u8(in) % 33;
    for (size_t i = 0; i < len; i++) text[i] = (char)fuzz_u8(in);
    hid_t parent = H5Oopen(file, t->object, H5P_DEFAULT);
    if (parent >= 0) {
      H5Adelete(parent, t->attr);
      hid_t st = H5Tcopy(H5T_C_S1);
      H5Tset_size(st, len ? len : 1);
      hid_t sc = H5Screate(H5S_SCALAR);
      hid_t a = H5Acreate2(parent, t->attr, st, sc, H5P_DEFAULT, H5P_DEFAULT);
      if (a >= 0) {
        H5Awrite(a, st, len ? text : "");
        H5Aclose(a);
      }
      H5Sclose(sc);
      H5Tclose(st);
      H5Oclose(parent);
    }
  }
  H5Tclose(type);
  H5Sclose(space);
  if (obj >= 0) {
    if (t->attr[0]) H5Aclose(obj);
    else H5Dclose(obj);
  }
}

/* a fresh object of a type, rank and shape chosen by the input, filled with one value */
static void replace_object(hid_t file, const target *t, fuzz_bytes *in, const char *new_name) {
  static const hid_t *types[] = {&H5T_NATIVE_DOUBLE_g, &H5T_NATIVE_INT64_g, &H5T_NATIVE_INT32_g,
                                 &H5T_NATIVE_UINT8_g, &H5T_NATIVE_FLOAT_g};
  hid_t type = *types[fuzz_u8(in) % 5];
  int rank = fuzz_u8(in) % 4;
  hsize_t dims[3] = {1, 1, 1}, total = 1;
  for (int r = 0; r < rank; r++) {
    unsigned d = fuzz_u8(in);
    dims[r] = d < 200 ? d % 16 : (hsize_t)(d - 199) * 1000; /* small, empty or biggish */
    total *= dims[r];
  }
  if (total > 200000) return;
  double v = special_value(in);
  hid_t space = rank ? H5Screate_simple(rank, dims, NULL) : H5Screate(H5S_SCALAR);
  double *buf = malloc((total ? total : 1) * sizeof *buf);
  for (hsize_t i = 0; i < total; i++) buf[i] = v + (double)(i % 3);
  const char *name = new_name ? new_name : (t->attr[0] ? t->attr : strrchr(t->object, '/') + 1);
  if (t->attr[0] || (new_name && !t->is_dataset)) {
    hid_t parent = H5Oopen(file, t->object, H5P_DEFAULT);
    if (parent >= 0) {
      if (!new_name) H5Adelete(parent, name);
      hid_t a = H5Acreate2(parent, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
      if (a >= 0) {
        H5Awrite(a, H5T_NATIVE_DOUBLE, buf);
        H5Aclose(a);
      }
      H5Oclose(parent);
    }
  } else if (t->is_dataset) {
    if (!new_name) H5Ldelete(file, t->object, H5P_DEFAULT);
    char path[200];
    snprintf(path, sizeof path, "%s", t->object);
    if (new_name) { /* a sibling of the dataset */
      char *slash = strrchr(path, '/');
      snprintf(slash + 1, sizeof path - (size_t)(slash + 1 - path), "%s", new_name);
    }
    hid_t d = H5Dcreate2(file, path, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (d >= 0) {
      H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
      H5Dclose(d);
    }
  }
  free(buf);
  H5Sclose(space);
}

static void delete_target(hid_t file, const target *t) {
  if (t->attr[0]) H5Adelete_by_name(file, t->object, t->attr, H5P_DEFAULT);
  else if (strcmp(t->object, "/")) H5Ldelete(file, t->object, H5P_DEFAULT);
}

/* delete a whole group (a material, a boundary face, the particles) */
static void delete_parent(hid_t file, const target *t) {
  char path[160];
  snprintf(path, sizeof path, "%s", t->object);
  char *slash = strrchr(path, '/');
  if (t->attr[0] || !slash) { /* the attribute's owner */
    if (strcmp(path, "/")) H5Ldelete(file, path, H5P_DEFAULT);
    return;
  }
  *slash = '\0';
  if (path[0]) H5Ldelete(file, path, H5P_DEFAULT);
}

static void apply_edits(const char *path, fuzz_bytes *in) {
  static int trace = -1; /* MORAINE_FUZZ_TRACE=1 lists the edits */
  if (trace < 0) trace = getenv("MORAINE_FUZZ_TRACE") != NULL;
  hid_t file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  if (file < 0) return;
  static targets ts;
  for (int edits = 0; edits < 16 && fuzz_left(in) >= 2; edits++) {
    ts.n = 0;
    H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_NATIVE, add_object, &ts, H5O_INFO_BASIC);
    if (ts.n == 0) break;
    unsigned op = fuzz_u8(in) % 6;
    const target *t = &ts.t[fuzz_u16(in) % (unsigned)ts.n];
    if (trace) fprintf(stderr, "  edit %u on %s%s%s\n", op, t->object, t->attr[0] ? " @" : "", t->attr);
    switch (op) {
    case 0: edit_element(file, t, in); break;
    case 1: edit_element(file, t, in); break;
    case 2: replace_object(file, t, in, NULL); break;
    case 3: delete_target(file, t); break;
    case 4: replace_object(file, t, in, "stray"); break;
    case 5: delete_parent(file, t); break;
    }
  }
  H5Fclose(file);
}

/* ---- one input ----------------------------------------------------------------- */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size == 0) return 0;
  if (data[0] == 0x89 || data[0] == 'm') {
    fuzz_write_file(case_path, data, size);
  } else {
    fuzz_bytes in = {data + 1, size - 1};
    fuzz_copy_file(template_path[data[0] & 1], case_path);
    apply_edits(case_path, &in);
    if (!(data[0] & 0x40)) mrn_checkpoint_sign(case_path); /* may fail on what the edits left: then unsigned */
  }
  mrn_checkpoint_info info;
  mrn_sim *sim = mrn_checkpoint_load_info(case_path, &info);
  if (sim) {
    /* an accepted file is a usable simulation: it must take a step (which
     * may stop with a diagnosis) and free cleanly */
    mrn_sim_step(sim);
    mrn_sim_free(sim);
  } else if (!mrn_error_message()[0]) {
    fuzz_die("the loader refused a file without a message");
  }
  return 0;
}
