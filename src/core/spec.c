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

int mrn_edit_distance(const char *a, const char *b) {
  size_t la = strlen(a), lb = strlen(b);
  if (la > 64 || lb > 64) return 99;
  int prev[65], cur[65];
  for (size_t j = 0; j <= lb; j++) prev[j] = (int)j;
  for (size_t i = 1; i <= la; i++) {
    cur[0] = (int)i;
    for (size_t j = 1; j <= lb; j++) {
      int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      int best = prev[j] + 1;
      if (cur[j - 1] + 1 < best) best = cur[j - 1] + 1;
      if (prev[j - 1] + cost < best) best = prev[j - 1] + cost;
      cur[j] = best;
    }
    memcpy(prev, cur, sizeof(int) * (lb + 1));
  }
  return prev[lb];
}

/* a suggestion is offered when at most a third of the letters differ */
static int close_enough(const char *candidate, const char *key, int distance) {
  size_t len = strlen(key) > strlen(candidate) ? strlen(key) : strlen(candidate);
  return distance <= 1 || (size_t)distance * 3 <= len;
}

const char *mrn_spec_suggest(const mrn_spec *specs, int count, const char *key) {
  const char *best = NULL;
  int best_d = 1000;
  for (int i = 0; i < count; i++) {
    int d = mrn_edit_distance(specs[i].key, key);
    if (d < best_d) { best_d = d; best = specs[i].key; }
  }
  return best && close_enough(best, key, best_d) ? best : NULL;
}

const char *mrn_suggest_from(const char *const *names, const char *key) {
  const char *best = NULL;
  int best_d = 1000;
  for (int i = 0; names[i]; i++) {
    int d = mrn_edit_distance(names[i], key);
    if (d < best_d) { best_d = d; best = names[i]; }
  }
  return best && close_enough(best, key, best_d) ? best : NULL;
}

int mrn_spec_check_range(const mrn_spec *spec, double v, char *buf, size_t len) {
  if (!isfinite(v)) {
    snprintf(buf, len, "a finite number");
    return 1;
  }
  int below = spec->min_open ? !(v > spec->min) : !(v >= spec->min);
  int above = spec->max_open ? !(v < spec->max) : !(v <= spec->max);
  if (!below && !above) return 0;
  int has_min = spec->min > -HUGE_VAL, has_max = spec->max < HUGE_VAL;
  if (has_min && has_max)
    snprintf(buf, len, "a value in %s%g, %g%s", spec->min_open ? "(" : "[", spec->min, spec->max,
             spec->max_open ? ")" : "]");
  else if (has_min)
    snprintf(buf, len, "a value %s %g", spec->min_open ? ">" : ">=", spec->min);
  else
    snprintf(buf, len, "a value %s %g", spec->max_open ? "<" : "<=", spec->max);
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
