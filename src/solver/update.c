/* moraine: the material-point update of the explicit step (see update.h). */
#include "solver/update.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "material/advance.h"
#include "material/user.h"
#include "transfer/kernels.h"
#include "transfer/volumetric.h"

typedef struct chunk_ctx {
  mrn_sim *sim;
  double dt;
} chunk_ctx;

/* Kinematics and constitutive update of particles [lo, hi) (at most
 * MRN_GRADIENT_CHUNK) from their velocity gradients L (9 per particle), in
 * runs of one material, with the energies weighted by the mid-step volume
 * (000, Eqs. 64-65) added in the same pass. Returns the first particle whose
 * F would invert, or -1. A gradient sink (transfer/kernels.h). */
static long update_chunk(void *ctx, size_t lo, size_t hi, const double *L) {
  const chunk_ctx *c = ctx;
  mrn_sim *sim = c->sim;
  mrn_particles *ps = &sim->particles;
  const int stride = ps->state_stride;
  long first_bad = -1;
  for (size_t a = lo, b; a < hi; a = b) {
    for (b = a + 1; b < hi && ps->material[b] == ps->material[a];) b++;
    const mrn_energy_sums energy = {ps->vol0 + a, ps->e_elastic + a, ps->w_plastic + a};
    long bad = mrn_material_advance_points(sim->materials[ps->material[a]], sim->dim, MRN_F_UPDATE_MIDPOINT, c->dt,
                                           b - a, L + 9 * (a - lo), ps->F + (size_t)mrn_tensor_stride(sim->dim) * a,
                                           ps->stress + 6 * a, ps->strain + 6 * a,
                                           stride ? ps->state + (size_t)stride * a : NULL,
                                           stride, &energy, NULL);
    if (bad >= 0 && first_bad < 0) first_bad = (long)a + bad;
  }
  return first_bad;
}

static int inverted_error(const mrn_sim *sim, long p, double dt) {
  const double *x = sim->particles.x + 3 * p;
  return mrn_error_code(MRN_ERR_STATE,
                        "step %ld: particle %lld at (%g, %g, %g) would invert (det F <= 0); "
                        "the time step %g s is probably too large",
                        sim->step + 1, (long long)sim->particles.id[p], x[0], x[1], x[2], dt);
}

/* The outcome of a material pass: a user material's failed law (its
 * message), else the first inverted particle, else MRN_OK. */
static int pass_result(const mrn_sim *sim, long bad, double dt) {
  for (int i = 0; i < sim->nmaterials; i++) {
    int rc = mrn_material_user_failure(sim->materials[i]);
    if (rc) return rc;
  }
  return bad >= 0 ? inverted_error(sim, bad, dt) : MRN_OK;
}

int mrn_update_from_grid(mrn_sim *sim, mrn_transfer *tr, const double *gvel, double dt) {
  chunk_ctx c = {sim, dt};
  const mrn_gradient_sink sink = {update_chunk, &c, MRN_PHASE_STRESS};
  return pass_result(sim, mrn_gradient(tr, gvel, &sink), dt);
}

int mrn_update_from_gradients(mrn_sim *sim, const double *L, double dt) {
  const double t0 = mrn_phase_begin();
  chunk_ctx c = {sim, dt};
  const long n = (long)sim->particles.n, nchunks = (n + MRN_GRADIENT_CHUNK - 1) / MRN_GRADIENT_CHUNK;
  long bad = n;
  /* the chunks are independent (a user material's law serialises itself) and
   * the lowest rejected index is the same for any thread count */
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS) reduction(min : bad)
  for (long k = 0; k < nchunks; k++) {
    const long lo = k * MRN_GRADIENT_CHUNK, hi = lo + MRN_GRADIENT_CHUNK < n ? lo + MRN_GRADIENT_CHUNK : n;
    const long b = update_chunk(&c, (size_t)lo, (size_t)hi, L + 9 * lo);
    if (b >= 0 && b < bad) bad = b;
  }
  mrn_phase_end(MRN_PHASE_STRESS, t0);
  return pass_result(sim, bad < n ? bad : -1, dt);
}

int mrn_update_then_force(mrn_sim *sim, mrn_transfer *tr, const double *gvel, double dt) {
  if (!mrn_update_force_fused(tr)) {
    int rc = mrn_update_from_grid(sim, tr, gvel, dt);
    if (rc) return rc;
    mrn_blocks_reuse(tr->blocks); /* the particles have not moved since the first P2G */
    mrn_p2g(tr, 0, 1);
    return MRN_OK;
  }
  chunk_ctx c = {sim, dt};
  const mrn_gradient_sink sink = {update_chunk, &c, MRN_PHASE_STRESS};
  return pass_result(sim, mrn_update_force(tr, gvel, &sink), dt);
}

int mrn_update_with_g2p(mrn_sim *sim, mrn_transfer *tr, double dt_move, double dt_stress, const mrn_particle_pass *after,
                        long *after_bad) {
  chunk_ctx c = {sim, dt_stress};
  const mrn_gradient_sink sink = {update_chunk, &c, MRN_PHASE_STRESS};
  return pass_result(sim, mrn_g2p_then(tr, dt_move, NULL, &sink, after, after_bad), dt_stress);
}

/* a gradient sink that keeps the gradients of every particle (9 each) */
static long store_chunk(void *ctx, size_t lo, size_t hi, const double *L) {
  memcpy((double *)ctx + 9 * lo, L, 9 * (hi - lo) * sizeof(double));
  return -1;
}

/* 12 doubles per particle: the gradients, then the averaging's scratch */
static double *fbar_buffer(mrn_sim *sim) {
  const size_t need = 12 * sim->particles.n;
  if (need > sim->fbar_cap) {
    double *b = realloc(sim->fbar, need * sizeof(double));
    if (!b) return NULL;
    sim->fbar = b, sim->fbar_cap = need;
  }
  return sim->fbar;
}

/* The chains with the material update under scheme volumetric = "fbar":
 * a particle's L~ needs the nodal sums of every particle's divergence
 * (transfer/volumetric.h), so the stages become passes of their own:
 * gradient from gvel (the particles where the last P2G saw them: before
 * G2P moves them, as the fused G2P takes it), the average, the material
 * update, then the internal force and G2P as the chain asks. */
static int stages_fbar(mrn_sim *sim, mrn_transfer *tr, mrn_particle_stages *s) {
  const unsigned st = s->stages;
  const size_t n = sim->particles.n;
  s->end_bad = -1;
  double *L = fbar_buffer(sim);
  if (!L && n) return mrn_error("step: out of memory for the volumetric averaging");
  const mrn_gradient_sink keep = {store_chunk, L, MRN_PHASE_G2P};
  mrn_gradient(tr, s->gvel, &keep);
  const double t0 = mrn_phase_begin();
  mrn_volumetric_average(tr, L, L + 9 * n);
  mrn_phase_end(MRN_PHASE_G2P, t0);
  const int rc = mrn_update_from_gradients(sim, L, s->material_dt);
  if (rc) return rc;
  if (st & MRN_STAGE_FORCE) {
    mrn_blocks_reuse(tr->blocks); /* the particles have not moved since the first P2G */
    mrn_p2g(tr, 0, 1);
  }
  if (st & MRN_STAGE_MOVE) mrn_g2p_then(tr, s->move_dt, s->dx, NULL, (st & MRN_STAGE_END) ? s->end : NULL, &s->end_bad);
  return MRN_OK;
}

int mrn_particle_stages_run(mrn_sim *sim, mrn_transfer *tr, mrn_particle_stages *s) {
  const unsigned st = s->stages, update = MRN_STAGE_GRADIENT | MRN_STAGE_MATERIAL;
  if ((st & update) == update && sim->scheme.volumetric == MRN_VOLUMETRIC_FBAR) return stages_fbar(sim, tr, s);
  const mrn_particle_pass *end = (st & MRN_STAGE_END) ? s->end : NULL;
  s->end_bad = -1;
  if (st & MRN_STAGE_MOVE) {
    if (!(st & (update | MRN_STAGE_FORCE))) {
      mrn_g2p_then(tr, s->move_dt, s->dx, NULL, end, &s->end_bad);
      return MRN_OK;
    }
    /* G2P gathers the gradient from the updated grid velocity */
    if ((st & update) == update && !(st & MRN_STAGE_FORCE) && !s->dx && s->gvel == tr->grid->vel_new)
      return mrn_update_with_g2p(sim, tr, s->move_dt, s->material_dt, end, &s->end_bad);
  } else if ((st & update) == update && !(st & MRN_STAGE_END)) {
    return (st & MRN_STAGE_FORCE) ? mrn_update_then_force(sim, tr, s->gvel, s->material_dt)
                                  : mrn_update_from_grid(sim, tr, s->gvel, s->material_dt);
  }
  return mrn_error("step: no pass over the particles chains the stages %#x", st);
}
