/* moraine: declarative descriptions of options.
 *
 * Every option a user can set (a material parameter, a key of a Lua argument
 * table) is described once by an mrn_spec: its name, type, default, allowed
 * range, unit and a one-line description. The Lua layer validates decks
 * against these tables, materials read their parameters through them, and
 * `moraine --list-options` prints them all so the API reference can be checked
 * against the code. */
#ifndef MRN_CORE_SPEC_H
#define MRN_CORE_SPEC_H

#include <stddef.h>

typedef enum {
  MRN_SPEC_NUMBER,   /* a real number, checked against [min, max] */
  MRN_SPEC_INTEGER,  /* a whole number, checked against [min, max] */
  MRN_SPEC_BOOLEAN,
  MRN_SPEC_STRING,   /* free text or, with `choices`, one of a list */
  MRN_SPEC_VECTOR,   /* a table of `dim` numbers */
  MRN_SPEC_TABLE,    /* a nested table with its own checks */
  MRN_SPEC_FUNCTION, /* a Lua function */
  MRN_SPEC_ANY       /* several accepted forms, checked by the reader */
} mrn_spec_type;

/* bounds: a value must satisfy min <= v <= max, or min < v when min_open */
typedef struct mrn_spec {
  const char *key;
  mrn_spec_type type;
  int required;
  double def;        /* default for numbers (ignored when required) */
  double min, max;
  int min_open;      /* 1: the lower bound is exclusive */
  int max_open;      /* 1: the upper bound is exclusive */
  const char *unit;  /* SI unit, "" when dimensionless, NULL when not a number */
  const char *doc;   /* one line for the reference */
  const char *const *choices; /* NULL-terminated list for MRN_SPEC_STRING */
} mrn_spec;

/* A named list of specs ("simulation{}", "material linear_elastic", ...) */
typedef struct mrn_spec_group {
  const char *name;
  const mrn_spec *specs;
  int count;
} mrn_spec_group;

const mrn_spec *mrn_spec_find(const mrn_spec *specs, int count, const char *key);
/* the closest key by edit distance, or NULL when nothing is close */
const char *mrn_spec_suggest(const mrn_spec *specs, int count, const char *key);
/* returns 0 when `value` is a finite number inside the spec's range;
 * otherwise writes a description of the expected range into buf and returns 1 */
int mrn_spec_check_range(const mrn_spec *spec, double value, char *buf, size_t len);
/* Levenshtein distance, exposed for other did-you-mean lists */
int mrn_edit_distance(const char *a, const char *b);
/* closest entry of a NULL-terminated list, or NULL */
const char *mrn_suggest_from(const char *const *names, const char *key);
/* The one wording of a suggestion: " (did you mean 'NAME'?)" for a name,
 * "" for NULL. As with mrn_num, the text lives until the end of the full
 * expression: mrn_error("unknown key '%s'%s", key, mrn_hint(name).s) */
typedef struct mrn_hint_text {
  char s[112];
} mrn_hint_text;
mrn_hint_text mrn_hint(const char *suggestion);

/* registry of every spec group, for --list-options */
void mrn_spec_register_group(const char *name, const mrn_spec *specs, int count);
int mrn_spec_group_count(void);
const mrn_spec_group *mrn_spec_group_at(int i);
const char *mrn_spec_type_name(mrn_spec_type t);

#endif
