/* moraine: the rigid walls in a checkpoint (/walls, doc/checkpoint-format.md).
 *
 * A rigid body is a wall with its body keys besides; its velocity and
 * angular velocity are the wall's, its centre of mass the wall's pivot.
 *
 * A wall is kept whole: its spec (shape, placement at creation, kind, mu,
 * motion as last set), where it is now, its accumulators and the nodes in
 * contact at the end of the last step. A motion function cannot be stored:
 * the loaded wall moves with the velocities the function gave last, until the
 * deck sets it again (a resume carries it over from the deck's wall). A file
 * without /walls loads with none. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "grid/wall.h"
#include "io/checkpoint_internal.h"

/* a rigid body's keys and the work done on it; its velocities are the wall's */
static void save_body(mrn_h5w *w, hid_t g, const mrn_wall *wall) {
  const mrn_wall_spec *s = &wall->spec;
  if (!s->body) return;
  mrn_h5w_int32(w, g, "body", 1);
  mrn_h5w_double(w, g, "density", s->density);
  mrn_h5w_double(w, g, "mass", s->mass);
  mrn_h5w_int32(w, g, "fix", (int)s->fix);
  mrn_h5w_doubles(w, g, "external_force", s->load, 3);
  mrn_h5w_doubles(w, g, "external_moment", s->load_moment, 3);
  mrn_h5w_double(w, g, "body_work", wall->body_work);
}

static void save_wall(mrn_h5w *w, hid_t g, const mrn_wall *wall, const mrn_grid *grid) {
  const mrn_wall_spec *s = &wall->spec;
  mrn_h5w_string(w, g, "name", s->name);
  mrn_h5w_string(w, g, "shape", mrn_wall_shape_names()[s->shape]);
  mrn_h5w_string(w, g, "kind", mrn_wall_kind_names()[s->kind]);
  mrn_h5w_int32(w, g, "inside", s->inside);
  mrn_h5w_int32(w, g, "gap_check", s->gap_check);
  mrn_h5w_double(w, g, "mu", s->mu);
  mrn_h5w_double(w, g, "radius", s->radius);
  mrn_h5w_doubles(w, g, "point", s->point, 3);
  mrn_h5w_doubles(w, g, "normal", s->normal, 3);
  mrn_h5w_doubles(w, g, "half", s->half, 3);
  mrn_h5w_doubles(w, g, "velocity", s->velocity, 3);
  mrn_h5w_doubles(w, g, "omega", s->omega, 3);
  mrn_h5w_doubles(w, g, "center", s->center, 3);
  mrn_h5w_doubles(w, g, "ref", wall->ref, 3);
  mrn_h5w_doubles(w, g, "rot", wall->rot, 9);
  mrn_h5w_doubles(w, g, "force", wall->force, 3);
  mrn_h5w_doubles(w, g, "moment", wall->moment, 3);
  mrn_h5w_doubles(w, g, "impulse", wall->total_impulse, 3);
  mrn_h5w_double(w, g, "work", wall->work);
  mrn_h5w_double(w, g, "work_friction", wall->work_friction);
  mrn_h5w_int32(w, g, "motion_function", wall->motion != NULL);
  save_body(w, g, wall);
  mrn_h5w_int32(w, g, "vertex_count", s->nvertex);
  if (s->nvertex)
    mrn_h5w_dataset(w, g, "vertices", H5T_NATIVE_DOUBLE, s->vertex, (size_t)s->nvertex, 2, "m", "polygon corners");
  if (s->ntriangle) {
    mrn_h5w_int32(w, g, "triangle_count", s->ntriangle);
    mrn_h5w_dataset(w, g, "triangles", H5T_NATIVE_DOUBLE, s->triangle, (size_t)s->ntriangle, 9, "m",
                    "mesh triangles: corners a, b, c");
  }
  size_t count = 0;
  for (size_t n = 0; n < grid->n; n++) count += (wall->state[n] & MRN_WALL_CONTACT) != 0;
  int64_t *rows = malloc((count ? count : 1) * sizeof *rows);
  if (!rows) {
    w->failed = 1;
    snprintf(w->what, sizeof w->what, "/walls (out of memory)");
    return;
  }
  for (size_t n = 0, k = 0; n < grid->n; n++)
    if (wall->state[n] & MRN_WALL_CONTACT) rows[k++] = (int64_t)n;
  mrn_h5w_int64(w, g, "contact_count", (int64_t)count);
  mrn_h5w_dataset(w, g, "contact", H5T_NATIVE_INT64, rows, count, MRN_H5_RANK1, "",
                  "nodes in contact with the wall at the end of the last step");
  free(rows);
}

void ck_save_walls(mrn_h5w *w, const mrn_sim *sim) {
  const mrn_walls *ws = sim->boundary.walls;
  if (!ws || !ws->count) return;
  hid_t g = mrn_h5w_group(w, w->file, "walls");
  if (g < 0) return;
  mrn_h5w_int32(w, g, "count", ws->count);
  for (int i = 0; i < ws->count; i++) {
    char name[32];
    snprintf(name, sizeof name, "%d", i);
    hid_t wg = mrn_h5w_group(w, g, name);
    if (wg < 0) break;
    save_wall(w, wg, &ws->wall[i], &sim->grid);
    H5Gclose(wg);
  }
  H5Gclose(g);
}

/* a mesh wall's triangles */
static int read_triangles(mrn_h5r *r, const char *g, mrn_wall_spec *s) {
  int64_t nt = 0;
  char path[96];
  if (mrn_h5r_int(r, g, "triangle_count", &nt)) return MRN_ERR;
  if (nt < 1 || nt > MRN_WALL_MAX_TRIANGLES) return mrn_h5r_fail(r, "%s: triangle_count out of range", g);
  snprintf(path, sizeof path, "%s/triangles", g);
  s->ntriangle = (int)nt;
  return (s->triangle = mrn_h5r_dataset(r, path, MRN_H5_FLOAT64, nt, 9)) ? MRN_OK : MRN_ERR;
}

/* a body's attributes, when the wall is one (a file without them: a wall) */
static int read_body(mrn_h5r *r, const char *g, ck_wall *c) {
  mrn_wall_spec *s = &c->spec;
  if (mrn_h5r_has_attr(r, g, "body") != 1) return MRN_OK;
  int64_t fix = 0;
  if (mrn_h5r_double(r, g, "density", &s->density) || mrn_h5r_double(r, g, "mass", &s->mass) ||
      mrn_h5r_int(r, g, "fix", &fix) || mrn_h5r_doubles(r, g, "external_force", s->load, 3) ||
      mrn_h5r_doubles(r, g, "external_moment", s->load_moment, 3) ||
      mrn_h5r_double(r, g, "body_work", &c->body_work))
    return MRN_ERR;
  if (fix < 0 || fix >= 64) return mrn_h5r_fail(r, "%s: fix %lld out of range", g, (long long)fix);
  s->body = 1, s->fix = (unsigned)fix;
  return MRN_OK;
}

static void read_wall(mrn_h5r *r, const char *g, ck_wall *c, int64_t nodes) {
  mrn_wall_spec *s = &c->spec;
  int shape = 0, kind = 0;
  int64_t inside = 0, nv = 0;
  if (mrn_h5r_string(r, g, "name", s->name, sizeof s->name) ||
      mrn_h5r_choice(r, g, "shape", mrn_wall_shape_names(), &shape) ||
      mrn_h5r_choice(r, g, "kind", mrn_wall_kind_names(), &kind) || mrn_h5r_int(r, g, "inside", &inside) ||
      mrn_h5r_double(r, g, "mu", &s->mu) || mrn_h5r_double(r, g, "radius", &s->radius) ||
      mrn_h5r_doubles(r, g, "point", s->point, 3) || mrn_h5r_doubles(r, g, "normal", s->normal, 3) ||
      mrn_h5r_doubles(r, g, "half", s->half, 3) || mrn_h5r_doubles(r, g, "velocity", s->velocity, 3) ||
      mrn_h5r_doubles(r, g, "omega", s->omega, 3) || mrn_h5r_doubles(r, g, "center", s->center, 3) ||
      mrn_h5r_doubles(r, g, "ref", c->ref, 3) || mrn_h5r_doubles(r, g, "rot", c->rot, 9) ||
      mrn_h5r_doubles(r, g, "force", c->force, 3) || mrn_h5r_doubles(r, g, "moment", c->moment, 3) ||
      mrn_h5r_doubles(r, g, "impulse", c->total_impulse, 3) || mrn_h5r_double(r, g, "work", &c->work) ||
      mrn_h5r_double(r, g, "work_friction", &c->work_friction) || mrn_h5r_int(r, g, "vertex_count", &nv) ||
      mrn_h5r_int(r, g, "contact_count", &c->ncontact) || read_body(r, g, c))
    return;
  s->shape = (mrn_wall_shape)shape, s->kind = (mrn_wall_kind)kind, s->inside = inside != 0;
  int64_t check = 0; /* absent from older checkpoints: off */
  if (mrn_h5r_has_attr(r, g, "gap_check")) mrn_h5r_int(r, g, "gap_check", &check);
  s->gap_check = check != 0;
  if (nv < 0 || nv > MRN_WALL_MAX_VERTICES || c->ncontact < 0 || c->ncontact > nodes) {
    mrn_h5r_fail(r, "%s: vertex_count or contact_count out of range", g);
    return;
  }
  char path[96];
  s->nvertex = (int)nv;
  snprintf(path, sizeof path, "%s/vertices", g);
  if (nv && !(s->vertex = mrn_h5r_dataset(r, path, MRN_H5_FLOAT64, nv, 2))) return;
  if (s->shape == MRN_WALL_MESH && read_triangles(r, g, s)) return;
  snprintf(path, sizeof path, "%s/contact", g);
  c->contact = mrn_h5r_dataset(r, path, MRN_H5_INT64, c->ncontact, MRN_H5_RANK1);
  for (int64_t k = 0; c->contact && k < c->ncontact; k++)
    if (c->contact[k] < 0 || c->contact[k] >= nodes) {
      mrn_h5r_fail(r, "%s: node %lld out of range", path, (long long)c->contact[k]);
      return;
    }
}

void ck_read_walls(mrn_h5r *r, ck_data *d, int64_t nodes) {
  if (r->failed || mrn_h5r_exists(r, "/walls") != 1) return;
  int64_t count = 0;
  if (mrn_h5r_int(r, "/walls", "count", &count)) return;
  if (count < 0 || count > 1 << 16) {
    mrn_h5r_fail(r, "/walls: count %lld out of range", (long long)count);
    return;
  }
  d->walls = calloc((size_t)(count ? count : 1), sizeof *d->walls);
  if (!d->walls) {
    mrn_h5r_fail(r, "out of memory reading /walls");
    return;
  }
  d->nwalls = (int)count;
  for (int i = 0; i < d->nwalls && !r->failed; i++) {
    char g[32];
    snprintf(g, sizeof g, "/walls/%d", i);
    read_wall(r, g, &d->walls[i], nodes);
  }
}

int ck_take_walls(mrn_sim *sim, const ck_data *d) {
  for (int i = 0; i < d->nwalls; i++) {
    const ck_wall *c = &d->walls[i];
    if (mrn_walls_add(&sim->boundary.walls, &sim->grid, &c->spec)) return MRN_ERR;
    mrn_wall *w = &sim->boundary.walls->wall[sim->boundary.walls->count - 1];
    memcpy(w->ref, c->ref, sizeof w->ref);
    memcpy(w->rot, c->rot, sizeof w->rot);
    memcpy(w->force, c->force, sizeof w->force);
    memcpy(w->moment, c->moment, sizeof w->moment);
    memcpy(w->total_impulse, c->total_impulse, sizeof w->total_impulse);
    w->work = c->work, w->work_friction = c->work_friction, w->body_work = c->body_work;
    size_t *nodes = malloc((size_t)(c->ncontact ? c->ncontact : 1) * sizeof *nodes);
    if (!nodes) return mrn_error("out of memory for a wall");
    for (int64_t k = 0; k < c->ncontact; k++) nodes[k] = (size_t)c->contact[k];
    int rc = mrn_wall_restore(w, nodes, (size_t)c->ncontact);
    free(nodes);
    if (rc) return rc;
  }
  return MRN_OK;
}

void ck_free_walls(ck_data *d) {
  for (int i = 0; i < d->nwalls; i++) {
    free(d->walls[i].spec.vertex);
    free(d->walls[i].spec.triangle);
    free(d->walls[i].contact);
  }
  free(d->walls);
  d->walls = NULL, d->nwalls = 0;
}
