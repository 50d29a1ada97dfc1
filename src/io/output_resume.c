/* moraine: an output's settings in a checkpoint, continuing its files on a
 * resume, and refusing to write over another run's files. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/comm.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/output.h"
#include "io/output_internal.h"

#define PENDING "output.series_next."

/* ---- the settings in a stash ------------------------------------------------ */

static void stash_encoding(mrn_stash *s, mrn_output *o) {
  static const char *const names[] = {"binary", "ascii", NULL};
  char *name = strdup(names[o->encoding == MRN_VTK_ASCII]);
  mrn_stash_text(s, "output.vtk_format", &name);
  if (s->loading && name) o->encoding = strcmp(name, "ascii") == 0 ? MRN_VTK_ASCII : MRN_VTK_BINARY;
  free(name);
}

/* the deck's field list, as one text "a,b,c" ("" for every field) */
static void stash_fields(mrn_stash *s, mrn_output *o) {
  char joined[MRN_OUTPUT_MAX_FIELDS * 49] = "";
  for (int i = 0; i < o->nfields; i++) {
    if (i) strcat(joined, ",");
    strcat(joined, o->fields[i]);
  }
  char *text = strdup(joined);
  mrn_stash_text(s, "output.vtk_fields", &text);
  if (s->loading) {
    o->nfields = 0;
    for (char *f = text ? strtok(text, ",") : NULL; f && o->nfields < MRN_OUTPUT_MAX_FIELDS; f = strtok(NULL, ","))
      snprintf(o->fields[o->nfields++], sizeof o->fields[0], "%s", f);
  }
  free(text);
}

void mrn_output_stash(mrn_output *o, mrn_stash *s) {
  /* the settings, as the deck gave them */
  mrn_stash_text(s, "output.vtk", &o->vtk_name);
  mrn_stash_real(s, "output.vtk_every", &o->vtk_every_time);
  mrn_stash_long(s, "output.vtk_every_steps", &o->vtk_every_steps);
  mrn_stash_int(s, "output.vtk_grid", &o->grid_vtk);
  stash_encoding(s, o);
  mrn_stash_int(s, "output.vtk_compress", &o->vtk_compress);
  mrn_stash_int(s, "output.vtk_float32", &o->vtk_float32);
  mrn_stash_int(s, "output.vtkhdf", &o->vtkhdf);
  mrn_stash_int(s, "output.vtk_gather", &o->vtk_gather);
  stash_fields(s, o);
  mrn_stash_text(s, "output.diagnostics", &o->csv_name);
  mrn_stash_long(s, "output.diagnostics_every", &o->csv_every);
  mrn_stash_text(s, "output.series", &o->series_name);
  /* where the files stand */
  mrn_stash_int(s, "output.vtk_count", &o->vtk_count);
  mrn_stash_long(s, "output.vtk_last_step", &o->vtk_last_step);
  mrn_stash_real(s, "output.vtk_next_time", &o->vtk_next_time);
  mrn_stash_long(s, "output.diagnostics_last_step", &o->csv_last_step);
  long bytes = (long)o->csv_size;
  mrn_stash_long(s, "output.diagnostics_bytes", &bytes);
  o->csv_size = bytes;
  mrn_stash_text(s, "output.series_file", &o->series_file);
  mrn_stash_long(s, "output.series_rows", &o->series_rows);
  /* values recorded for the series' next row (sim:record), by column */
  for (int i = 0; !s->loading && i < mrn_series_column_count(o->series); i++) {
    double v = mrn_series_pending(o->series, i);
    char name[128];
    if (isnan(v) || snprintf(name, sizeof name, PENDING "%s", mrn_series_column_name(o->series, i)) >= 64) continue;
    mrn_stash_real(s, name, &v);
  }
}

/* ---- continuing the files ------------------------------------------------------ */

/* an entry added to the collection in memory only: mrn_pvd_add of the last
 * one rewrites the file with them all */
static int pvd_push(mrn_pvd *pvd, double time, const char *file) {
  if (pvd->count == pvd->cap) {
    int cap = pvd->cap ? 2 * pvd->cap : 16;
    double *times = realloc(pvd->times, (size_t)cap * sizeof *times);
    if (times) pvd->times = times;
    char **files = realloc(pvd->files, (size_t)cap * sizeof *files);
    if (files) pvd->files = files;
    if (!times || !files) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", pvd->path);
    pvd->cap = cap;
  }
  if (!(pvd->files[pvd->count] = strdup(file))) return mrn_error_code(MRN_ERR_IO, "cannot write '%s': out of memory", pvd->path);
  pvd->times[pvd->count++] = time;
  return MRN_OK;
}

/* the value of attribute `key` in one line of a .pvd ("" when absent), XML
 * entities decoded */
static void pvd_attr(const char *line, const char *key, char *out, size_t cap) {
  out[0] = '\0';
  char pattern[32];
  snprintf(pattern, sizeof pattern, " %s=\"", key);
  const char *p = strstr(line, pattern);
  if (!p) return;
  p += strlen(pattern);
  static const char *const ent[][2] = {{"&amp;", "&"}, {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}};
  size_t n = 0;
  while (*p && *p != '"' && n + 1 < cap) {
    int k = 0;
    while (k < 5 && strncmp(p, ent[k][0], strlen(ent[k][0])) != 0) k++;
    if (k < 5) out[n++] = ent[k][1][0], p += strlen(ent[k][0]);
    else out[n++] = *p++;
  }
  out[n] = '\0';
}

/* the value of "key": "..." in one line of a JSON file series ("" when
 * absent), the escapes of mrn_pvd's writer decoded */
static void json_attr(const char *line, const char *key, char *out, size_t cap) {
  out[0] = '\0';
  char pattern[32];
  snprintf(pattern, sizeof pattern, "\"%s\": \"", key);
  const char *p = strstr(line, pattern);
  if (!p) return;
  size_t n = 0;
  for (p += strlen(pattern); *p && *p != '"' && n + 1 < cap; p++) {
    if (*p == '\\' && p[1] == 'u') {
      out[n++] = (char)strtol((char[]){p[4], p[5], 0}, NULL, 16);
      p += 5;
    } else {
      if (*p == '\\' && p[1]) p++;
      out[n++] = *p;
    }
  }
  out[n] = '\0';
}

/* whether a line of the collection is an entry, and its file and time */
static int collection_entry(const mrn_pvd *pvd, const char *line, char *file, size_t cap, double *time) {
  char t[64];
  if (pvd->json) {
    const char *at = strstr(line, "\"time\": ");
    if (!strstr(line, "\"name\": ") || !at) return 0;
    json_attr(line, "name", file, cap);
    *time = strtod(at + strlen("\"time\": "), NULL);
    return 1;
  }
  if (!strstr(line, "<DataSet ")) return 0;
  pvd_attr(line, "timestep", t, sizeof t);
  pvd_attr(line, "file", file, cap);
  *time = strtod(t, NULL);
  return 1;
}

/* the snapshot `file` in `dir`; a .pvtp with its pieces FILE_p0.vtp,
 * FILE_p1.vtp, ... (io/output.h), the .pvtp first so that no reader finds
 * it without them */
static void remove_snapshot(const char *dir, const char *file) {
  char *path = mrn_path_join(dir, file);
  const size_t len = path ? strlen(path) : 0;
  if (!path || unlink(path) != 0 || len < 5 || strcmp(path + len - 5, ".pvtp") != 0) {
    free(path);
    return;
  }
  char *piece = malloc(len + 32);
  for (int r = 0; piece; r++) {
    snprintf(piece, len + 32, "%.*s_p%d.vtp", (int)(len - 5), path, r);
    if (unlink(piece) != 0) break; /* the pieces are numbered from 0 without a gap */
  }
  free(piece);
  free(path);
}

/* the collection at pvd->path, as written before: its first `keep` entries
 * stay (rewritten at once), the files of the others are removed */
static int resume_pvd(mrn_pvd *pvd, int keep) {
  FILE *f = fopen(pvd->path, "r");
  if (!f) return MRN_OK; /* none yet: it starts with the next snapshot */
  char line[8192], file[4096];
  double time;
  double last_time = 0;
  char *last_file = NULL;
  int index = 0, rc = MRN_OK;
  char *dir = strdup(pvd->path);
  char *slash = strrchr(dir, '/');
  if (slash) slash[1] = '\0';
  else dir[0] = '\0';
  while (rc == MRN_OK && fgets(line, sizeof line, f)) {
    if (!collection_entry(pvd, line, file, sizeof file, &time)) continue;
    if (index < keep - 1) {
      rc = pvd_push(pvd, time, file);
    } else if (index == keep - 1) {
      last_time = time;
      last_file = strdup(file);
    } else if (!strchr(file, '/')) { /* a snapshot written after the checkpoint */
      remove_snapshot(dir, file);
    }
    index++;
  }
  fclose(f);
  free(dir);
  if (rc == MRN_OK) rc = last_file ? mrn_pvd_add(pvd, last_time, last_file) : (unlink(pvd->path), MRN_OK);
  free(last_file);
  return rc;
}

/* OUTDIR/<vtk name><suffix>, malloc'd */
static char *vtk_path(const mrn_output *o, const char *suffix) {
  char *base = mrn_path_join(o->dir, o->vtk_name);
  size_t len = strlen(base) + strlen(suffix) + 1;
  char *path = malloc(len);
  snprintf(path, len, "%s%s", base, suffix);
  free(base);
  return path;
}

static int resume_snapshots(mrn_output *o) {
  if (!o->vtk_name) return MRN_OK;
  char *pvd = vtk_path(o, MRN_OUTPUT_COLLECTION(o)), *grid_pvd = vtk_path(o, "_grid.pvd");
  if (o->vtkhdf) mrn_file_series_init(&o->pvd, pvd);
  else mrn_pvd_init(&o->pvd, pvd);
  int rc = resume_pvd(&o->pvd, o->vtk_count);
  if (rc == MRN_OK && o->grid_vtk) {
    mrn_pvd_init(&o->grid_pvd, grid_pvd);
    rc = resume_pvd(&o->grid_pvd, o->vtk_count);
  }
  free(pvd);
  free(grid_pvd);
  return rc;
}

/* the CSV cut to the bytes of the rows written before the checkpoint, open
 * for appending; a missing file (or none written yet) starts anew */
static int resume_csv(mrn_output *o) {
  if (!o->csv_name || o->csv_size <= 0) return MRN_OK;
  char *path = mrn_path_join(o->dir, o->csv_name);
  struct stat st;
  if (stat(path, &st) != 0) {
    o->csv_size = 0;
    free(path);
    return MRN_OK;
  }
  int rc = MRN_OK;
  if (st.st_size < o->csv_size)
    rc = mrn_error_code(MRN_ERR_IO, "cannot continue '%s': it holds %lld bytes, fewer than the %lld the checkpoint's run "
                        "had written (it is another run's file)", path, (long long)st.st_size, (long long)o->csv_size);
  /* process 0 continues the rows of a distributed run */
  int fd = rc == MRN_OK ? open(mrn_comm_writes() ? path : "/dev/null", O_WRONLY | O_APPEND | O_CLOEXEC) : -1;
  if (rc == MRN_OK && (fd < 0 || (mrn_comm_writes() && ftruncate(fd, o->csv_size) != 0)))
    rc = mrn_error_code(MRN_ERR_IO, "cannot continue '%s': %s", path, strerror(errno));
  if (rc != MRN_OK) {
    if (fd >= 0) close(fd);
    free(path);
    return rc;
  }
  mrn_output_mark_written(path);
  o->csv_fd = fd;
  o->csv_path = path;
  return MRN_OK;
}

static int resume_series(mrn_output *o, const mrn_stash *s) {
  if (!o->series_name || !o->series_file || o->series_rows <= 0) return MRN_OK;
  char *path = mrn_path_join(o->dir, o->series_file);
  int rc = MRN_OK;
  if (access(path, F_OK) == 0) {
    rc = mrn_series_reopen(&o->series, path, o->series_rows);
    if (rc == MRN_OK) rc = mrn_series_describe(o->series, o->run_name, o->deck_path, o->deck_text);
    if (rc == MRN_OK) mrn_output_mark_written(path);
  } else {
    o->series_rows = 0; /* a new series from here */
  }
  free(path);
  for (int i = 0; rc == MRN_OK && o->series && i < s->n; i++)
    if (!strncmp(s->v[i].name, PENDING, strlen(PENDING)))
      rc = mrn_series_set(o->series, s->v[i].name + strlen(PENDING), s->v[i].real);
  return rc;
}

int mrn_output_resume(mrn_output *o, const mrn_stash *s) {
  if (mrn_mkdir_p(o->dir) != MRN_OK) return MRN_ERR_IO;
  int rc = resume_snapshots(o);
  if (rc == MRN_OK) rc = resume_csv(o);
  if (rc == MRN_OK) rc = resume_series(o, s);
  if (rc == MRN_OK) mrn_output_claim(o, 1);
  return rc;
}

/* ---- another run's files ------------------------------------------------------ */

static mrn_path_set claimed;

void mrn_output_forget_claims(void) { mrn_path_set_clear(&claimed); }

typedef struct found {
  char text[1536];
  int count;
} found;

static void note_found(found *f, const char *name) {
  size_t used = strlen(f->text);
  if (used < sizeof f->text - 200)
    snprintf(f->text + used, sizeof f->text - used, "%s'%s'", f->count ? ", " : "", name);
  f->count++;
}

/* the snapshots <base>_NNNNNN<ext> of a series in its directory */
static void find_snapshots(const char *base, const char *ext, found *f) {
  char *dir = strdup(base);
  char *slash = strrchr(dir, '/');
  const char *stem = slash ? slash + 1 : base;
  if (slash) *slash = '\0';
  DIR *d = opendir(slash ? dir : ".");
  size_t len = strlen(stem);
  int count = 0;
  char first[512] = "";
  for (struct dirent *e; d && (e = readdir(d));) {
    const char *n = e->d_name;
    if (strncmp(n, stem, len) != 0 || n[len] != '_' || strspn(n + len + 1, "0123456789") != 6 ||
        strcmp(n + len + 7, ext) != 0)
      continue;
    if (!count++ || strcmp(n, first) < 0) snprintf(first, sizeof first, "%s", n);
  }
  if (d) closedir(d);
  if (count) {
    char name[1024];
    snprintf(name, sizeof name, "%s%s%s", slash ? dir : "", slash ? "/" : "", first);
    note_found(f, name);
    size_t used = strlen(f->text);
    if (count > 1) snprintf(f->text + used, sizeof f->text - used, " (and %d more %s)", count - 1, ext);
  }
  free(dir);
}

static void check_file(const char *path, found *f) {
  if (path && !mrn_path_set_has(&claimed, path) && access(path, F_OK) == 0) note_found(f, path);
}

int mrn_output_claim(mrn_output *o, int overwrite) {
  char *pvd = o->vtk_name ? vtk_path(o, MRN_OUTPUT_COLLECTION(o)) : NULL, *base = o->vtk_name ? vtk_path(o, "") : NULL;
  char *csv = o->csv_name ? mrn_path_join(o->dir, o->csv_name) : NULL;
  char *series = o->series_name ? mrn_path_join(o->dir, o->series_name) : NULL;
  found f = {"", 0};
  if (!overwrite) {
    check_file(pvd, &f);
    if (pvd && !mrn_path_set_has(&claimed, pvd)) {
      find_snapshots(base, MRN_OUTPUT_SNAPSHOT_EXT(o), &f);
      if (!o->vtkhdf) find_snapshots(base, ".pvtp", &f); /* a distributed run's */
    }
    check_file(csv, &f);
    check_file(series, &f);
  }
  if (f.count == 0) {
    const char *mine[] = {pvd, csv, series};
    for (int i = 0; i < 3; i++)
      if (mine[i]) mrn_path_set_add(&claimed, mine[i]);
  }
  free(pvd), free(base), free(csv), free(series);
  if (f.count == 0) return MRN_OK;
  return mrn_error("the output directory '%s' holds this simulation's outputs of another run: %s; use another "
                   "output directory (-o), remove them, pass --overwrite to replace them, or --restart CHECKPOINT to "
                   "continue that run", o->dir, f.text);
}
