#include "io/output.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/comm.h"
#include "core/error.h"
#include "core/spec.h"
#include "grid/wall.h"
#include "io/atomic_file.h"
#include "io/output_internal.h"
#include "io/particle_fields.h"
#include "io/summary.h"
#include "io/vti.h"
#include "io/vtkhdf.h"
#include "solver/dist.h"
#include "solver/simulation.h"

static char *dup_or_null(const char *s) { return s ? strdup(s) : NULL; }

void mrn_output_init(mrn_output *o, const char *dir) {
  memset(o, 0, sizeof *o);
  o->dir = strdup(dir ? dir : ".");
  o->vtk_last_step = -1;
  o->csv_every = 10;
  o->csv_last_step = -1;
  o->csv_fd = -1;
  o->encoding = MRN_VTK_BINARY;
}

static int close_csv(mrn_output *o);

int mrn_output_free(mrn_output *o) {
  int rc = close_csv(o);
  /* the series' last rewrite: rows appended since the one before */
  int src = o->series ? mrn_series_close(o->series) : MRN_OK;
  if (rc == MRN_OK) rc = src;
  free(o->dir);
  free(o->vtk_name);
  free(o->csv_name);
  if (o->pvd.path) mrn_pvd_free(&o->pvd);
  if (o->grid_pvd.path) mrn_pvd_free(&o->grid_pvd);
  free(o->series_name);
  free(o->run_name);
  free(o->deck_path);
  free(o->deck_text);
  free(o->series_file);
  memset(o, 0, sizeof *o);
  o->csv_fd = -1;
  return rc;
}

/* numbering from 000000 and new collections, from the next snapshot on */
static void restart_vtk(mrn_output *o) {
  if (o->pvd.path) mrn_pvd_free(&o->pvd);
  memset(&o->pvd, 0, sizeof o->pvd);
  if (o->grid_pvd.path) mrn_pvd_free(&o->grid_pvd);
  memset(&o->grid_pvd, 0, sizeof o->grid_pvd);
  o->vtk_count = 0;
  o->vtk_last_step = -1;
}

int mrn_output_set_vtk(mrn_output *o, const char *name, double every_time, long every_steps) {
  int renamed = !name || !o->vtk_name || strcmp(name, o->vtk_name) != 0;
  if (renamed) {
    free(o->vtk_name);
    o->vtk_name = dup_or_null(name);
    restart_vtk(o);
  }
  o->vtk_every_time = every_time;
  o->vtk_every_steps = every_steps;
  o->vtk_next_time = -HUGE_VAL; /* the first check writes the current state */
  return MRN_OK;
}

void mrn_output_set_vtkhdf(mrn_output *o, int vtkhdf) {
  if (!vtkhdf == !o->vtkhdf) return;
  o->vtkhdf = vtkhdf != 0;
  restart_vtk(o);
  o->vtk_next_time = -HUGE_VAL;
}

int mrn_output_set_csv(mrn_output *o, const char *name, long every) {
  int rc = MRN_OK;
  if (o->csv_fd >= 0 && (!name || !o->csv_name || strcmp(name, o->csv_name) != 0)) rc = close_csv(o);
  free(o->csv_name);
  o->csv_name = dup_or_null(name);
  if (every > 0) o->csv_every = every;
  return rc;
}

static int csv_seen_before(const char *path);

int mrn_output_set_series(mrn_output *o, const char *name) {
  int rc = MRN_OK;
  if (o->series && (!name || !o->series_name || strcmp(name, o->series_name) != 0)) {
    rc = mrn_series_close(o->series);
    o->series = NULL;
  }
  free(o->series_name);
  o->series_name = dup_or_null(name);
  return rc;
}

/* HDF5 series cannot be appended to by a second writer like the CSV: a second
 * simulation of the deck naming the same file gets NAME_2.h5, NAME_3.h5, ... */
static char *unused_series_path(mrn_output *o) {
  char *path = mrn_path_join(o->dir, o->series_name);
  for (int k = 2; csv_seen_before(path) && k < 1000; k++) {
    free(path);
    char name[512];
    const char *dot = strrchr(o->series_name, '.');
    int stem = dot ? (int)(dot - o->series_name) : (int)strlen(o->series_name);
    snprintf(name, sizeof name, "%.*s_%d%s", stem, o->series_name, k, dot ? dot : "");
    path = mrn_path_join(o->dir, name);
  }
  return path;
}

/* the series of a `dim`-dimensional simulation, its columns declared */
static int open_series(mrn_output *o, int dim) {
  char *path = unused_series_path(o);
  int rc = mrn_series_create(&o->series, path);
  if (rc == MRN_OK) {
    free(o->series_file);
    /* its name in the directory, as a checkpoint keeps it */
    size_t dlen = strlen(o->dir);
    const char *rel = path;
    if (dlen && strncmp(path, o->dir, dlen) == 0)
      for (rel = path + dlen; *rel == '/'; rel++) continue;
    o->series_file = strdup(rel);
    o->series_rows = 0;
  }
  free(path);
  if (rc != MRN_OK) return rc;
  rc = mrn_series_describe(o->series, o->run_name, o->deck_path, o->deck_text);
  if (rc == MRN_OK) rc = mrn_series_add_column(o->series, "dt", "s", "size of the last step");
  for (int i = 0; rc == MRN_OK && i < mrn_diagnostics_column_count(); i++)
    rc = mrn_series_add_column(o->series, mrn_diagnostics_column_name(i), mrn_diagnostics_column_unit_in(i, dim),
                               "diagnostics, as in the CSV");
  return rc;
}

int mrn_output_describe(mrn_output *o, const char *run_name, const char *deck_path, const char *deck_text) {
  free(o->run_name), free(o->deck_path), free(o->deck_text);
  o->run_name = dup_or_null(run_name), o->deck_path = dup_or_null(deck_path), o->deck_text = dup_or_null(deck_text);
  if ((run_name && !o->run_name) || (deck_path && !o->deck_path) || (deck_text && !o->deck_text))
    return mrn_error_code(MRN_ERR_IO, "cannot describe the run: out of memory");
  return o->series ? mrn_series_describe(o->series, run_name, deck_path, deck_text) : MRN_OK;
}

int mrn_output_record(mrn_output *o, int dim, const char *name, double value) {
  if (!o->series_name) return mrn_error("record: the simulation writes no HDF5 series (series = false)");
  if (!o->series && open_series(o, dim) != MRN_OK) return MRN_ERR_IO;
  return mrn_series_set(o->series, name, value);
}

/* a particle field the .vtp writer asks for a chunk of points at a time
 * (mrn_vtk_array.fill), so a snapshot holds no field whole in memory */
typedef struct field_source {
  const mrn_sim *sim;
  mrn_field_ref field;
} field_source;

static void fill_from_field(const void *ctx, size_t first, size_t count, void *out) {
  const field_source *src = ctx;
  mrn_field_fill_range(src->sim, &src->field, first, count, out);
}

/* OUTDIR/<vtk name>, the directories it names made and its .pvd started;
 * NULL (MRN_ERR_IO, message set) when a directory cannot be made */
static char *snapshot_base(mrn_output *o) {
  if (mrn_mkdir_p(o->dir) != MRN_OK) return NULL;
  char *base = mrn_path_join(o->dir, o->vtk_name);
  /* a series name may contain directories: make them too */
  char *slash = strrchr(base, '/');
  if (slash) {
    *slash = '\0';
    int rc = mrn_mkdir_p(base);
    *slash = '/';
    if (rc != MRN_OK) {
      free(base);
      return NULL;
    }
  }
  if (!o->pvd.path) {
    size_t len = strlen(base) + 16;
    char *pvd_path = malloc(len);
    snprintf(pvd_path, len, "%s%s", base, MRN_OUTPUT_COLLECTION(o));
    if (o->vtkhdf) mrn_file_series_init(&o->pvd, pvd_path);
    else mrn_pvd_init(&o->pvd, pvd_path);
    free(pvd_path);
  }
  return base;
}

/* the arrays of the fields the deck listed, every field when it listed none
 * (the built-in ones but those written on request, then those it
 * registered); an error names a field that is neither */
static int gather_fields(const mrn_output *o, const mrn_sim *sim, mrn_vtk_array *arrays, field_source *sources,
                         int *nf) {
  const int builtins = mrn_output_field_count();
  int count = o->nfields ? o->nfields : builtins + sim->particles.nuser;
  *nf = 0;
  for (int i = 0; i < count && *nf < MRN_OUTPUT_MAX_FIELDS; i++) {
    if (!o->nfields && i < builtins && mrn_output_field_at(i)->on_request) continue;
    const char *name = o->nfields      ? o->fields[i]
                       : i < builtins ? mrn_output_field_at(i)->name
                                      : sim->particles.user_fields[i - builtins].name;
    mrn_field_ref f;
    if (!mrn_field_lookup(sim, name, &f)) {
      const char *known[MRN_OUTPUT_MAX_FIELDS + MRN_USER_FIELDS_MAX + 1];
      int k = 0;
      for (const char *const *b = mrn_output_field_names(); *b; b++) known[k++] = *b;
      for (int u = 0; u < sim->particles.nuser; u++) known[k++] = sim->particles.user_fields[u].name;
      known[k] = NULL;
      return mrn_error("output field '%s' is neither a built-in particle field nor one registered with "
                       "sim:particle_field%s", name, mrn_hint(mrn_suggest_from(known, name)).s);
    }
    sources[*nf] = (field_source){sim, f};
    arrays[*nf] = (mrn_vtk_array){f.name, f.ncomp, f.type, NULL, fill_from_field, &sources[*nf]};
    (*nf)++;
  }
  return MRN_OK;
}

/* OUTDIR/<vtk name>_NNNNNN<suffix> of snapshot `count`, malloc'd */
static char *snapshot_path(const char *base, int count, const char *suffix) {
  size_t len = strlen(base) + strlen(suffix) + 32;
  char *path = malloc(len);
  if (path) snprintf(path, len, "%s_%06d%s", base, count, suffix);
  return path;
}

/* the name of a file in its directory, as a collection lists it */
static const char *file_part(const char *path) {
  const char *slash = strrchr(path, '/');
  return slash ? slash + 1 : path;
}

/* the nodal mass, velocity and force of the last step, beside the particles'
 * snapshot: <vtk>_grid_NNNNNN.vti in <vtk>_grid.pvd */
static int write_grid_snapshot(mrn_output *o, const mrn_sim *sim, const char *base) {
  const size_t len = strlen(base) + 16;
  char *grid_base = malloc(len);
  if (!grid_base) return mrn_error_code(MRN_ERR_IO, "cannot write a grid snapshot: out of memory");
  snprintf(grid_base, len, "%s_grid", base);
  char *grid_path = snapshot_path(grid_base, o->vtk_count, ".vti");
  if (!o->grid_pvd.path) {
    char *pvd_path = malloc(len);
    if (pvd_path) snprintf(pvd_path, len, "%s.pvd", grid_base);
    mrn_pvd_init(&o->grid_pvd, pvd_path); /* without a path, its mrn_pvd_add fails */
    free(pvd_path);
  }
  int rc = grid_path ? mrn_vti_write_grid(grid_path, &sim->grid, sim->time, o->encoding)
                     : mrn_error_code(MRN_ERR_IO, "cannot write a grid snapshot: out of memory");
  if (rc == MRN_OK) rc = mrn_pvd_add(&o->grid_pvd, sim->time, file_part(grid_path));
  free(grid_path);
  free(grid_base);
  return rc;
}

/* the same in a distributed run whose particles were not gathered: each node
 * row from the process that owns it, gathered on process 0 for the file, so
 * that the file is the one a single process writes; agreed */
static int write_grid_gathered(mrn_output *o, const mrn_sim *sim, const char *base) {
  int rc = mrn_dist_gather_grid_begin(sim);
  if (rc == MRN_OK) rc = write_grid_snapshot(o, sim, base);
  mrn_dist_gather_grid_end(sim);
  return mrn_dist_agree(sim, rc);
}

/* every particle in one file: this process's own, or, in a distributed run,
 * every process's gathered on process 0 (mrn_dist_gather_begin) */
static int write_whole(mrn_output *o, const mrn_sim *sim, const char *base, const mrn_vtk_array *arrays, int nf,
                       const mrn_vtp_options *form) {
  char *path = snapshot_path(base, o->vtk_count, MRN_OUTPUT_SNAPSHOT_EXT(o));
  if (!path) return mrn_error_code(MRN_ERR_IO, "cannot write a snapshot: out of memory");
  int rc = o->vtkhdf ? mrn_vtkhdf_write(path, sim->particles.n, sim->particles.x, arrays, nf, form)
                     : mrn_vtp_write_with(path, sim->particles.n, sim->particles.x, arrays, nf, form);
  if (rc == MRN_OK) rc = mrn_pvd_add(&o->pvd, sim->time, file_part(path));
  free(path);
  return rc;
}

/* the paths of the pieces of snapshot `count`, <base>_NNNNNN_p<rank>.vtp for
 * each of `size` processes, and their names in their directory (names[r]
 * points into paths[r]); NULL when out of memory */
static char **piece_paths(const char *base, int count, int size, const char ***names) {
  char **paths = calloc((size_t)size, sizeof *paths + sizeof **names);
  if (!paths) return NULL;
  *names = (const char **)(paths + size);
  for (int r = 0; r < size; r++) {
    char suffix[32];
    snprintf(suffix, sizeof suffix, "_p%d.vtp", r);
    if (!(paths[r] = snapshot_path(base, count, suffix))) {
      for (int k = 0; k < r; k++) free(paths[k]);
      free(paths);
      return NULL;
    }
    (*names)[r] = file_part(paths[r]);
  }
  return paths;
}

/* This process's particles as its piece of the snapshot, then, once every
 * process's piece is complete, the .pvtp that lists them (written by process
 * 0) entered in the .pvd: a reader never sees a .pvtp whose pieces are
 * missing. A snapshot that fails on any process leaves neither its .pvtp
 * nor its pieces. `rc`: this process's outcome so far; the result is agreed. */
static int write_pieces(mrn_output *o, const mrn_sim *sim, const char *base, const mrn_vtk_array *arrays, int nf,
                        const mrn_vtp_options *form, int rc) {
  const int size = sim->dist->size, rank = sim->dist->rank;
  const char **names = NULL;
  char **paths = rc == MRN_OK ? piece_paths(base, o->vtk_count, size, &names) : NULL;
  char *pvtp = rc == MRN_OK ? snapshot_path(base, o->vtk_count, ".pvtp") : NULL;
  if (rc == MRN_OK && (!paths || !pvtp)) rc = mrn_error_code(MRN_ERR_IO, "cannot write a snapshot: out of memory");
  int wrote = 0;
  if (rc == MRN_OK) {
    rc = mrn_vtp_write_with(paths[rank], sim->particles.n, sim->particles.x, arrays, nf, form);
    wrote = rc == MRN_OK;
  }
  rc = mrn_dist_agree(sim, rc); /* every piece complete before the .pvtp names it */
  if (rc == MRN_OK) {
    /* the run's summary (process 0's) counts every process's piece */
    for (int r = 0; r < size && mrn_comm_writes(); r++) mrn_summary_note_file(paths[r]);
    rc = mrn_pvtp_write(pvtp, arrays, nf, form, names, size);
    if (rc == MRN_OK && (rc = mrn_pvd_add(&o->pvd, sim->time, file_part(pvtp))) != MRN_OK && mrn_comm_writes())
      unlink(pvtp); /* not listed: gone before its pieces are */
  }
  rc = mrn_dist_agree(sim, rc);
  if (rc != MRN_OK && wrote) unlink(paths[rank]);
  for (int r = 0; paths && r < size; r++) free(paths[r]);
  free(paths);
  free(pvtp);
  return rc;
}

/* Snapshot number vtk_count: the particles (a piece per process, or whole)
 * and, if asked, the grid. A distributed run's processes all take part;
 * the result is agreed when `pieces` is set (mrn_output_write_vtk agrees
 * on a whole one). */
static int write_snapshot(mrn_output *o, const mrn_sim *sim, int pieces) {
  char *base = snapshot_base(o);
  int nf = 0;
  mrn_vtk_array arrays[MRN_OUTPUT_MAX_FIELDS];
  field_source sources[MRN_OUTPUT_MAX_FIELDS]; /* made a chunk at a time as the file is written */
  int rc = base ? gather_fields(o, sim, arrays, sources, &nf) : MRN_ERR_IO;
  /* the model time in the file too, for readers given the file alone */
  const mrn_vtp_options form = {o->encoding, o->vtk_compress, o->vtk_float32, 1, sim->time, pieces};
  if (pieces) rc = write_pieces(o, sim, base, arrays, nf, &form, rc);
  else if (rc == MRN_OK) rc = write_whole(o, sim, base, arrays, nf, &form);
  /* a whole snapshot's grid was gathered with its particles */
  if (rc == MRN_OK && o->grid_vtk) rc = pieces ? write_grid_gathered(o, sim, base) : write_grid_snapshot(o, sim, base);
  if (rc == MRN_OK) {
    o->vtk_count++;
    o->vtk_last_step = sim->step;
  }
  free(base);
  return rc;
}

/* In a distributed run each process writes its particles as a piece of the
 * snapshot, listed by a .pvtp, unless the deck asked for one file (gather)
 * or the snapshots are VTKHDF files: then process 0 writes the snapshot
 * with every particle gathered to it (solver/dist.h), and the others go
 * through the same steps into no file, so that every process keeps the
 * same series. */
int mrn_output_write_vtk(mrn_output *o, const mrn_sim *sim) {
  if (!o->vtk_name) return MRN_OK;
  if (sim->dist && !o->vtkhdf && !o->vtk_gather) return write_snapshot(o, sim, 1);
  int rc = mrn_dist_gather_begin(sim);
  if (rc == MRN_OK) rc = write_snapshot(o, sim, 0);
  mrn_dist_gather_end(sim);
  return mrn_dist_agree(sim, rc);
}

int mrn_output_maybe_vtk(mrn_output *o, const mrn_sim *sim) {
  if (!o->vtk_name || o->vtk_last_step == sim->step) return MRN_OK;
  int due = 0;
  if (o->vtk_every_steps > 0 && (o->vtk_last_step < 0 || sim->step - o->vtk_last_step >= o->vtk_every_steps)) due = 1;
  if (o->vtk_every_time > 0) {
    /* a small tolerance so round-off in the accumulated time does not skip a frame */
    double tol = 1e-9 * o->vtk_every_time;
    if (sim->time >= o->vtk_next_time - tol) {
      due = 1;
      if (o->vtk_next_time == -HUGE_VAL) o->vtk_next_time = sim->time;
      while (o->vtk_next_time <= sim->time + tol) o->vtk_next_time += o->vtk_every_time;
    }
  }
  if (o->vtk_every_time <= 0 && o->vtk_every_steps <= 0 && o->vtk_last_step < 0) due = 1;
  return due ? mrn_output_write_vtk(o, sim) : MRN_OK;
}

/* CSV files opened in this process: a second simulation writing to the same
 * file (a settling run and the collapse that follows it, say) appends its rows
 * under the same header instead of truncating the first one's */
static mrn_path_set csv_seen;

static int csv_seen_before(const char *path) {
  if (mrn_path_set_has(&csv_seen, path)) return 1;
  mrn_path_set_add(&csv_seen, path);
  return 0;
}

void mrn_output_mark_written(const char *path) { mrn_path_set_add(&csv_seen, path); }

int mrn_path_set_has(const mrn_path_set *set, const char *path) {
  for (int i = 0; i < set->n; i++)
    if (strcmp(set->p[i], path) == 0) return 1;
  return 0;
}

void mrn_path_set_add(mrn_path_set *set, const char *path) {
  if (set->n < MRN_PATH_SET_MAX && !mrn_path_set_has(set, path)) set->p[set->n++] = strdup(path);
}

void mrn_path_set_clear(mrn_path_set *set) {
  for (int i = 0; i < set->n; i++) free(set->p[i]);
  set->n = 0;
}

void mrn_output_forget_files(void) {
  mrn_path_set_clear(&csv_seen);
  mrn_output_forget_claims();
}

/* ---- the CSV ------------------------------------------------------------ */

/* The CSV is appended to with write(2), a row at a time, so what the file
 * holds is known to the byte: csv_size, the end of its last whole row. */

static int csv_error(const mrn_output *o, int err, const char *what) {
  return mrn_error_code(MRN_ERR_IO, "cannot write '%s': %s%s", o->csv_path, strerror(err), what);
}

/* `len` bytes at the end of the CSV, whole or not at all: a write cut short
 * (a disk filling up within it) is taken back by truncating the file to its
 * length before, so the file never ends in part of a row */
static int csv_append(mrn_output *o, const char *text, size_t len) {
  for (size_t done = 0; done < len;) {
    ssize_t n = write(o->csv_fd, text + done, len - done);
    if (n > 0) {
      done += (size_t)n;
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    int err = n < 0 ? errno : EIO;
    if (ftruncate(o->csv_fd, o->csv_size) != 0)
      return csv_error(o, err, " (and the part of a row written could not be removed)");
    return csv_error(o, err, "");
  }
  o->csv_size += (off_t)len;
  return MRN_OK;
}

/* some file systems cannot sync (EINVAL); the rows are still written */
static int sync_csv(const mrn_output *o) {
  if (fsync(o->csv_fd) == 0 || errno == EINVAL || errno == ENOTSUP) return MRN_OK;
  return csv_error(o, errno, "");
}

/* the rows on disk, then the file closed: a delayed write error shows in either */
static int close_csv(mrn_output *o) {
  int rc = MRN_OK;
  if (o->csv_fd >= 0) {
    rc = sync_csv(o);
    if (close(o->csv_fd) != 0 && rc == MRN_OK) rc = csv_error(o, errno, "");
  }
  o->csv_fd = -1;
  free(o->csv_path);
  o->csv_path = NULL;
  return rc;
}

/* the header, or nothing: a new file whose header cannot be written is removed */
/* ---- the walls' columns: wall.<name>.<what>, after the diagnostics ---- */

enum { WALL_COLUMNS_MAX = 8 };

/* the columns of wall i of a `dim`-dimensional simulation: names, units
 * and values (NULL: not wanted); returns their count */
static int wall_columns(const mrn_wall *w, int dim, const char **what, const char **unit, double *value) {
  static const char *const names2[] = {"force_x", "force_y", "moment", "work", "work_friction"};
  static const char *const names3[] = {"force_x", "force_y", "force_z", "moment_x", "moment_y", "moment_z", "work",
                                       "work_friction"};
  static const char *const units2[] = {"N/m", "N/m", "N m/m", "J/m", "J/m"};
  static const char *const units3[] = {"N", "N", "N", "N m", "N m", "N m", "J", "J"};
  const double v2[] = {w->force[0], w->force[1], w->moment[2], w->work, w->work_friction};
  const double v3[] = {w->force[0], w->force[1], w->force[2], w->moment[0], w->moment[1], w->moment[2], w->work,
                       w->work_friction};
  const int n = dim == 2 ? 5 : 8;
  for (int k = 0; k < n; k++) {
    if (what) what[k] = dim == 2 ? names2[k] : names3[k];
    if (unit) unit[k] = dim == 2 ? units2[k] : units3[k];
    if (value) value[k] = dim == 2 ? v2[k] : v3[k];
  }
  return n;
}

static int wall_count(const mrn_sim *sim) { return sim->boundary.walls ? sim->boundary.walls->count : 0; }

/* the walls' values into the series' staged row, declaring their columns */
static int series_walls(mrn_series *s, const mrn_sim *sim) {
  int rc = MRN_OK;
  for (int i = 0; rc == MRN_OK && i < wall_count(sim); i++) {
    const mrn_wall *w = &sim->boundary.walls->wall[i];
    const char *what[WALL_COLUMNS_MAX], *unit[WALL_COLUMNS_MAX];
    double value[WALL_COLUMNS_MAX];
    const int n = wall_columns(w, sim->dim, what, unit, value);
    for (int k = 0; rc == MRN_OK && k < n; k++) {
      char name[MRN_WALL_NAME_MAX + 32];
      snprintf(name, sizeof name, "wall.%s.%s", w->spec.name, what[k]);
      rc = mrn_series_add_column(s, name, unit[k], "a rigid wall's reaction (last step) or work (accumulated)");
      if (rc == MRN_OK) rc = mrn_series_set(s, name, value[k]);
    }
  }
  return rc;
}

static int csv_header(mrn_output *o, const mrn_sim *sim) {
  char header[4096];
  size_t len = (size_t)snprintf(header, sizeof header, "step,time,dt");
  for (int i = 0; i < mrn_diagnostics_column_count() && len < sizeof header; i++)
    len += (size_t)snprintf(header + len, sizeof header - len, ",%s", mrn_diagnostics_column_name(i));
  for (int i = 0; i < wall_count(sim) && len < sizeof header; i++) {
    const char *what[WALL_COLUMNS_MAX];
    const int n = wall_columns(&sim->boundary.walls->wall[i], sim->dim, what, NULL, NULL);
    for (int k = 0; k < n && len < sizeof header; k++)
      len += (size_t)snprintf(header + len, sizeof header - len, ",wall.%s.%s", sim->boundary.walls->wall[i].spec.name,
                              what[k]);
  }
  if (len + 1 >= sizeof header) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': header too long", o->csv_path);
  header[len++] = '\n';
  int rc = csv_append(o, header, len);
  if (rc != MRN_OK) unlink(o->csv_path);
  return rc;
}

static int open_csv(mrn_output *o, const mrn_sim *sim) {
  char *path = mrn_path_join(o->dir, o->csv_name);
  char *slash = strrchr(path, '/');
  if (slash) { /* the output directory and any directory in the file name */
    *slash = '\0';
    int rc = mrn_mkdir_p(path);
    *slash = '/';
    if (rc != MRN_OK) {
      free(path);
      return MRN_ERR_IO;
    }
  }
  int append = csv_seen_before(path);
  /* O_APPEND: every row lands at the end, also after a row taken back */
  /* process 0 writes the rows of a distributed run */
  o->csv_fd = open(mrn_comm_writes() ? path : "/dev/null",
                   O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | (append ? 0 : O_TRUNC), 0666);
  o->csv_path = path;
  if (o->csv_fd < 0) {
    int rc = csv_error(o, errno, "");
    close_csv(o);
    return rc;
  }
  mrn_summary_note_file(path);
  o->csv_size = append ? lseek(o->csv_fd, 0, SEEK_END) : 0;
  int rc = o->csv_size < 0 ? csv_error(o, errno, "") : append ? MRN_OK : csv_header(o, sim);
  if (rc != MRN_OK) close_csv(o);
  return rc;
}

int mrn_output_maybe_csv(mrn_output *o, const mrn_sim *sim, const mrn_diagnostics *d, int force) {
  if (!o->csv_name && !o->series_name) return MRN_OK;
  if (!force && (o->csv_every <= 0 || sim->step % o->csv_every != 0)) return MRN_OK;
  if (sim->step == o->csv_last_step) return MRN_OK; /* a run continuing from here */
  double values[64];
  mrn_diagnostics_values(d, values);
  if (o->series_name) {
    if (!o->series && open_series(o, sim->dim) != MRN_OK) return MRN_ERR_IO;
    int rc = mrn_series_set_at(o->series, 0, sim->dt);
    for (int i = 0; rc == MRN_OK && i < mrn_diagnostics_column_count(); i++)
      rc = mrn_series_set_at(o->series, i + 1, values[i]);
    if (rc == MRN_OK) rc = series_walls(o->series, sim);
    if (rc == MRN_OK) rc = mrn_series_append(o->series, sim->step, sim->time);
    if (rc != MRN_OK) return rc;
    o->series_rows++;
  }
  if (!o->csv_name) {
    o->csv_last_step = sim->step;
    return MRN_OK;
  }
  if (o->csv_fd < 0 && open_csv(o, sim) != MRN_OK) return MRN_ERR_IO;
  /* the row is formatted first and handed over in one write: a kill never
   * leaves part of a row in the file, and a full disk is taken back */
  const size_t cap = (size_t)(64 + wall_count(sim) * WALL_COLUMNS_MAX) * 26 + 64;
  char *row = malloc(cap);
  if (!row) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", o->csv_path);
  int len = snprintf(row, cap, "%ld,%.17g,%.17g", sim->step, sim->time, sim->dt);
  for (int i = 0; i < mrn_diagnostics_column_count(); i++) len += snprintf(row + len, cap - (size_t)len, ",%.17g", values[i]);
  for (int i = 0; i < wall_count(sim); i++) {
    double wv[WALL_COLUMNS_MAX];
    const int n = wall_columns(&sim->boundary.walls->wall[i], sim->dim, NULL, NULL, wv);
    for (int k = 0; k < n; k++) len += snprintf(row + len, cap - (size_t)len, ",%.17g", wv[k]);
  }
  len += snprintf(row + len, cap - (size_t)len, "\n");
  int rc = csv_append(o, row, (size_t)len);
  free(row);
  if (rc == MRN_OK) o->csv_last_step = sim->step;
  return rc;
}

int mrn_output_flush(mrn_output *o) {
  int rc = o->series ? mrn_series_flush(o->series) : MRN_OK;
  if (rc == MRN_OK && o->csv_fd >= 0) rc = sync_csv(o);
  return rc;
}

/* ---- observing a run (solver/run.h) -------------------------------------- */

static int observe_snapshot(void *ctx, const mrn_sim *sim, int *wrote) {
  mrn_output *o = ctx;
  const int before = o->vtk_count;
  int rc = mrn_output_maybe_vtk(o, sim);
  *wrote = o->vtk_count != before;
  return rc;
}

/* a row of the starting state, then on the CSV's cadence, and of the state a
 * run ends on unless the cadence has just written it */
static int observe_row_due(void *ctx, const mrn_sim *sim, mrn_run_moment when) {
  const mrn_output *o = ctx;
  if (!o->csv_name && !o->series_name) return 0;
  const int on_cadence = o->csv_every > 0 && sim->step % o->csv_every == 0;
  if (when == MRN_RUN_START) return 1;
  return when == MRN_RUN_STEP ? on_cadence : o->csv_every > 0 && !on_cadence;
}

static int observe_row(void *ctx, const mrn_sim *sim, const mrn_diagnostics *d) {
  return mrn_output_maybe_csv(ctx, sim, d, 1);
}

mrn_run_observer mrn_output_observer(mrn_output *o) {
  return (mrn_run_observer){observe_snapshot, observe_row_due, observe_row, o};
}
