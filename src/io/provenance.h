/* moraine: provenance — what any figure made from an output directory needs
 * to be made again.
 *
 *   OUTDIR/provenance/deck.lua   a byte-for-byte copy of the deck that ran
 *   OUTDIR/provenance/run.txt    one "key: value" line each: moraine version,
 *                                git commit, start time (UTC), host name,
 *                                threads, working directory, the deck's path,
 *                                the full command line (shell-quoted, ready
 *                                to paste) and one "set: NAME=VALUE" line per
 *                                --set, in the order given
 *
 * Both files are written under a temporary name and renamed when complete
 * (io/atomic_file.h). Values are escaped C-style (\n, \t, \\, \xHH) so that
 * each key stays on one line. Files the deck itself reads (dofile, meshes)
 * are not copied. */
#ifndef MRN_IO_PROVENANCE_H
#define MRN_IO_PROVENANCE_H

#include <stddef.h>

/* Write OUTDIR/provenance/{deck.lua,run.txt}, making the directories as
 * needed; call it once when the run starts (the start time is the time of
 * the call, the thread count is OpenMP's at that moment). `deck_path` may be
 * NULL (no copy: run.txt says so); `argv` holds `argc` strings, the command
 * line as main() got it; `sets` holds the `nsets` NAME=VALUE strings of
 * --set. 0 or MRN_ERR_IO with the file in the message. */
int mrn_provenance_write(const char *outdir, const char *deck_path, int argc, const char *const *argv,
                         const char *const *sets, int nsets);
/* The same for a deck read from standard input (moraine -): `text`, `len`
 * bytes, is the copy and run.txt says "deck: - (standard input)". */
int mrn_provenance_write_text(const char *outdir, const char *text, size_t len, int argc, const char *const *argv,
                              const char *const *sets, int nsets);

#endif
