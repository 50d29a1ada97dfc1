/* moraine: materials whose update is supplied at run time (see user.h). */
#include "material/user.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

enum { P_DENSITY, P_WAVE_SPEED, P_COUNT };

static const mrn_spec params[P_COUNT] = {
    [P_DENSITY] = {"density", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "kg/m^3", "mass density", NULL},
    [P_WAVE_SPEED] = {"wave_speed", MRN_SPEC_NUMBER, 1, 0, 0, HUGE_VAL, 1, 0, "m/s",
                      "speed of the fastest elastic wave, for time-step estimates (sqrt((lambda + 2 G) / rho))",
                      NULL},
};

/* what a user material owns besides mrn_material */
typedef struct mrn_user_box {
  mrn_material_type type; /* a copy of mrn_material_user with its own history variables */
  char names[MRN_USER_MAX_STATE][32];
  const char *name_ptr[MRN_USER_MAX_STATE];
  mrn_user_law law;
  int failed;          /* the law's error code, 0 while it has not failed */
  char message[2048];  /* its message, kept here: error buffers are per thread */
} mrn_user_box;

static int prepare(mrn_material *m) {
  if (m->user) return MRN_OK;
  /* made without a law (read from a checkpoint): an update that fails */
  m->user = calloc(1, sizeof *m->user);
  if (!m->user) return mrn_error("material lua: out of memory");
  m->user->type = mrn_material_user;
  return MRN_OK;
}

static void record_failure(mrn_user_box *u, int code) {
  u->failed = code;
  snprintf(u->message, sizeof u->message, "%s", mrn_error_message());
}

/* Batches from every thread go through the one critical section: the law
 * (a Lua function) is not reentrant. After a failure the rest of the pass
 * leaves its points with the rotated start-of-step stress. */
static void update(const mrn_material *m, mrn_material_point *pt, int n) {
  mrn_user_box *u = m->user;
#pragma omp critical(mrn_user_material)
  {
    if (!u->failed) {
      if (!u->law.update)
        record_failure(u, mrn_error("material '%s' (lua) has no update function: a material read from a "
                                    "checkpoint gets it back from its deck (--restart)",
                                    m->name));
      else {
        int rc = u->law.update(u->law.ctx, m, pt, n);
        if (rc) record_failure(u, rc);
      }
    }
  }
}

static double wave_speed(const mrn_material *m) { return m->param[P_WAVE_SPEED]; }

const mrn_material_type mrn_material_user = {
    .name = "lua",
    .summary = "a user material: the stress update is a function given by the deck, called per batch of points",
    .params = params,
    .nparams = P_COUNT,
    .nstate = 0,
    .state_names = NULL,
    .rate_form = 1,
    .prepare = prepare,
    .update = update,
    .wave_speed = wave_speed,
};

mrn_material *mrn_material_user_new(int nstate, const char *const *names, const mrn_user_law *law) {
  if (nstate < 0 || nstate > MRN_USER_MAX_STATE)
    return mrn_error("material lua: %d history variables, at most %d", nstate, MRN_USER_MAX_STATE), NULL;
  mrn_user_box *u = calloc(1, sizeof *u);
  mrn_material *m = u ? mrn_material_new(&mrn_material_user) : NULL;
  if (!m) {
    free(u);
    return mrn_error("material lua: out of memory"), NULL;
  }
  u->type = mrn_material_user;
  for (int i = 0; i < nstate; i++) {
    snprintf(u->names[i], sizeof u->names[i], "%s", names[i]);
    u->name_ptr[i] = u->names[i];
  }
  u->type.nstate = nstate;
  u->type.state_names = nstate ? u->name_ptr : NULL;
  if (law) u->law = *law;
  m->type = &u->type;
  m->user = u;
  return m;
}

int mrn_material_is_user(const mrn_material *m) { return m->user != NULL; }

int mrn_material_user_has_law(const mrn_material *m) { return m->user && m->user->law.update; }

int mrn_material_user_failure(const mrn_material *m) {
  mrn_user_box *u = m->user;
  if (!u || !u->failed) return 0;
  int code = u->failed;
  u->failed = 0;
  return mrn_error_code(code, "%s", u->message);
}

void mrn_material_user_free(mrn_material *m) {
  mrn_user_box *u = m->user;
  if (!u) return;
  if (u->law.release) u->law.release(u->law.ctx);
  free(u);
  m->user = NULL;
}
