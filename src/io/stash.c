#include "io/stash.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void mrn_stash_init(mrn_stash *s, int loading) {
  memset(s, 0, sizeof *s);
  s->loading = loading;
}

void mrn_stash_free(mrn_stash *s) {
  for (int i = 0; i < s->n; i++) free(s->v[i].text);
  free(s->v);
  memset(s, 0, sizeof *s);
}

const mrn_stash_value *mrn_stash_find(const mrn_stash *s, const char *name) {
  for (int i = 0; i < s->n; i++)
    if (strcmp(s->v[i].name, name) == 0) return &s->v[i];
  return NULL;
}

int mrn_stash_put(mrn_stash *s, const char *name, mrn_stash_kind kind, double real, int64_t integer, const char *text) {
  if (s->n == s->cap) {
    int cap = s->cap ? 2 * s->cap : 32;
    mrn_stash_value *v = realloc(s->v, (size_t)cap * sizeof *v);
    if (!v) return -1;
    s->v = v;
    s->cap = cap;
  }
  mrn_stash_value *e = &s->v[s->n];
  memset(e, 0, sizeof *e);
  snprintf(e->name, sizeof e->name, "%s", name);
  e->kind = kind;
  e->real = real;
  e->integer = integer;
  if (text && !(e->text = strdup(text))) return -1;
  s->n++;
  return 0;
}

/* a value recorded by a walker; out of memory loses it, and the resumed run
 * then keeps the deck's setting for it */
void mrn_stash_real(mrn_stash *s, const char *name, double *value) {
  if (!s->loading) {
    mrn_stash_put(s, name, MRN_STASH_REAL, *value, 0, NULL);
    return;
  }
  const mrn_stash_value *e = mrn_stash_find(s, name);
  if (e) *value = e->kind == MRN_STASH_REAL ? e->real : (double)e->integer;
}

void mrn_stash_long(mrn_stash *s, const char *name, long *value) {
  if (!s->loading) {
    mrn_stash_put(s, name, MRN_STASH_INT, 0, *value, NULL);
    return;
  }
  const mrn_stash_value *e = mrn_stash_find(s, name);
  if (e && e->kind == MRN_STASH_INT) *value = (long)e->integer;
}

void mrn_stash_int(mrn_stash *s, const char *name, int *value) {
  long v = *value;
  mrn_stash_long(s, name, &v);
  *value = (int)v;
}

void mrn_stash_text(mrn_stash *s, const char *name, char **value) {
  if (!s->loading) {
    mrn_stash_put(s, name, MRN_STASH_TEXT, 0, 0, *value ? *value : "");
    return;
  }
  const mrn_stash_value *e = mrn_stash_find(s, name);
  if (!e || e->kind != MRN_STASH_TEXT) return;
  free(*value);
  *value = e->text && e->text[0] ? strdup(e->text) : NULL;
}
