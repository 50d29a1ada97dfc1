/* moraine: rigid walls from Lua — sim:add_wall{...}, sim:wall(name),
 * sim:set_wall(name, {...}) (grid/wall.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/error.h"
#include "grid/wall.h"
#include "io/atomic_file.h"
#include "io/stl.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"
#include "lua/lua_sim.h"

static const mrn_spec wall_specs[] = {
    {"name", MRN_SPEC_STRING, 1, 0, 0, 0, 0, 0, NULL, "the wall's name, unique in the simulation", NULL},
    {"shape", MRN_SPEC_STRING, 1, 0, 0, 0, 0, 0, NULL, "plane, box, cylinder (a disk in 2D), polygon (2D) or mesh (3D)", NULL},
    {"kind", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "slip, friction or fixed (default slip)", NULL},
    {"mu", MRN_SPEC_NUMBER, 0, 0.0, 0.0, HUGE_VAL, 0, 1, "", "Coulomb friction coefficient (friction walls)", NULL},
    {"point", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "plane: a point of the plane", NULL},
    {"normal", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "", "plane: its normal, out of the wall", NULL},
    {"min", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "box: lower corner", NULL},
    {"max", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "box: upper corner", NULL},
    {"center", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "cylinder: a point of its axis (the centre)",
     NULL},
    {"radius", MRN_SPEC_NUMBER, 0, 0, 0.0, HUGE_VAL, 1, 1, "m", "cylinder: its radius", NULL},
    {"axis", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "", "cylinder, 3D: its axis direction", NULL},
    {"vertices", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL, "polygon: its corners, {{x, y}, ...}", NULL},
    {"file", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "mesh: an STL file (binary or ASCII) of a closed surface", NULL},
    {"scale", MRN_SPEC_NUMBER, 0, 1.0, 0.0, HUGE_VAL, 1, 1, "m", "mesh: metres per unit of the file (default 1)",
     NULL},
    {"translate", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m", "mesh: added to its scaled corners", NULL},
    {"inside", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL, "the material is inside the shape (default false)", NULL},
    {"gap_check", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL,
     "no contact where the material over the wall stands clear of it (default false)", NULL},
    {"velocity", MRN_SPEC_ANY, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s",
     "velocity of the wall: a vector, or a function of time returning one", NULL},
    {"omega", MRN_SPEC_ANY, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "rad/s",
     "angular velocity about pivot: a number (2D) or vector (3D), or a function of time", NULL},
    {"pivot", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m",
     "the point the wall turns about and its moment is taken about (default: the shape's point or centre)", NULL},
    {"density", MRN_SPEC_NUMBER, 0, 0, 0.0, HUGE_VAL, 1, 1, "kg/m^3",
     "makes the wall a rigid body moved by its forces, of this density (or give mass)", NULL},
    {"mass", MRN_SPEC_NUMBER, 0, 0, 0.0, HUGE_VAL, 1, 1, "kg",
     "makes the wall a rigid body of this mass (kg/m in 2D; or give density)", NULL},
    {"fix", MRN_SPEC_TABLE, 0, 0, 0, 0, 0, 0, NULL,
     "rigid body: degrees of freedom that keep their velocity, e.g. {\"x\", \"rz\"} (x, y, z, rx, ry, rz)", NULL},
    {"external_force", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "N",
     "rigid body: a constant force on it besides gravity and the material (N/m in 2D)", NULL},
    {"external_moment", MRN_SPEC_ANY, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "N m",
     "rigid body: a constant moment about its centre of mass (a number in 2D, N m/m)", NULL},
};
#define NSPECS MRN_COUNT(wall_specs)

static const mrn_spec set_specs[] = {
    {"velocity", MRN_SPEC_ANY, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s", "as add_wall{}", NULL},
    {"omega", MRN_SPEC_ANY, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "rad/s", "as add_wall{}", NULL},
};

/* the motion functions of a wall, called from the engine */
typedef struct wall_motion {
  mrn_lua_callback *velocity, *omega;
  int dim;
} wall_motion;

static void motion_release(void *ctx) {
  wall_motion *m = ctx;
  if (!m) return;
  mrn_lua_callback_release(m->velocity);
  mrn_lua_callback_release(m->omega);
  free(m);
}

/* call one function of t; its result into out (n numbers, or a number for n == 1) */
static int call_motion(lua_State *L, mrn_lua_callback *cb, double t, int n, double *out) {
  mrn_lua_callback_push(L, cb);
  lua_pushnumber(L, t);
  int rc = mrn_lua_callback_pcall(L, 1, 1);
  if (rc != MRN_OK) return rc;
  int ok = n == 1 && lua_type(L, -1) == LUA_TNUMBER ? (out[0] = lua_tonumber(L, -1), 1)
                                                     : mrn_lua_read_numbers(L, -1, n, out);
  lua_pop(L, 1);
  if (!ok) return mrn_error_code(MRN_ERR_HOOK, "%s: expected %d number%s", cb->where, n, n > 1 ? "s" : "");
  return MRN_OK;
}

static int motion_call(void *ctx, double t, double v[3], double o[3]) {
  wall_motion *m = ctx;
  lua_State *L = mrn_lua_active;
  int rc = MRN_OK;
  if (m->velocity) rc = call_motion(L, m->velocity, t, m->dim, v);
  if (!rc && m->omega) rc = call_motion(L, m->omega, t, m->dim == 2 ? 1 : 3, m->dim == 2 ? o + 2 : o);
  return rc;
}

/* The value on top of the stack as a vector, or, for a turning quantity
 * (`turning`) in 2D, as a number about z: into out. `or` ends the message
 * of a value of another type. */
static void read_vector_or_turn(lua_State *L, const char *where, const mrn_spec *s, int dim, int turning,
                                const char *or, double out[3]) {
  if (turning && dim == 2 && lua_type(L, -1) == LUA_TNUMBER) {
    out[2] = lua_tonumber(L, -1);
    mrn_lua_check_number(L, where, s, NULL, out[2]);
    return;
  }
  if (!lua_istable(L, -1))
    mrn_lua_error(L, where, "%s: expected %s%s", s->key, turning && dim == 2 ? "a number" : "a vector", or);
  mrn_lua_to_vector(L, -1, where, s, dim, out);
}

/* velocity or omega at idx, when a constant: into out (kept when absent or
 * a function); raises on a bad value before anything is allocated */
static void read_constant(lua_State *L, int idx, const char *where, const char *key, const mrn_spec *specs,
                          int nspecs, int dim, double out[3]) {
  lua_getfield(L, idx, key);
  if (!lua_isnil(L, -1) && !lua_isfunction(L, -1))
    read_vector_or_turn(L, where, mrn_spec_find(specs, nspecs, key), dim, strcmp(key, "omega") == 0,
                        " or a function of time", out);
  lua_pop(L, 1);
}

/* the function at key, referenced, or NULL */
static mrn_lua_callback *read_function(lua_State *L, int idx, const char *key) {
  lua_getfield(L, idx, key);
  mrn_lua_callback *cb =
      lua_isfunction(L, -1)
          ? mrn_lua_callback_new(L, -1, strcmp(key, "omega") == 0 ? "wall omega function" : "wall velocity function")
          : NULL;
  lua_pop(L, 1);
  return cb;
}

/* polygon vertices {{x, y}, ...} into an array that lives in a userdata
 * left on the stack (collected even when an error follows) */
static double *read_vertices(lua_State *L, int idx, const char *where, int *count) {
  lua_getfield(L, idx, "vertices");
  if (!lua_istable(L, -1)) mrn_lua_error(L, where, "vertices: a polygon needs a table of {x, y} points");
  const int n = (int)luaL_len(L, -1);
  if (n < 3 || n > MRN_WALL_MAX_VERTICES)
    mrn_lua_error(L, where, "vertices: expected 3 to %d points, got %d", MRN_WALL_MAX_VERTICES, n);
  double *v = lua_newuserdatauv(L, 2 * (size_t)n * sizeof *v, 0);
  for (int i = 0; i < n; i++) {
    lua_geti(L, -2, i + 1);
    const int ok = mrn_lua_read_numbers(L, -1, 2, v + 2 * i) && isfinite(v[2 * i]) && isfinite(v[2 * i + 1]);
    lua_pop(L, 1);
    if (!ok) mrn_lua_error(L, where, "vertices[%d]: expected a point {x, y} of finite numbers", i + 1);
  }
  lua_remove(L, -2); /* the table; the userdata stays */
  *count = n;
  return v;
}

/* a relative path as given, else beside the deck; the result stays on the stack */
static const char *find_mesh_file(lua_State *L, const char *path) {
  lua_pushstring(L, path);
  if (path[0] == '/' || access(path, F_OK) == 0) return lua_tostring(L, -1);
  lua_getfield(L, LUA_REGISTRYINDEX, MRN_LUA_DECK_KEY);
  const char *deck = lua_tostring(L, -1), *slash = deck ? strrchr(deck, '/') : NULL;
  if (slash) {
    lua_pushlstring(L, deck, (size_t)(slash - deck));
    char *joined = mrn_path_join(lua_tostring(L, -1), path);
    if (joined && access(joined, F_OK) == 0) lua_pushstring(L, joined), lua_replace(L, -4);
    free(joined);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return lua_tostring(L, -1);
}

/* the mesh's triangles from its file, scaled and moved, into an array that
 * lives in a userdata left on the stack (above the path); its point: the
 * centre of its bounding box */
static void read_mesh(lua_State *L, int idx, const char *where, mrn_wall_spec *s) {
  const char *path = find_mesh_file(L, mrn_lua_get_string(L, idx, where, wall_specs, NSPECS, "file"));
  const double scale = mrn_lua_get_number(L, idx, where, wall_specs, NSPECS, "scale");
  double shift[3] = {0, 0, 0}, lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  mrn_lua_get_vector(L, idx, where, wall_specs, NSPECS, "translate", 3, shift, 0);
  double *raw = NULL;
  size_t n = 0;
  if (mrn_stl_read(path, &raw, &n)) mrn_lua_engine_error(L, where);
  if (n > MRN_WALL_MAX_TRIANGLES) {
    free(raw);
    mrn_lua_error(L, where, "'%s': %zu triangles, more than %d", path, n, MRN_WALL_MAX_TRIANGLES);
  }
  double *t = lua_newuserdatauv(L, 9 * n * sizeof *t, 0);
  for (size_t i = 0; i < 9 * n; i++) {
    t[i] = scale * raw[i] + shift[i % 3];
    lo[i % 3] = fmin(lo[i % 3], t[i]), hi[i % 3] = fmax(hi[i % 3], t[i]);
  }
  free(raw);
  s->triangle = t, s->ntriangle = (int)n, s->source = path;
  for (int d = 0; d < 3; d++) s->point[d] = 0.5 * (lo[d] + hi[d]);
}

static void require_key(lua_State *L, int idx, const char *where, const char *shape, const char *key) {
  if (!mrn_lua_has(L, idx, key)) mrn_lua_error(L, where, "missing required key '%s' for a %s wall", key, shape);
}

/* the shape's own keys into s; the default pivot */
static void read_shape(lua_State *L, int idx, const char *where, int dim, mrn_wall_spec *s) {
  const char *shape = mrn_wall_shape_names()[s->shape];
  switch (s->shape) {
  case MRN_WALL_PLANE:
    require_key(L, idx, where, shape, "point"), require_key(L, idx, where, shape, "normal");
    mrn_lua_get_vector(L, idx, where, wall_specs, NSPECS, "point", dim, s->point, 1);
    mrn_lua_get_vector(L, idx, where, wall_specs, NSPECS, "normal", dim, s->normal, 1);
    break;
  case MRN_WALL_BOX: {
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    require_key(L, idx, where, shape, "min"), require_key(L, idx, where, shape, "max");
    mrn_lua_get_vector(L, idx, where, wall_specs, NSPECS, "min", dim, lo, 1);
    mrn_lua_get_vector(L, idx, where, wall_specs, NSPECS, "max", dim, hi, 1);
    for (int d = 0; d < dim; d++) {
      if (!(hi[d] > lo[d])) mrn_lua_error(L, where, "max must exceed min along every axis (axis %d)", d + 1);
      s->point[d] = 0.5 * (lo[d] + hi[d]), s->half[d] = 0.5 * (hi[d] - lo[d]);
    }
    break;
  }
  case MRN_WALL_CYLINDER:
    require_key(L, idx, where, shape, "center"), require_key(L, idx, where, shape, "radius");
    mrn_lua_get_vector(L, idx, where, wall_specs, NSPECS, "center", dim, s->point, 1);
    s->radius = mrn_lua_get_number(L, idx, where, wall_specs, NSPECS, "radius");
    if (dim == 3) require_key(L, idx, where, shape, "axis");
    if (dim == 3) mrn_lua_get_vector(L, idx, where, wall_specs, NSPECS, "axis", dim, s->normal, 1);
    break;
  case MRN_WALL_POLYGON:
    if (dim != 2) mrn_lua_error(L, where, "shape: a polygon wall is 2D only");
    s->vertex = read_vertices(L, idx, where, &s->nvertex);
    for (int i = 0; i < s->nvertex; i++)
      s->point[0] += s->vertex[2 * i] / s->nvertex, s->point[1] += s->vertex[2 * i + 1] / s->nvertex;
    break;
  case MRN_WALL_MESH:
    if (dim != 3) mrn_lua_error(L, where, "shape: a mesh wall is 3D only");
    require_key(L, idx, where, shape, "file");
    read_mesh(L, idx, where, s);
    break;
  default: break;
  }
  memcpy(s->center, s->point, sizeof s->center);
}

/* fix = {"x", "rz", ...} into the bits of s->fix */
static void read_fix(lua_State *L, int idx, const char *where, int dim, mrn_wall_spec *s) {
  static const char *const dofs2[] = {"x", "y", "rz", NULL};
  const char *const *all = mrn_body_dof_names();
  lua_getfield(L, idx, "fix");
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    return;
  }
  const int n = (int)luaL_len(L, -1);
  for (int i = 1; i <= n; i++) {
    lua_geti(L, -1, i);
    if (lua_type(L, -1) != LUA_TSTRING) mrn_lua_error(L, where, "fix[%d]: expected the name of a degree of freedom", i);
    const char *dof = lua_tostring(L, -1);
    mrn_lua_check_choice(L, where, "fix", dof, dim == 2 ? dofs2 : all);
    for (int k = 0; all[k]; k++)
      if (strcmp(all[k], dof) == 0) s->fix |= 1u << k;
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

/* the rigid-body keys (density or mass, fix, external load) into s */
static void read_body(lua_State *L, int idx, const char *where, int dim, mrn_wall_spec *s) {
  static const char *const body_only[] = {"fix", "external_force", "external_moment"};
  s->body = mrn_lua_has(L, idx, "density") || mrn_lua_has(L, idx, "mass");
  for (int k = 0; k < 3; k++)
    if (!s->body && mrn_lua_has(L, idx, body_only[k]))
      mrn_lua_error(L, where, "%s: only a rigid body takes it (give density or mass)", body_only[k]);
  if (!s->body) return;
  if (mrn_lua_has(L, idx, "density") && mrn_lua_has(L, idx, "mass"))
    mrn_lua_error(L, where, "mass: give a rigid body's density or its mass, not both");
  if (mrn_lua_has(L, idx, "pivot"))
    mrn_lua_error(L, where, "pivot: a rigid body turns about its centre of mass (fix its rotation to hold it)");
  if (mrn_lua_has(L, idx, "density")) s->density = mrn_lua_get_number(L, idx, where, wall_specs, NSPECS, "density");
  if (mrn_lua_has(L, idx, "mass")) s->mass = mrn_lua_get_number(L, idx, where, wall_specs, NSPECS, "mass");
  read_fix(L, idx, where, dim, s);
  mrn_lua_get_vector(L, idx, where, wall_specs, NSPECS, "external_force", dim, s->load, 0);
  lua_getfield(L, idx, "external_moment");
  if (!lua_isnil(L, -1))
    read_vector_or_turn(L, where, mrn_spec_find(wall_specs, NSPECS, "external_moment"), dim, 1, "", s->load_moment);
  lua_pop(L, 1);
}

/* a body moves by its forces: no motion function */
static void check_no_function(lua_State *L, int idx, const char *where, const mrn_wall_spec *s) {
  static const char *const keys[] = {"velocity", "omega"};
  for (int k = 0; s->body && k < 2; k++) {
    lua_getfield(L, idx, keys[k]);
    const int fn = lua_isfunction(L, -1);
    lua_pop(L, 1);
    if (fn)
      mrn_lua_error(L, where, "%s: a rigid body moves by its forces; give its initial %s as a constant", keys[k],
                    keys[k]);
  }
}

/* the motion keys of the table at idx, checked: constants into s */
static void read_constants(lua_State *L, int idx, const char *where, const mrn_spec *specs, int nspecs, int dim,
                           mrn_wall_spec *s) {
  read_constant(L, idx, where, "velocity", specs, nspecs, dim, s->velocity);
  read_constant(L, idx, where, "omega", specs, nspecs, dim, s->omega);
}

/* the motion functions of the table at idx (already checked) into w,
 * replacing any; constants given alone replace a motion function too */
static void attach_functions(lua_State *L, int idx, int dim, mrn_wall *w) {
  const int given = mrn_lua_has(L, idx, "velocity") || mrn_lua_has(L, idx, "omega");
  mrn_lua_callback *v = read_function(L, idx, "velocity"), *o = read_function(L, idx, "omega");
  if (!given) return;
  if (w->motion_release) w->motion_release(w->motion_ctx);
  w->motion = NULL, w->motion_ctx = NULL, w->motion_release = NULL;
  if (!v && !o) return;
  wall_motion *m = malloc(sizeof *m);
  if (!m) {
    mrn_lua_callback_release(v), mrn_lua_callback_release(o);
    luaL_error(L, "out of memory");
  }
  m->velocity = v, m->omega = o, m->dim = dim;
  w->motion = motion_call, w->motion_ctx = m, w->motion_release = motion_release;
}

/* sim:add_wall{name = ..., shape = ..., ...} */
static int l_sim_add_wall(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *where = "add_wall{}";
  const int dim = b->sim->dim;
  mrn_lua_check_table(L, 2, where, wall_specs, NSPECS);
  if (b->sim->integrator.step)
    mrn_lua_error(L, where, "the simulation steps with the implicit integrator, which does not take rigid walls");
  mrn_wall_spec s;
  memset(&s, 0, sizeof s);
  const char *name = mrn_lua_get_string(L, 2, where, wall_specs, NSPECS, "name");
  if (strlen(name) >= MRN_WALL_NAME_MAX) mrn_lua_error(L, where, "name: longer than %d characters", MRN_WALL_NAME_MAX - 1);
  snprintf(s.name, sizeof s.name, "%s", name);
  const char *shape = mrn_lua_get_string(L, 2, where, wall_specs, NSPECS, "shape");
  mrn_lua_check_choice(L, where, "shape", shape, mrn_wall_shape_names());
  while (strcmp(mrn_wall_shape_names()[s.shape], shape) != 0) s.shape++;
  const char *kind = mrn_lua_has(L, 2, "kind") ? mrn_lua_get_string(L, 2, where, wall_specs, NSPECS, "kind") : "slip";
  mrn_lua_check_choice(L, where, "kind", kind, mrn_wall_kind_names());
  while (strcmp(mrn_wall_kind_names()[s.kind], kind) != 0) s.kind++;
  if (s.kind == MRN_WALL_FRICTION && !mrn_lua_has(L, 2, "mu")) mrn_lua_error(L, where, "mu: a friction wall needs mu");
  s.mu = mrn_lua_get_number(L, 2, where, wall_specs, NSPECS, "mu");
  s.inside = mrn_lua_get_boolean(L, 2, where, wall_specs, NSPECS, "inside", 0);
  s.gap_check = mrn_lua_get_boolean(L, 2, where, wall_specs, NSPECS, "gap_check", 0);
  read_shape(L, 2, where, dim, &s);
  read_body(L, 2, where, dim, &s);
  check_no_function(L, 2, where, &s);
  mrn_lua_get_vector(L, 2, where, wall_specs, NSPECS, "pivot", dim, s.center, 0);
  read_constants(L, 2, where, wall_specs, NSPECS, dim, &s);
  mrn_lua_active = L;
  if (mrn_walls_add(&b->sim->boundary.walls, &b->sim->grid, &s)) mrn_lua_engine_error(L, where);
  attach_functions(L, 2, dim, mrn_walls_find(b->sim->boundary.walls, s.name));
  return 0;
}

static mrn_wall *check_wall(lua_State *L, sim_box *b, int idx, const char *where) {
  const char *name = luaL_checkstring(L, idx);
  mrn_wall *w = mrn_walls_find(b->sim->boundary.walls, name);
  if (!w) mrn_lua_error(L, where, "no wall named '%s'", name);
  return w;
}

/* a body's fields of sim:wall(name): mass, inertia (now), kinetic energy, work on it */
static void push_body(lua_State *L, const mrn_wall *w, int dim) {
  lua_pushnumber(L, w->mass), lua_setfield(L, -2, "mass");
  double I[9];
  mrn_body_inertia(w, I);
  if (dim == 2) lua_pushnumber(L, I[8]);
  else mrn_lua_push_vector(L, I, 9);
  lua_setfield(L, -2, "inertia");
  lua_pushnumber(L, mrn_body_kinetic(w, dim)), lua_setfield(L, -2, "kinetic");
  lua_pushnumber(L, w->body_work), lua_setfield(L, -2, "body_work");
}

/* sim:wall(name) -> {force, moment, position, ...} of the last step */
static int l_sim_wall(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  mrn_wall *w = check_wall(L, b, 2, "wall()");
  const int dim = b->sim->dim;
  lua_createtable(L, 0, 10);
  mrn_lua_push_vector(L, w->force, dim), lua_setfield(L, -2, "force");
  if (dim == 2) lua_pushnumber(L, w->moment[2]);
  else mrn_lua_push_vector(L, w->moment, 3);
  lua_setfield(L, -2, "moment");
  mrn_lua_push_vector(L, w->ref, dim), lua_setfield(L, -2, "pivot");
  mrn_lua_push_vector(L, w->spec.velocity, dim), lua_setfield(L, -2, "velocity");
  if (dim == 2) lua_pushnumber(L, w->spec.omega[2]);
  else mrn_lua_push_vector(L, w->spec.omega, 3);
  lua_setfield(L, -2, "omega");
  mrn_lua_push_vector(L, w->rot, 9), lua_setfield(L, -2, "rotation");
  mrn_lua_push_vector(L, w->total_impulse, dim), lua_setfield(L, -2, "impulse");
  lua_pushnumber(L, w->work), lua_setfield(L, -2, "work");
  lua_pushnumber(L, w->work_friction), lua_setfield(L, -2, "work_friction");
  lua_pushinteger(L, w->contacts), lua_setfield(L, -2, "contacts");
  lua_pushstring(L, w->spec.name), lua_setfield(L, -2, "name");
  lua_pushboolean(L, w->spec.gap_check), lua_setfield(L, -2, "gap_check");
  if (w->spec.body) push_body(L, w, dim);
  return 1;
}

/* sim:set_wall(name, {velocity = ..., omega = ...}) */
static int l_sim_set_wall(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const char *where = "set_wall()";
  mrn_wall *w = check_wall(L, b, 2, where);
  mrn_lua_check_table(L, 3, where, set_specs, MRN_COUNT(set_specs));
  mrn_wall_spec s = w->spec;
  check_no_function(L, 3, where, &s);
  read_constants(L, 3, where, set_specs, MRN_COUNT(set_specs), b->sim->dim, &s);
  memcpy(w->spec.velocity, s.velocity, sizeof s.velocity);
  memcpy(w->spec.omega, s.omega, sizeof s.omega);
  attach_functions(L, 3, b->sim->dim, w);
  return 0;
}

static const luaL_Reg wall_methods[] = {
    {"add_wall", l_sim_add_wall},
    {"wall", l_sim_wall},
    {"set_wall", l_sim_set_wall},
    {NULL, NULL},
};

void mrn_lua_add_wall_methods(lua_State *L, int methods) {
  lua_pushvalue(L, methods);
  luaL_setfuncs(L, wall_methods, 0);
  lua_pop(L, 1);
}

const mrn_spec_group mrn_lua_wall_group = {"add_wall{}", wall_specs, NSPECS};
