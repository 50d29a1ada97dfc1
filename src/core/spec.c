#include "core/spec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const mrn_spec *mrn_spec_find(const mrn_spec *specs, int count, const char *key) {
  for (int i = 0; i < count; i++)
    if (strcmp(specs[i].key, key) == 0) return &specs[i];
  return NULL;
}

/* optimal string alignment distance: insertions, deletions, substitutions
 * and transpositions of neighbours each cost 1 ("shpae" is 1 from "shape") */
int mrn_edit_distance(const char *a, const char *b) {
  size_t la = strlen(a), lb = strlen(b);
  if (la > 64 || lb > 64) return 99;
  int d[65][65];
  for (size_t i = 0; i <= la; i++) d[i][0] = (int)i;
  for (size_t j = 0; j <= lb; j++) d[0][j] = (int)j;
  for (size_t i = 1; i <= la; i++)
    for (size_t j = 1; j <= lb; j++) {
      int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      int best = d[i - 1][j] + 1;
      if (d[i][j - 1] + 1 < best) best = d[i][j - 1] + 1;
      if (d[i - 1][j - 1] + cost < best) best = d[i - 1][j - 1] + cost;
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < best)
        best = d[i - 2][j - 2] + 1;
      d[i][j] = best;
    }
  return d[la][lb];
}

/* a suggestion is offered when at most a third of the letters differ, or
 * when the key is the start of a longer name ("quadratic" -> "quadratic_bspline") */
static int close_enough(const char *candidate, const char *key, int distance) {
  size_t len = strlen(key) > strlen(candidate) ? strlen(key) : strlen(candidate);
  if (strlen(key) >= 3 && strncmp(candidate, key, strlen(key)) == 0) return 1;
  return distance <= 1 || (size_t)distance * 3 <= len;
}

/* prefer a name the key starts, then the smallest distance */
static int score(const char *candidate, const char *key) {
  if (strlen(key) >= 3 && strncmp(candidate, key, strlen(key)) == 0) return 0;
  return 1 + mrn_edit_distance(candidate, key);
}

const char *mrn_spec_suggest(const mrn_spec *specs, int count, const char *key) {
  const char *best = NULL;
  int best_d = 1000;
  for (int i = 0; i < count; i++) {
    int d = score(specs[i].key, key);
    if (d < best_d) { best_d = d; best = specs[i].key; }
  }
  return best && close_enough(best, key, best_d ? best_d - 1 : 0) ? best : NULL;
}

const char *mrn_suggest_from(const char *const *names, const char *key) {
  const char *best = NULL;
  int best_d = 1000;
  for (int i = 0; names[i]; i++) {
    int d = score(names[i], key);
    if (d < best_d) { best_d = d; best = names[i]; }
  }
  return best && close_enough(best, key, best_d ? best_d - 1 : 0) ? best : NULL;
}

mrn_hint_text mrn_hint(const char *suggestion) {
  mrn_hint_text t = {""};
  if (suggestion) snprintf(t.s, sizeof t.s, " (did you mean '%.64s'?)", suggestion);
  return t;
}

/* Every non-finite value is refused; a range open at one end or both says
 * "a finite value" then, so that NaN and inf learn what was expected too. */
int mrn_spec_check_range(const mrn_spec *spec, double v, char *buf, size_t len) {
  const int finite = isfinite(v);
  int below = spec->min_open ? !(v > spec->min) : !(v >= spec->min);
  int above = spec->max_open ? !(v < spec->max) : !(v <= spec->max);
  if (finite && !below && !above) return 0;
  const int has_min = spec->min > -HUGE_VAL, has_max = spec->max < HUGE_VAL;
  const char *value = finite ? "a value" : "a finite value";
  if (has_min && has_max)
    snprintf(buf, len, "a value in %s%g, %g%s", spec->min_open ? "(" : "[", spec->min, spec->max,
             spec->max_open ? ")" : "]");
  else if (has_min)
    snprintf(buf, len, "%s %s %g", value, spec->min_open ? ">" : ">=", spec->min);
  else if (has_max)
    snprintf(buf, len, "%s %s %g", value, spec->max_open ? "<" : "<=", spec->max);
  else
    snprintf(buf, len, "a finite value");
  return 1;
}

#define MAX_GROUPS 128
static mrn_spec_group groups[MAX_GROUPS];
static int group_count = 0;

void mrn_spec_register_group(const char *name, const mrn_spec *specs, int count) {
  for (int i = 0; i < group_count; i++)
    if (strcmp(groups[i].name, name) == 0) return;
  if (group_count < MAX_GROUPS) groups[group_count++] = (mrn_spec_group){name, specs, count};
}

int mrn_spec_group_count(void) { return group_count; }
const mrn_spec_group *mrn_spec_group_at(int i) { return &groups[i]; }

const char *mrn_spec_type_name(mrn_spec_type t) {
  switch (t) {
  case MRN_SPEC_NUMBER: return "number";
  case MRN_SPEC_INTEGER: return "integer";
  case MRN_SPEC_BOOLEAN: return "boolean";
  case MRN_SPEC_STRING: return "string";
  case MRN_SPEC_VECTOR: return "vector";
  case MRN_SPEC_TABLE: return "table";
  case MRN_SPEC_FUNCTION: return "function";
  case MRN_SPEC_ANY: return "value";
  }
  return "value";
}
