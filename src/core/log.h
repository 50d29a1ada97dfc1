/* moraine: console messages. Thermo lines go to stdout, everything else to
 * stderr; --quiet silences info and thermo output (warnings and errors stay). */
#ifndef MRN_CORE_LOG_H
#define MRN_CORE_LOG_H

void mrn_log_set_quiet(int quiet);
int mrn_log_quiet(void);
void mrn_info(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void mrn_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
