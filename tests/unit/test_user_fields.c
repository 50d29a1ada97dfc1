/* moraine: per-particle fields registered by a deck follow their particles.
 * Each particle's values are set from its id; after growth, a field added
 * late, a reordering (mrn_particles_permute) and a removal
 * (mrn_particles_compact) every particle must still hold its own values. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "particles/particles.h"
#include "particles/sort.h"

static double *value(mrn_particles *p, const char *name, size_t i) {
  const mrn_user_field *f = mrn_particles_user_field(p, name);
  return p->user + i * p->user_stride + f->offset;
}

/* every particle holds a = id, b = (id, -id, 0.5 id), c = 7 (its init) */
static int consistent(mrn_particles *p) {
  for (size_t i = 0; i < p->n; i++) {
    double id = (double)p->id[i];
    double *a = value(p, "a", i), *b = value(p, "b", i), *c = value(p, "c", i);
    if (a[0] != id || b[0] != id || b[1] != -id || b[2] != 0.5 * id || c[0] != 7.0) return 0;
  }
  return 1;
}

int main(void) {
  mrn_particles p;
  mrn_particles_init(&p, 3);
  CHECK(mrn_particles_add_user_field(&p, "a", 1, -1.0, "Pa") == MRN_OK);
  const double x[3] = {0, 0, 0};
  for (int i = 0; i < 300; i++) CHECK(mrn_particles_add(&p, x, 1.0, 1.0, 0) >= 0); /* grows past 256 */
  CHECK(*value(&p, "a", 299) == -1.0); /* the init value */
  CHECK(mrn_particles_add_user_field(&p, "b", 3, 0.0, NULL) == MRN_OK);
  for (size_t i = 0; i < p.n; i++) {
    double id = (double)p.id[i];
    *value(&p, "a", i) = id;
    double *b = value(&p, "b", i);
    b[0] = id, b[1] = -id, b[2] = 0.5 * id;
  }
  /* a field added after the others keeps their values and fills its own */
  CHECK(mrn_particles_add_user_field(&p, "c", 1, 7.0, "") == MRN_OK);
  CHECK(p.user_stride == 5 && p.nuser == 3);
  CHECK(consistent(&p));

  /* refusals */
  CHECK(mrn_particles_add_user_field(&p, "a", 1, 0.0, NULL) != MRN_OK);
  CHECK(strstr(mrn_error_message(), "already registered") != NULL);
  CHECK(mrn_particles_add_user_field(&p, "", 1, 0.0, NULL) != MRN_OK);
  CHECK(mrn_particles_add_user_field(&p, "d", 10, 0.0, NULL) != MRN_OK);

  /* reorder: reverse */
  uint32_t *order = malloc(sizeof *order * p.n);
  for (size_t i = 0; i < p.n; i++) order[i] = (uint32_t)(p.n - 1 - i);
  CHECK(mrn_particles_permute(&p, order) == MRN_OK);
  CHECK(p.id[0] == 300 && consistent(&p));
  free(order);

  /* remove every third particle */
  unsigned char *keep = malloc(p.n);
  for (size_t i = 0; i < p.n; i++) keep[i] = i % 3 != 0;
  mrn_particles_compact(&p, keep);
  free(keep);
  CHECK(p.n == 200 && consistent(&p));

  /* a particle added now starts at every field's init */
  long k = mrn_particles_add(&p, x, 1.0, 1.0, 0);
  CHECK(k == 200 && *value(&p, "a", 200) == -1.0 && value(&p, "b", 200)[2] == 0.0 && *value(&p, "c", 200) == 7.0);
  mrn_particles_free(&p);
  CHECK(p.user == NULL);
  CHECK_DONE();
}
