/* moraine: the methods of a distributed run — sim:set_parallel,
 * sim:parallel, sim:rebalance (solver/dist.h, doc/parallel.md). */
#include <math.h>

#include "core/comm.h"
#include "core/error.h"
#include "lua/lua_check.h"
#include "lua/lua_sim.h"
#include "solver/dist.h"

static const mrn_spec parallel_specs[] = {
    {"rebalance_every", MRN_SPEC_INTEGER, 0, MRN_DIST_REBALANCE_EVERY, 0, 1e15, 0, 0, "steps",
     "re-cut the slabs by particle count every this many steps (0: never)", NULL},
    {"imbalance", MRN_SPEC_NUMBER, 0, MRN_DIST_IMBALANCE, 1, HUGE_VAL, 0, 0, "",
     "re-cut only when the largest particle count exceeds the mean by this factor", NULL},
};

const mrn_spec_group mrn_lua_parallel_group = {"set_parallel{}", parallel_specs, MRN_COUNT(parallel_specs)};

/* sim:set_parallel{rebalance_every, imbalance} */
int l_sim_set_parallel(lua_State *L) {
  sim_box *b = mrn_lua_sim_check_idle(L, 1, "set_parallel()");
  const int n = MRN_COUNT(parallel_specs);
  mrn_lua_check_table(L, 2, "set_parallel()", parallel_specs, n);
  const long every = mrn_lua_get_integer(L, 2, "set_parallel()", parallel_specs, n, "rebalance_every");
  const double imbalance = mrn_lua_get_number(L, 2, "set_parallel()", parallel_specs, n, "imbalance");
  mrn_lua_active = L;
  if (mrn_sim_set_rebalance(b->sim, every, imbalance) != MRN_OK) mrn_lua_engine_error(L, "set_parallel()");
  return 0;
}

static void set_number(lua_State *L, const char *key, double v) {
  lua_pushnumber(L, v);
  lua_setfield(L, -2, key);
}

static void set_integer(lua_State *L, const char *key, lua_Integer v) {
  lua_pushinteger(L, v);
  lua_setfield(L, -2, key);
}

/* sim:parallel() -> {rank, size, particles (this process's), cuts, halo,
 * halo_bytes, migrate_bytes, migrated, rebalances} */
int l_sim_parallel(lua_State *L) {
  sim_box *b = mrn_lua_sim_check(L, 1);
  const mrn_dist *d = b->sim->dist;
  lua_createtable(L, 0, 10);
  set_integer(L, "rank", mrn_comm_rank());
  set_integer(L, "size", mrn_comm_size());
  set_integer(L, "particles", (lua_Integer)b->sim->particles.n);
  set_integer(L, "rebalance_every", b->sim->rebalance_every);
  set_number(L, "imbalance", b->sim->rebalance_imbalance);
  if (!d) return 1;
  lua_createtable(L, d->size + 1, 0);
  for (int r = 0; r <= d->size; r++) {
    lua_pushinteger(L, d->cut[r]);
    lua_rawseti(L, -2, r + 1);
  }
  lua_setfield(L, -2, "cuts");
  set_integer(L, "halo", d->halo);
  set_number(L, "halo_bytes", d->halo_bytes);
  set_number(L, "migrate_bytes", d->migrate_bytes);
  set_integer(L, "migrated", d->migrated);
  set_integer(L, "rebalances", d->rebalances);
  return 1;
}

/* sim:rebalance(): re-cut the slabs by particle count now (collective) */
int l_sim_rebalance(lua_State *L) {
  sim_box *b = mrn_lua_sim_check_idle(L, 1, "rebalance()");
  mrn_lua_active = L;
  if (mrn_dist_rebalance(b->sim) != MRN_OK) mrn_lua_engine_error(L, "rebalance()");
  return 0;
}
