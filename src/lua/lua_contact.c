/* moraine: contact between bodies from Lua — sim:add_contact{...}
 * (solver/contact.h). The bodies are named in add_particles{body = ...}. */
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "lua/lua_check.h"
#include "lua/lua_internal.h"
#include "lua/lua_sim.h"
#include "solver/contact.h"

static const char *const kind_choices[] = {"friction", "frictionless", "bonded", NULL};
static const mrn_spec contact_specs[] = {
    {"bodies", MRN_SPEC_TABLE, 1, 0, 0, 0, 0, 0, NULL, "the two bodies, {\"a\", \"b\"}, named in add_particles{body}", NULL},
    {"kind", MRN_SPEC_STRING, 0, 0, 0, 0, 0, 0, NULL, "friction (default), frictionless or bonded", kind_choices},
    {"mu", MRN_SPEC_NUMBER, 0, 0.0, 0.0, HUGE_VAL, 0, 1, "", "Coulomb friction coefficient (friction)", NULL},
    {"normal", MRN_SPEC_VECTOR, 0, 0, -HUGE_VAL, HUGE_VAL, 0, 0, "",
     "a fixed contact normal from the first body into the second (a flat interface; default: from the mass gradients)",
     NULL},
};
#define NSPECS MRN_COUNT(contact_specs)

/* sim:add_contact{bodies = {"a", "b"}, kind = "friction", mu = 0.3} */
static int l_sim_add_contact(lua_State *L) {
  const char *where = "add_contact{}";
  sim_box *b = mrn_lua_sim_check_idle(L, 1, where);
  mrn_lua_check_table(L, 2, where, contact_specs, NSPECS);
  if (b->sim->integrator.step)
    mrn_lua_error(L, where, "the simulation steps with the implicit integrator, which does not take contact");
  lua_getfield(L, 2, "bodies");
  const char *names[2] = {NULL, NULL};
  if (luaL_len(L, -1) != 2) mrn_lua_error(L, where, "bodies: two body names are needed, {\"a\", \"b\"}");
  for (int k = 0; k < 2; k++) {
    lua_rawgeti(L, -1 - k, k + 1);
    if (lua_type(L, -1) != LUA_TSTRING) mrn_lua_error(L, where, "bodies[%d]: a body name (string) is needed", k + 1);
    names[k] = lua_tostring(L, -1);
  }
  const char *kind = mrn_lua_has(L, 2, "kind") ? mrn_lua_get_string(L, 2, where, contact_specs, NSPECS, "kind") : "friction";
  mrn_lua_check_choice(L, where, "kind", kind, kind_choices);
  if (strcmp(kind, "friction") == 0 && !mrn_lua_has(L, 2, "mu"))
    mrn_lua_error(L, where, "mu: friction contact needs mu (or kind = \"frictionless\")");
  const double mu = strcmp(kind, "friction") == 0 ? mrn_lua_get_number(L, 2, where, contact_specs, NSPECS, "mu") : 0.0;
  const mrn_contact_kind k = strcmp(kind, "bonded") == 0 ? MRN_CONTACT_BONDED : MRN_CONTACT_FRICTION;
  double normal[3] = {0, 0, 0};
  const int given = mrn_lua_get_vector(L, 2, where, contact_specs, NSPECS, "normal", b->sim->dim, normal, 0);
  if (mrn_sim_add_contact(b->sim, names[0], names[1], k, mu, given ? normal : NULL)) mrn_lua_engine_error(L, where);
  lua_pop(L, 3);
  return 0;
}

static const luaL_Reg contact_methods[] = {
    {"add_contact", l_sim_add_contact},
    {NULL, NULL},
};

void mrn_lua_add_contact_methods(lua_State *L, int methods) {
  lua_pushvalue(L, methods);
  luaL_setfuncs(L, contact_methods, 0);
  lua_pop(L, 1);
}

const mrn_spec_group mrn_lua_contact_group = {"add_contact{}", contact_specs, NSPECS};
