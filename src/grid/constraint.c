#include "grid/constraint.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"

int mrn_constraint_init(mrn_constraint *c, const mrn_grid *g, mrn_point_test inside, void *ctx, unsigned mask,
                        const double velocity[3]) {
  memset(c, 0, sizeof *c);
  size_t cap = 64;
  c->nodes = malloc(cap * sizeof *c->nodes);
  if (!c->nodes) return mrn_error("constraint: out of memory");
  for (size_t i = 0; i < g->n; i++) {
    int ijk[3];
    mrn_grid_node_ijk(g, i, ijk);
    int inside_domain = 1;
    for (int d = 0; d < g->dim; d++) inside_domain &= ijk[d] >= 0 && ijk[d] <= g->ncell[d];
    if (!inside_domain) continue;
    double x[3];
    mrn_grid_node_position(g, i, x);
    int in = inside(ctx, x);
    if (in < 0) {
      mrn_constraint_free(c);
      return MRN_ERR;
    }
    if (!in) continue;
    if (c->count == cap) {
      size_t *grown = realloc(c->nodes, 2 * cap * sizeof *c->nodes);
      if (!grown) {
        mrn_constraint_free(c);
        return mrn_error("constraint: out of memory");
      }
      c->nodes = grown;
      cap *= 2;
    }
    c->nodes[c->count++] = i;
  }
  if (c->count == 0) {
    mrn_constraint_free(c);
    return mrn_error("constraint: the region contains no grid node");
  }
  c->mask = mask;
  memcpy(c->velocity, velocity, sizeof c->velocity);
  return MRN_OK;
}

void mrn_constraint_free(mrn_constraint *c) {
  free(c->nodes);
  c->nodes = NULL;
  c->count = 0;
}

void mrn_constraint_apply(mrn_constraint *c, const mrn_grid *g, double *vel, double floor_mass, double dt) {
  double reaction[3] = {0, 0, 0};
  for (size_t k = 0; k < c->count; k++) {
    size_t n = c->nodes[k];
    double m = g->mass[n];
    if (!(m > floor_mass)) continue;
    for (int d = 0; d < 3; d++) {
      if (!(c->mask & (1u << d))) continue;
      if (dt > 0.0 && mrn_grid_owns(g, (long)n)) reaction[d] += m * (c->velocity[d] - vel[3 * n + d]) / dt;
      vel[3 * n + d] = c->velocity[d];
    }
  }
  if (dt > 0.0) memcpy(c->reaction, reaction, sizeof reaction);
}
