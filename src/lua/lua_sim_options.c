/* moraine: the options of simulation{} that the set_*() methods change
 * later — boundary, scheme, dt and damping — each read by one function. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"
#include "solver/split.h"

static const char *const gradient_choices[] = {"standard", "mls", NULL};
static const mrn_spec scheme_specs[] = {
    {"transfer", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "strategy preset (default FLIP)", NULL},
    {"stress_update", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "USF, USL, MUSL or USAVG (default USF)", NULL},
    {"grid_velocity", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "plain, affine or taylor (overrides the preset)", NULL},
    {"velocity_update", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "PIC, FLIP, blend or XPIC (overrides the preset)", NULL},
    {"position_update", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "grid, particle or XPIC (overrides the preset)", NULL},
    {"flip_fraction", MRN_SPEC_NUMBER, 0, 1, 0, 1, 0, 0, "", "X of the blend X FLIP + (1 - X) PIC (000, Eq. 37)", NULL},
    {"xpic_order", MRN_SPEC_INTEGER, 0, 1, 1, 16, 0, 0, "", "m of XPIC(m) (000, Eqs. 39-41)", NULL},
    {"gradient", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "kernel gradient: standard or mls (002, Eq. 62)", gradient_choices},
    {"volumetric", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "volumetric part of the velocity gradient: standard or fbar (averaged over the nodes, against locking)", NULL},
    {"holds", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL,
     "where FLIP's increment takes the holds of V: grid (left out, default) or particles (two-stage contact)", NULL},
};

static const mrn_spec boundary_specs[] = {
    {"xmin", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face x = origin", NULL},
    {"xmax", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face x = origin + size", NULL},
    {"ymin", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face y = origin", NULL},
    {"ymax", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face y = origin + size", NULL},
    {"zmin", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face z = origin (3D)", NULL},
    {"zmax", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "face z = origin + size (3D)", NULL},
    {"left", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of xmin", NULL},
    {"right", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of xmax", NULL},
    {"bottom", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of ymin in 2D, zmin in 3D", NULL},
    {"top", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of ymax in 2D, zmax in 3D", NULL},
    {"front", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of ymin in 3D", NULL},
    {"back", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "alias of ymax in 3D", NULL},
    {"all", MRN_SPEC_ANY, 0, 0, 0, 0, 0, 0, NULL, "every face not named otherwise", NULL},
};

static const mrn_spec face_specs[] = {
    {"kind", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "free, fixed, slip, friction, velocity or periodic", NULL},
    {"mu", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "", "Coulomb friction coefficient (friction faces)", NULL},
    {"v", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "m/s", "prescribed velocity (velocity faces)", NULL},
    {"gap_check", MRN_SPEC_BOOLEAN, 0, 0, 0, 0, 0, 0, NULL,
     "friction faces: no contact where the material over the face stands clear of it (default false)", NULL},
};

static const mrn_spec dt_specs[] = {
    {"fixed", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 1, 0, "s", "constant time step", NULL},
    {"a_tau", MRN_SPEC_NUMBER, 0, 0.05, 0, HUGE_VAL, 1, 0, "", "dt = a_tau l_cell sqrt(rho/E) (000, Eq. 29)", NULL},
    {"cfl", MRN_SPEC_NUMBER, 0, 0.5, 0, HUGE_VAL, 1, 0, "", "Courant number of the particle CFL step (002, Eqs. 34-37)", NULL},
    {"grid_cfl", MRN_SPEC_NUMBER, 0, 1, 0, HUGE_VAL, 1, 0, "", "factor on the grid-averaged CFL step (001, Eqs. 58-61)", NULL},
    {"fn", MRN_SPEC_FUNCTION, 0, 0, 0, 0, 0, 0, NULL, "function(sim) returning dt", NULL},
    {"min", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "s", "stop the run if dt falls below this", NULL},
    {"max", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "s", "upper bound on dt", NULL},
};

static const mrn_spec damping_specs[] = {
    {"cundall", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "", "D of Cundall's local non-viscous damping (000, Eqs. 61-62)", NULL},
    {"viscous", MRN_SPEC_NUMBER, 0, 0, 0, HUGE_VAL, 0, 0, "1/s", "alpha of mass-proportional viscous damping -alpha m v", NULL},
};

void mrn_lua_read_damping(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  char sub[96];
  snprintf(sub, sizeof sub, "%s damping", where);
  mrn_lua_check_table(L, idx, sub, damping_specs, MRN_COUNT(damping_specs));
  if (mrn_lua_has(L, idx, "cundall"))
    sim->damping_cundall = mrn_lua_get_number(L, idx, sub, damping_specs, MRN_COUNT(damping_specs), "cundall");
  if (mrn_lua_has(L, idx, "viscous"))
    sim->damping_viscous = mrn_lua_get_number(L, idx, sub, damping_specs, MRN_COUNT(damping_specs), "viscous");
}

static void read_face(lua_State *L, int value_idx, const char *where, const char *key, mrn_face_bc *f, int dim) {
  value_idx = lua_absindex(L, value_idx);
  const char *kind = NULL;
  f->mu = 0.0;
  f->gap_check = 0;
  f->velocity[0] = f->velocity[1] = f->velocity[2] = 0.0;
  if (lua_type(L, value_idx) == LUA_TSTRING) {
    kind = lua_tostring(L, value_idx);
  } else if (lua_istable(L, value_idx)) {
    lua_geti(L, value_idx, 1);
    const char *positional = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
    lua_pop(L, 1);
    /* { "friction", mu = 0.3 } or { kind = "friction", mu = 0.3 } */
    lua_pushnil(L);
    while (lua_next(L, value_idx)) {
      lua_pop(L, 1);
      if (lua_type(L, -1) == LUA_TSTRING) {
        const char *k = lua_tostring(L, -1);
        if (!mrn_spec_find(face_specs, MRN_COUNT(face_specs), k)) {
          const char *hint = mrn_spec_suggest(face_specs, MRN_COUNT(face_specs), k);
          mrn_lua_error(L, where, "%s: unknown key '%s'%s", key, k, mrn_hint(hint).s);
        }
      }
    }
    kind = mrn_lua_get_string(L, value_idx, where, face_specs, MRN_COUNT(face_specs), "kind");
    if (!kind) kind = positional;
    if (mrn_lua_has(L, value_idx, "mu")) {
      lua_getfield(L, value_idx, "mu");
      if (lua_type(L, -1) != LUA_TNUMBER) mrn_lua_error(L, where, "%s.mu must be a number", key);
      lua_pop(L, 1);
      f->mu = mrn_lua_get_number(L, value_idx, where, face_specs, MRN_COUNT(face_specs), "mu");
    }
    f->gap_check = mrn_lua_get_boolean(L, value_idx, where, face_specs, MRN_COUNT(face_specs), "gap_check", 0);
  } else {
    mrn_lua_error(L, where, "%s must be a condition name or a table like {\"friction\", mu = 0.3}, got %s", key,
                  luaL_typename(L, value_idx));
  }
  if (!kind) mrn_lua_error(L, where, "%s: no condition kind given (free, fixed, slip or friction)", key);
  mrn_lua_check_choice(L, where, key, kind, mrn_bc_kind_names());
  mrn_bc_kind_from_name(kind, &f->kind);
  if (f->kind == MRN_BC_FRICTION && (!lua_istable(L, value_idx) || !mrn_lua_has(L, value_idx, "mu")))
    mrn_lua_error(L, where, "%s: a friction face needs a coefficient, e.g. {\"friction\", mu = 0.3}", key);
  if (f->kind == MRN_BC_VELOCITY) {
    if (!lua_istable(L, value_idx) || !mrn_lua_has(L, value_idx, "v"))
      mrn_lua_error(L, where, "%s: a velocity face needs v, e.g. {\"velocity\", v = {0.001, 0}}", key);
    char sub[96];
    snprintf(sub, sizeof sub, "%s %s", where, key);
    mrn_lua_get_vector(L, value_idx, sub, face_specs, MRN_COUNT(face_specs), "v", dim, f->velocity, 1);
  }
}

static int face_of_key(const char *key, int dim) {
  static const char *direct[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  for (int i = 0; i < 6; i++)
    if (strcmp(key, direct[i]) == 0) return i;
  if (strcmp(key, "left") == 0) return MRN_FACE_XMIN;
  if (strcmp(key, "right") == 0) return MRN_FACE_XMAX;
  if (strcmp(key, "bottom") == 0) return dim == 2 ? MRN_FACE_YMIN : MRN_FACE_ZMIN;
  if (strcmp(key, "top") == 0) return dim == 2 ? MRN_FACE_YMAX : MRN_FACE_ZMAX;
  if (strcmp(key, "front") == 0) return dim == 3 ? MRN_FACE_YMIN : -2;
  if (strcmp(key, "back") == 0) return dim == 3 ? MRN_FACE_YMAX : -2;
  return -1; /* "all" */
}

/* apply a boundary table on top of the current conditions */
void mrn_lua_read_boundary(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  mrn_lua_check_table(L, idx, where, boundary_specs, MRN_COUNT(boundary_specs));
  char sub[96];
  snprintf(sub, sizeof sub, "%s boundary", where);
  if (mrn_lua_has(L, idx, "all")) {
    mrn_face_bc f;
    lua_getfield(L, idx, "all");
    read_face(L, -1, sub, "all", &f, sim->dim);
    lua_pop(L, 1);
    for (int i = 0; i < 2 * sim->dim; i++) sim->boundary.face[i] = f;
  }
  for (int i = 0; i < MRN_COUNT(boundary_specs); i++) {
    const char *key = boundary_specs[i].key;
    if (strcmp(key, "all") == 0 || !mrn_lua_has(L, idx, key)) continue;
    int face = face_of_key(key, sim->dim);
    if (face == -2 || face >= 2 * sim->dim)
      mrn_lua_error(L, sub, "face '%s' does not exist in %dD", key, sim->dim);
    lua_getfield(L, idx, key);
    read_face(L, -1, sub, key, &sim->boundary.face[face], sim->dim);
    lua_pop(L, 1);
  }
  if (mrn_boundary_validate(&sim->boundary, sim->dim) != MRN_OK) mrn_lua_engine_error(L, sub);
}

/* one of the three knobs by name, overriding the preset */
static int read_knob(lua_State *L, int idx, const char *where, const char *key, const char *const *names) {
  const char *v = mrn_lua_get_string(L, idx, where, scheme_specs, MRN_COUNT(scheme_specs), key);
  if (!v) return -1;
  mrn_lua_check_choice(L, where, key, v, names);
  return mrn_name_index(names, v);
}

void mrn_lua_read_scheme(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  mrn_scheme s = sim->scheme;
  if (lua_type(L, idx) == LUA_TSTRING) {
    if (mrn_scheme_from_preset(lua_tostring(L, idx), &s) != MRN_OK) mrn_lua_engine_error(L, where);
  } else if (lua_istable(L, idx)) {
    const int n = MRN_COUNT(scheme_specs);
    mrn_lua_check_table(L, idx, where, scheme_specs, n);
    const char *su = mrn_lua_get_string(L, idx, where, scheme_specs, n, "stress_update");
    if (su) {
      mrn_lua_check_choice(L, where, "stress_update", su, mrn_stress_update_names());
      mrn_stress_update_from_name(su, &s.stress_update);
    }
    const char *tr = mrn_lua_get_string(L, idx, where, scheme_specs, n, "transfer");
    if (tr && mrn_scheme_from_preset(tr, &s) != MRN_OK) mrn_lua_error(L, where, "transfer: %s", mrn_error_message());
    int k;
    int custom = 0;
    if ((k = read_knob(L, idx, where, "grid_velocity", mrn_grid_velocity_names())) >= 0) s.grid_velocity = k, custom = 1;
    if ((k = read_knob(L, idx, where, "velocity_update", mrn_velocity_update_names())) >= 0) s.velocity_update = k, custom = 1;
    if ((k = read_knob(L, idx, where, "position_update", mrn_position_update_names())) >= 0) s.position_update = k, custom = 1;
    if (mrn_lua_has(L, idx, "flip_fraction")) {
      s.flip_fraction = mrn_lua_get_number(L, idx, where, scheme_specs, n, "flip_fraction");
      custom = 1;
    }
    if (mrn_lua_has(L, idx, "xpic_order")) {
      s.xpic_order = (int)mrn_lua_get_integer(L, idx, where, scheme_specs, n, "xpic_order");
      custom = 1;
    }
    const char *grad = mrn_lua_get_string(L, idx, where, scheme_specs, n, "gradient");
    if (grad) {
      s.mls_gradient = strcmp(grad, "mls") == 0;
      custom = 1;
    }
    if (custom) mrn_scheme_describe(&s);
    /* not a transfer choice: the preset's name stays */
    if ((k = read_knob(L, idx, where, "volumetric", mrn_volumetric_names())) >= 0) s.volumetric = k;
    if ((k = read_knob(L, idx, where, "holds", mrn_holds_names())) >= 0) s.holds = k;
  } else {
    mrn_lua_error(L, where, "scheme must be a preset name or a table {transfer = ..., stress_update = ...}, got %s",
                  luaL_typename(L, idx));
  }
  if (mrn_scheme_validate(&s) != MRN_OK) mrn_lua_engine_error(L, where);
  sim->scheme = s;
}

static int call_dt_function(void *ctx, mrn_sim *sim, double *dt) {
  lua_State *L = mrn_lua_active;
  (void)sim;
  mrn_lua_callback_push(L, ctx);
  lua_pushvalue(L, 1); /* the simulation userdata is argument 1 of sim:run */
  int rc = mrn_lua_callback_pcall(L, 1, 1);
  if (rc != MRN_OK) return rc;
  int isnum = 0;
  *dt = lua_tonumberx(L, -1, &isnum);
  lua_pop(L, 1);
  if (!isnum) return mrn_error_code(MRN_ERR_HOOK, "dt function: expected a number, got a non-number");
  return MRN_OK;
}

void mrn_lua_read_dt(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  mrn_dt_policy *p = &sim->dt_policy;
  double min = p->min, max = p->max;
  if (lua_type(L, idx) == LUA_TNUMBER) { /* dt = 0.001 is short for dt = {fixed = 0.001} */
    double dt = lua_tonumber(L, idx);
    mrn_lua_check_number(L, where, mrn_spec_find(dt_specs, MRN_COUNT(dt_specs), "fixed"), "dt", dt);
    mrn_dt_policy_fixed(p, dt);
  } else if (lua_type(L, idx) == LUA_TFUNCTION) {
    mrn_dt_policy_release(p);
    p->kind = MRN_DT_CALLBACK;
    p->callback = call_dt_function;
    p->ctx = mrn_lua_callback_new(L, idx, "dt function");
    p->release = mrn_lua_callback_release;
  } else if (lua_istable(L, idx)) {
    char sub[96];
    snprintf(sub, sizeof sub, "%s dt", where);
    mrn_lua_check_table(L, idx, sub, dt_specs, MRN_COUNT(dt_specs));
    int kinds = mrn_lua_has(L, idx, "fixed") + mrn_lua_has(L, idx, "a_tau") + mrn_lua_has(L, idx, "fn") +
                mrn_lua_has(L, idx, "cfl") + mrn_lua_has(L, idx, "grid_cfl");
    if (kinds != 1) mrn_lua_error(L, sub, "give exactly one of fixed, a_tau, cfl, grid_cfl or fn (got %d)", kinds);
    min = mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "min");
    max = mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "max");
    if (mrn_lua_has(L, idx, "fixed")) {
      mrn_dt_policy_fixed(p, mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "fixed"));
    } else if (mrn_lua_has(L, idx, "a_tau")) {
      mrn_dt_policy_a_tau(p, mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "a_tau"));
    } else if (mrn_lua_has(L, idx, "cfl")) {
      mrn_dt_policy_cfl(p, MRN_DT_CFL, mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "cfl"));
    } else if (mrn_lua_has(L, idx, "grid_cfl")) {
      mrn_dt_policy_cfl(p, MRN_DT_GRID_CFL, mrn_lua_get_number(L, idx, sub, dt_specs, MRN_COUNT(dt_specs), "grid_cfl"));
    } else {
      lua_getfield(L, idx, "fn");
      mrn_lua_read_dt(L, -1, where, sim);
      lua_pop(L, 1);
    }
    if (max > 0 && min > max) mrn_lua_error(L, sub, "min = %g is above max = %g", min, max);
  } else {
    mrn_lua_error(L, where, "dt must be a number, a table {fixed|a_tau|cfl|grid_cfl|fn, min, max} or a function, got %s",
                  luaL_typename(L, idx));
  }
  p->min = min;
  p->max = max;
}

const mrn_spec_group mrn_lua_scheme_group = {"simulation{} scheme", scheme_specs, MRN_COUNT(scheme_specs)};
const mrn_spec_group mrn_lua_boundary_group = {"simulation{} boundary", boundary_specs, MRN_COUNT(boundary_specs)};
const mrn_spec_group mrn_lua_face_group = {"boundary face", face_specs, MRN_COUNT(face_specs)};
const mrn_spec_group mrn_lua_dt_group = {"simulation{} dt", dt_specs, MRN_COUNT(dt_specs)};
const mrn_spec_group mrn_lua_damping_group = {"simulation{} damping", damping_specs, MRN_COUNT(damping_specs)};

/* ------------------------------------------------------- splitting */

static const mrn_spec split_specs[] = {
    {"stretch", MRN_SPEC_NUMBER, 0, 2, 1, HUGE_VAL, 1, 0, "",
     "split a particle whose domain's largest half-axis exceeds this times its initial half-width", NULL},
    {"max_level", MRN_SPEC_INTEGER, 0, 3, 0, MRN_SPLIT_MAX_LEVEL, 0, 0, "",
     "the most splits in a particle's ancestry (a particle becomes at most 2^max_level)", NULL},
};

/* split = {stretch, max_level} or false (solver/split.h) */
void mrn_lua_read_split(lua_State *L, int idx, const char *where, mrn_sim *sim) {
  idx = lua_absindex(L, idx);
  char sub[96];
  snprintf(sub, sizeof sub, "%s split", where);
  double stretch = 0.0;
  int levels = 0;
  if (lua_type(L, idx) == LUA_TBOOLEAN && !lua_toboolean(L, idx)) {
    /* false: no splitting */
  } else {
    mrn_lua_check_table(L, idx, sub, split_specs, MRN_COUNT(split_specs));
    stretch = mrn_lua_get_number(L, idx, sub, split_specs, MRN_COUNT(split_specs), "stretch");
    levels = (int)mrn_lua_get_integer(L, idx, sub, split_specs, MRN_COUNT(split_specs), "max_level");
  }
  mrn_lua_active = L;
  if (mrn_sim_set_split(sim, stretch, levels) != MRN_OK) mrn_lua_engine_error(L, sub);
}

const mrn_spec_group mrn_lua_split_group = {"simulation{} split", split_specs, MRN_COUNT(split_specs)};
