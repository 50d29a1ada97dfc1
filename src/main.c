/* moraine: the command line.
 *
 *   moraine DECK.lua [-o OUTDIR] [--set NAME=VALUE ...] [--threads N] [--quiet] [--safe]
 *   moraine --help | --version | --list-options
 *   moraine --sign-checkpoint FILE...
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/warn.h"
#include "io/atomic_file.h"
#include "io/checkpoint.h"
#include "io/h5util.h"
#include "io/summary.h"
#include "core/spec.h"
#include "lua/moraine_lua.h"

#include <lauxlib.h>
#include <lualib.h>

static void usage(FILE *f) {
  fprintf(f,
          "usage: moraine DECK.lua [options]\n"
          "\n"
          "Runs a Material Point Method simulation described by a Lua deck.\n"
          "\n"
          "options:\n"
          "  -o, --output DIR     directory for every output file and the run log\n"
          "                       log.txt (default: out)\n"
          "  --set NAME=VALUE     a parameter the deck reads with mpm.param(\"NAME\", default);\n"
          "                       may be repeated\n"
          "  --threads N          number of OpenMP threads (default: all cores)\n"
          "  -q, --quiet          no thermo lines, progress bar, summary or information\n"
          "                       messages on the screen (log.txt still gets them)\n"
          "  --ignore-warning ID  silence one kind of warning (or 'all'); may be repeated\n"
          "  --safe               restrict the deck: no os.execute, io.popen, C modules,\n"
          "                       binary chunks or debug library, and writes only inside\n"
          "                       the output directory (what it does not stop: doc/security.md)\n"
          "  --list-options       print every deck option with its type, default and unit\n"
          "  --sign-checkpoint FILE...  write the checksum table of checkpoints changed on\n"
          "                       purpose with another program (h5py) anew (doc/checkpoint-format.md)\n"
          "  -h, --help           this text\n"
          "  -v, --version        the version\n"
          "\n"
          "Exit status: 0 on success, 1 on any error (the message names the deck file\n"
          "and line), 2 on a command-line error, 3 when an output file could not be\n"
          "written (disk full, quota, permission: the message names the file; every\n"
          "earlier output stays complete), 130 when SIGINT or SIGTERM stopped the run\n"
          "(after writing a checkpoint; a second signal exits at once).\n"
          "Documentation (doc/ in the source tree; installed in share/doc/moraine):\n"
          "  doc/getting-started.md            install, a first deck, outputs, ParaView\n"
          "  doc/tutorial-column-collapse.md   a complete study step by step\n"
          "  doc/lua-api.md                    every function, option, default, unit and error\n"
          "  doc/validation.md                 how moraine compares with the references\n"
          "  doc/README.md                     the index of all of them\n");
}

static void list_options(void) {
  /* the registry fills up as the Lua module opens */
  lua_State *L = luaL_newstate();
  luaL_openlibs(L);
  mrn_deck_options opt = {0};
  mrn_lua_open(L, &opt);
  lua_close(L);
  for (int g = 0; g < mrn_spec_group_count(); g++) {
    const mrn_spec_group *grp = mrn_spec_group_at(g);
    for (int i = 0; i < grp->count; i++) {
      const mrn_spec *s = &grp->specs[i];
      printf("%s\t%s\t%s\t%s\t%s\n", grp->name, s->key, mrn_spec_type_name(s->type), s->unit ? s->unit : "", s->doc);
    }
  }
}

/* --sign-checkpoint FILE...: 0, or 1 when a file could not be signed */
static int sign_checkpoints(int count, char **files) {
  if (count == 0) {
    fprintf(stderr, "moraine: option '--sign-checkpoint' needs a file\n");
    return 2;
  }
  mrn_h5_quiet hdf5;
  mrn_h5_silence(&hdf5);
  int rc = 0;
  for (int i = 0; i < count; i++) {
    if (mrn_checkpoint_sign(files[i]) == MRN_OK) {
      printf("signed '%s'\n", files[i]);
    } else {
      fprintf(stderr, "moraine: %s\n", mrn_error_message());
      rc = 1;
    }
  }
  return rc;
}

/* what the command line asks for */
typedef struct cli {
  const char *deck;
  mrn_deck_options opt;
  const char **sets; /* the NAME=VALUE of every --set */
  int nsets;
} cli;

#define GO_ON (-1) /* a parsing step's answer when moraine is not done yet */

/* the options that print something and exit: their exit status, or GO_ON for any other */
static int informational_option(const char *a, int argc, char **argv, int i) {
  if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
    usage(stdout);
    return 0;
  }
  if (!strcmp(a, "-v") || !strcmp(a, "--version")) {
    printf("moraine %s (commit %s)\n", MORAINE_VERSION, MORAINE_GIT_COMMIT);
    return 0;
  }
  if (!strcmp(a, "--list-options")) {
    list_options();
    return 0;
  }
  if (!strcmp(a, "--sign-checkpoint")) return sign_checkpoints(argc - i - 1, argv + i + 1);
  return GO_ON;
}

/* the value of option `a`: GO_ON when valid, else 2 with the message printed */
static int value_option(const char *a, const char *value, cli *c) {
  if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
    c->opt.outdir = value;
  } else if (!strcmp(a, "--set")) {
    if (!strchr(value, '=') || value[0] == '=') {
      fprintf(stderr, "moraine: --set expects NAME=VALUE, got '%s'\n", value);
      return 2;
    }
    c->sets[c->nsets++] = value;
  } else if (!strcmp(a, "--ignore-warning")) {
    if (mrn_warning_ignore(value) != MRN_OK) {
      fprintf(stderr, "moraine: --ignore-warning: %s (known: ", mrn_error_message());
      for (const char *const *id = mrn_warning_ids(); *id; id++) fprintf(stderr, "%s, ", *id);
      fprintf(stderr, "all)\n");
      return 2;
    }
  } else { /* --threads */
    char *end;
    long n = strtol(value, &end, 10);
    if (*end || n < 1 || n > 4096) {
      fprintf(stderr, "moraine: --threads expects a positive whole number, got '%s'\n", value);
      return 2;
    }
#ifdef _OPENMP
    omp_set_num_threads((int)n);
#endif
  }
  return GO_ON;
}

static int takes_value(const char *a) {
  return !strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--set") || !strcmp(a, "--ignore-warning") ||
         !strcmp(a, "--threads");
}

/* The arguments in order, each option applied as it comes. GO_ON, or the
 * exit status when moraine is done (an informational option, an error). */
static int parse_args(int argc, char **argv, cli *c) {
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    int rc = informational_option(a, argc, argv, i);
    if (rc != GO_ON) return rc;
    if (!strcmp(a, "--safe")) {
      c->opt.safe = 1;
    } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
      mrn_log_set_quiet(1);
    } else if (takes_value(a)) {
      if (++i >= argc) {
        fprintf(stderr, "moraine: option '%s' needs a value\n", argv[argc - 1]);
        return 2;
      }
      if ((rc = value_option(a, argv[i], c)) != GO_ON) return rc;
    } else if (a[0] == '-' && a[1]) {
      fprintf(stderr, "moraine: unknown option '%s' (see moraine --help)\n", a);
      return 2;
    } else if (!c->deck) {
      c->deck = a;
    } else {
      fprintf(stderr, "moraine: more than one deck given ('%s' and '%s')\n", c->deck, a);
      return 2;
    }
  }
  if (!c->deck) {
    usage(stderr);
    return 2;
  }
  return GO_ON;
}

static int log_open; /* from open_run_log to close_run_log */

/* The run log OUTDIR/log.txt, opened before the deck runs: everything moraine
 * and the deck print, up to the summary. `append`: a run that continues
 * another adds to that run's log. GO_ON, or the exit status. */
static int open_run_log(const cli *c, int argc, char **argv, int append) {
  char *path = mrn_path_join(c->opt.outdir, "log.txt");
  int rc = path ? mrn_log_open(path, append) : mrn_error_code(MRN_ERR_IO, "out of memory");
  free(path);
  if (rc != MRN_OK) {
    mrn_log_error("%s", mrn_error_message());
    return MRN_EXIT_OUTPUT;
  }
  char date[32];
  time_t t = time(NULL);
  strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", gmtime(&t));
  /* the first line, one message: the version, the date and the command */
  char head[4096];
  size_t len =
      (size_t)snprintf(head, sizeof head, "moraine %s (commit %s), %s:", MORAINE_VERSION, MORAINE_GIT_COMMIT, date);
  for (int i = 0; i < argc && len < sizeof head; i++)
    len += (size_t)snprintf(head + len, sizeof head - len, " %s", argv[i]);
  mrn_log_printf(NULL, "%s\n", head);
  log_open = 1;
  return GO_ON;
}

/* how the run ended, in words, for the summary */
static const char *status_text(int rc, char *buf, size_t len) {
  const char *msg = mrn_log_last_error();
  if (rc == 0) return "ok (exit status 0)";
  const char *how = rc == MRN_EXIT_INTERRUPTED ? "interrupted"
                    : rc == MRN_EXIT_OUTPUT    ? "an output could not be written"
                    : strstr(msg, "the watchdog stopped the run") ? "stopped by the watchdog"
                                                                  : "failed";
  snprintf(buf, len, "%s (exit status %d): %s", how, rc, msg);
  return buf;
}

/* A log that could not be written is an output error (exit status 3) for a
 * run that would otherwise succeed or stop on a signal; its message is
 * printed unless the run already did. */
static int log_failure_status(int rc) {
  if (!mrn_log_failed()) return rc;
  if (!strstr(mrn_log_last_error(), mrn_log_failure())) mrn_log_error("%s", mrn_log_failure());
  return rc == 0 || rc == MRN_EXIT_INTERRUPTED ? MRN_EXIT_OUTPUT : rc;
}

/* the summary, and the log closed: the exit status */
static int close_run_log(int rc) {
  log_open = 0;
  rc = log_failure_status(rc);
  char status[2200];
  mrn_summary_print(status_text(rc, status, sizeof status));
  mrn_summary_end();
  mrn_log_close();
  return log_failure_status(rc); /* its last sync or close */
}

/* a deck that calls os.exit() ends the process here, with its summary */
static void close_run_log_at_exit(void) {
  if (!log_open) return;
  mrn_summary_print("ended by os.exit() in the deck");
  mrn_summary_end();
  mrn_log_close();
}

/* the deck, once the command line is read; the exit status */
static int run(int argc, char **argv, cli *c) {
  /* the output directory exists before the deck runs, so decks can write there too */
  if (mrn_mkdir_p(c->opt.outdir) != 0) {
    fprintf(stderr, "moraine: %s\n", mrn_error_message());
    return 1;
  }
  int rc = open_run_log(c, argc, argv, 0);
  if (rc != GO_ON) return rc;
  mrn_summary_start();
  atexit(close_run_log_at_exit);
  c->opt.sets = c->sets;
  c->opt.nsets = c->nsets;
  c->opt.argv = (const char *const *)argv;
  c->opt.argc = argc;
  mrn_interrupt_install();
  /* moraine reports every HDF5 failure in its own words; HDF5's printing
   * stays off to the end, when HDF5 1.10 would otherwise complain
   * ("infinite loop closing library") about the blocks it lost reading a
   * damaged file of format version 1, which has no checksums */
  mrn_h5_quiet hdf5;
  mrn_h5_silence(&hdf5);
  rc = mrn_lua_run_deck(c->deck, &c->opt);
  /* a signal stopped the run; unless what it leaves could not be written */
  if (rc && rc != MRN_EXIT_OUTPUT && mrn_interrupt_pending()) rc = MRN_EXIT_INTERRUPTED;
  return close_run_log(rc);
}

int main(int argc, char **argv) {
  cli c = {0};
  c.opt.outdir = "out";
  c.sets = calloc((size_t)argc + 1, sizeof *c.sets);
  int rc = parse_args(argc, argv, &c);
  if (rc == GO_ON) rc = run(argc, argv, &c);
  free(c.sets);
  return rc;
}
