/* moraine: console messages and the run log.
 *
 * Thermo lines and the deck's prints go to stdout, everything else to
 * stderr; --quiet silences info and thermo output on the screen (warnings,
 * errors and the deck's prints stay).
 *
 * When a run log is open (the command line opens OUTDIR/log.txt), every
 * message printed through here goes to it as well, whether or not --quiet
 * keeps it off the screen. Each message reaches the file with one write(2)
 * as it is printed, so a crash of the process loses none of it; a message
 * cut short by a full disk is taken back, so the file holds whole messages.
 * After the first failed write the log stays closed: mrn_log_failure() names
 * the file and the reason, and the caller stops as for any output error.
 *
 * A progress bar (mrn_log_bar) takes the terminal's last line: every message
 * to the screen clears it first and, when it ends a line, draws it again. */
#ifndef MRN_CORE_LOG_H
#define MRN_CORE_LOG_H

#include <stddef.h>
#include <stdio.h>

void mrn_log_set_quiet(int quiet);
int mrn_log_quiet(void);
void mrn_info(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void mrn_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* `text` on `screen` (stdout, stderr, or NULL for the log alone) and in the log */
void mrn_log_text(FILE *screen, const char *text, size_t len);
void mrn_log_printf(FILE *screen, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* "moraine: MESSAGE" on stderr and in the log; the message is kept for the summary */
void mrn_log_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* the last message of mrn_log_error ("" when none) */
const char *mrn_log_last_error(void);

/* Open the run log `path`: a new file, or with `append` the end of an
 * existing one. A symbolic link in the last component is refused, so the log
 * stays where its name says (the --safe confinement). MRN_OK, or MRN_ERR_IO
 * with the file and the reason in the message. */
int mrn_log_open(const char *path, int append);
/* sync and close it: MRN_OK, or MRN_ERR_IO when that or an earlier write failed */
int mrn_log_close(void);
/* nonzero once a write to the open log failed; the message of that failure */
int mrn_log_failed(void);
const char *mrn_log_failure(void);
/* the file descriptor of the open log, -1 when none (for a signal handler) */
int mrn_log_fd(void);

/* Draw `text` (one line, no newline) as the progress bar on stderr, the
 * caller having checked that stderr is a terminal; mrn_log_bar_end() ends
 * it: with `keep` the bar stays as a line of its own, otherwise it is erased. */
void mrn_log_bar(const char *text);
void mrn_log_bar_end(int keep);

#endif
