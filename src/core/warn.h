/* moraine: warnings for legal but suspicious choices.
 *
 * A warning never stops a run: it prints one line to stderr,
 *   moraine: warning [ID]: message (silence: mpm.warnings{ignore = {"ID"}})
 * once per ID and process, so a loop over many simulations is not flooded.
 * Each kind has a stable ID a deck (mpm.warnings{ignore = {...}}) or the
 * command line (--ignore-warning ID) can silence; "all" silences them all. */
#ifndef MRN_CORE_WARN_H
#define MRN_CORE_WARN_H

/* the kinds of warning, for validating ignore lists and for the reference */
typedef struct mrn_warning_kind {
  const char *id;
  const char *doc;
} mrn_warning_kind;

/* NULL-terminated list of the IDs, and the description of each */
const char *const *mrn_warning_ids(void);
const mrn_warning_kind *mrn_warning_find(const char *id);

/* Print the warning unless it is silenced or was already printed.
 * Returns 1 when it was printed. `id` must be one of mrn_warning_ids(). */
int mrn_warning(const char *id, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* silence an ID (or "all"); 0, or MRN_ERR for an unknown ID (message set) */
int mrn_warning_ignore(const char *id);
/* forget every ignore and every "already printed" mark (for tests) */
void mrn_warning_reset(void);
/* how many warnings were printed since the start (or the last reset) */
int mrn_warning_count(void);

#endif
