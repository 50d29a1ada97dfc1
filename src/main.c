/* moraine: the command line.
 *
 *   moraine [OPTION]... DECK.lua        (DECK "-": the deck on stdin)
 *   moraine --help | --version | --list-options
 *   moraine --sign-checkpoint FILE...
 *
 * GNU long options through getopt_long: --output=DIR or --output DIR, any
 * unambiguous abbreviation, options before or after the deck, "--" ends
 * them. Every option is one entry of the table `options` below, which also
 * writes --help (and so the man page help2man makes from it).
 */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/comm.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/warn.h"
#include "io/atomic_file.h"
#include "io/checkpoint.h"
#include "io/dirlock.h"
#include "io/h5util.h"
#include "io/summary.h"
#include "core/spec.h"
#include "lua/moraine_lua.h"

#include <lauxlib.h>
#include <lualib.h>

/* what the command line asks for */
typedef struct cli {
  const char *deck;
  mrn_deck_options opt;
  const char **sets; /* the NAME=VALUE of every --set */
  int nsets;
  int sign;          /* --sign-checkpoint: the operands are checkpoints */
} cli;

#define GO_ON (-1) /* a parsing step's answer when moraine is not done yet */

/* An option's action, with its value (NULL for an option without one): GO_ON,
 * or the exit status when moraine is done (an informational option, or 2
 * with the message printed). */
typedef int (*option_fn)(cli *c, const char *value);

typedef struct cli_option {
  const char *name; /* the long name */
  char short_name;  /* 0: none */
  const char *arg;  /* the value's name in --help; NULL: the option takes none */
  option_fn apply;
  const char *help; /* lines of --help, '\n' between them */
} cli_option;

static void usage(FILE *f);

static int opt_output(cli *c, const char *value) {
  c->opt.outdir = value;
  return GO_ON;
}

static int opt_set(cli *c, const char *value) {
  if (!strchr(value, '=') || value[0] == '=') {
    fprintf(stderr, "moraine: --set expects NAME=VALUE, got '%s'\n", value);
    return 2;
  }
  c->sets[c->nsets++] = value;
  return GO_ON;
}

static int opt_threads(cli *c, const char *value) {
  char *end;
  long n = strtol(value, &end, 10);
  if (end == value || *end || n < 1 || n > 4096) {
    fprintf(stderr, "moraine: --threads expects a positive whole number, got '%s'\n", value);
    return 2;
  }
#ifdef _OPENMP
  omp_set_num_threads((int)n);
#endif
  return GO_ON;
}

static int opt_quiet(cli *c, const char *value) {
  mrn_log_set_quiet(1);
  return GO_ON;
}

static int opt_ignore_warning(cli *c, const char *value) {
  if (mrn_warning_ignore(value) == MRN_OK) return GO_ON;
  fprintf(stderr, "moraine: --ignore-warning: %s (known: ", mrn_error_message());
  for (const char *const *id = mrn_warning_ids(); *id; id++) fprintf(stderr, "%s, ", *id);
  fprintf(stderr, "all)\n");
  return 2;
}

static int opt_safe(cli *c, const char *value) {
  c->opt.safe = 1;
  return GO_ON;
}

static int opt_list_options(cli *c, const char *value) {
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
  return 0;
}

static int opt_sign_checkpoint(cli *c, const char *value) {
  c->sign = 1;
  return GO_ON;
}

static int opt_restart(cli *c, const char *value) {
  c->opt.restart = value;
  return GO_ON;
}

static int opt_overwrite(cli *c, const char *value) {
  c->opt.overwrite = 1;
  return GO_ON;
}

static int opt_help(cli *c, const char *value) {
  usage(stdout);
  return 0;
}

static int opt_version(cli *c, const char *value) {
  printf("moraine %s (commit %s)\n", MORAINE_VERSION, MORAINE_GIT_COMMIT);
  return 0;
}

static const cli_option options[] = {
    {"output", 'o', "DIR", opt_output, "directory for every output file and the run log log.txt\n(default: out)"},
    {"set", 0, "NAME=VALUE", opt_set,
     "a parameter the deck reads with mpm.param(\"NAME\", default);\nmay be repeated; a NAME the deck never "
     "reads is\nwarned about at the end"},
    {"threads", 0, "N", opt_threads, "number of OpenMP threads (default: all cores)"},
    {"restart", 0, "FILE", opt_restart,
     "continue the run of a checkpoint (<name>_interrupted.h5,\n<name>_checkpoint_N.h5): the deck runs again and the run{}\n"
     "the checkpoint was in goes on from it, its outputs appended to"},
    {"overwrite", 0, NULL, opt_overwrite,
     "replace the outputs another run left in the output directory\n(without it such a run is refused, naming the "
     "files)"},
    {"quiet", 'q', NULL, opt_quiet, "no thermo lines, progress bar, summary or information\nmessages on the screen (log.txt still gets them)"},
    {"ignore-warning", 0, "ID", opt_ignore_warning, "silence one kind of warning (or 'all'); may be repeated"},
    {"safe", 0, NULL, opt_safe,
     "restrict the deck: no os.execute, io.popen, C modules,\nbinary chunks or debug library, and writes only inside\n"
     "the output directory (what it does not stop: doc/security.md)"},
    {"list-options", 0, NULL, opt_list_options, "print every deck option with its type, default and unit"},
    {"sign-checkpoint", 0, NULL, opt_sign_checkpoint,
     "write the checksum table of the checkpoints given in place\nof the deck anew, for files changed on purpose with "
     "another\nprogram (h5py) (doc/checkpoint-format.md)"},
    {"help", 'h', NULL, opt_help, "this text"},
    {"version", 'v', NULL, opt_version, "the version"},
};
#define NOPTIONS ((int)(sizeof options / sizeof options[0]))

static void usage(FILE *f) {
  fprintf(f, "Usage: moraine [OPTION]... DECK.lua\n"
             "  or:  moraine --sign-checkpoint FILE...\n"
             "Runs a Material Point Method simulation described by a Lua deck;\n"
             "DECK '-' reads the deck from standard input.\n"
             "\n"
             "Options (a long option's value follows '=' or comes as the next word):\n");
  for (int i = 0; i < NOPTIONS; i++) {
    const cli_option *o = &options[i];
    char head[64], letter[8] = "    "; /* the long names in one column */
    if (o->short_name) snprintf(letter, sizeof letter, "-%c, ", o->short_name);
    snprintf(head, sizeof head, "%s--%s%s%s", letter, o->name, o->arg ? " " : "", o->arg ? o->arg : "");
    fprintf(f, "  %-26s ", head);
    for (const char *line = o->help; *line;) {
      size_t n = strcspn(line, "\n");
      fprintf(f, "%.*s\n", (int)n, line);
      line += n + (line[n] == '\n');
      if (*line) fprintf(f, "%29s", "");
    }
  }
  fprintf(f, "\n"
             "Exit status: 0 on success, 1 on any error (the message names the deck file\n"
             "and line), 2 on a command-line error, 3 when an output file could not be\n"
             "written (disk full, quota, permission: the message names the file; every\n"
             "earlier output stays complete), 130 when SIGINT or SIGTERM stopped the run\n"
             "(after writing a checkpoint; a second signal exits at once).\n"
             "\n"
             "Documentation (doc/ in the source tree; installed in share/doc/moraine):\n"
             "  doc/getting-started.md            install, a first deck, outputs, ParaView\n"
             "  doc/tutorial-column-collapse.md   a complete study step by step\n"
             "  doc/lua-api.md                    every function, option, default, unit and error\n"
             "  doc/c-api.md                      the engine from C, without Lua\n"
             "  doc/validation.md                 how moraine compares with the references\n"
             "  doc/README.md                     the index of all of them\n");
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

/* getopt_long's tables from `options`: a short option is its letter, a long
 * one alone is 256 + its index */
static void getopt_tables(struct option *longs, char *shorts) {
  char *s = shorts;
  *s++ = ':'; /* a missing value answers ':', not '?' */
  for (int i = 0; i < NOPTIONS; i++) {
    const cli_option *o = &options[i];
    int val = o->short_name ? o->short_name : 256 + i;
    longs[i] = (struct option){o->name, o->arg ? required_argument : no_argument, NULL, val};
    if (o->short_name) {
      *s++ = o->short_name;
      if (o->arg) *s++ = ':';
    }
  }
  longs[NOPTIONS] = (struct option){NULL, 0, NULL, 0};
  *s = '\0';
}

static const cli_option *option_of(int val) {
  if (val <= 0) return NULL;
  if (val >= 256) return &options[val - 256];
  for (int i = 0; i < NOPTIONS; i++)
    if (options[i].short_name == val) return &options[i];
  return NULL;
}

/* an unknown or ambiguous long option `word` (--NAME or --NAME=VALUE): exit status 2 */
static int unknown_long(const char *word) {
  const char *names[NOPTIONS + 1];
  char given[64], matches[256] = "";
  snprintf(given, sizeof given, "%.*s", (int)strcspn(word + 2, "="), word + 2);
  int nmatch = 0;
  for (int i = 0; i < NOPTIONS; i++) {
    names[i] = options[i].name;
    if (!strncmp(names[i], given, strlen(given)) && ++nmatch)
      snprintf(matches + strlen(matches), sizeof matches - strlen(matches), "%s--%s", nmatch > 1 ? ", " : "", names[i]);
  }
  names[NOPTIONS] = NULL;
  if (nmatch > 1) {
    fprintf(stderr, "moraine: option '%s' is ambiguous: %s\n", word, matches);
  } else {
    const char *near = mrn_suggest_from(names, given);
    char hint[96] = "";
    if (near) snprintf(hint, sizeof hint, " (did you mean '--%s'?)", near);
    fprintf(stderr, "moraine: unknown option '%s'%s (see moraine --help)\n", word, hint);
  }
  return 2;
}

/* the message of what getopt_long refused in `word`: exit status 2 */
static int refused(int answer, const char *word) {
  const cli_option *o = option_of(optopt);
  char letter[3] = {'-', (char)optopt, '\0'}; /* a short option, which may sit inside a cluster such as -qx */
  const int is_long = !strncmp(word, "--", 2);
  if (answer == ':') {
    fprintf(stderr, "moraine: option '%s' needs a value (see moraine --help)\n", is_long ? word : letter);
  } else if (is_long) {
    if (!o) return unknown_long(word);
    fprintf(stderr, "moraine: option '--%s' takes no value, got '%s'\n", o->name, word);
  } else {
    fprintf(stderr, "moraine: unknown option '%s' (see moraine --help)\n", letter);
  }
  return 2;
}

/* The options in order, each applied as it comes, then the operands: the
 * deck, or the checkpoints of --sign-checkpoint. GO_ON, or the exit status
 * when moraine is done (an informational option, an error). */
static int parse_args(int argc, char **argv, cli *c) {
  struct option longs[NOPTIONS + 1];
  char shorts[2 * NOPTIONS + 2];
  getopt_tables(longs, shorts);
  opterr = 0; /* moraine's own messages */
  int answer;
  while ((answer = getopt_long(argc, argv, shorts, longs, NULL)) != -1) {
    const cli_option *o = answer == '?' || answer == ':' ? NULL : option_of(answer);
    if (!o) return refused(answer, argv[optind - 1]);
    int rc = o->apply(c, o->arg ? optarg : NULL);
    if (rc != GO_ON) return rc;
  }
  if (c->sign) return sign_checkpoints(argc - optind, argv + optind);
  if (optind == argc) {
    usage(stderr);
    return 2;
  }
  if (argc - optind > 1) {
    fprintf(stderr, "moraine: more than one deck given ('%s' and '%s')\n", argv[optind], argv[optind + 1]);
    return 2;
  }
  c->deck = argv[optind];
  return GO_ON;
}

static int log_open; /* from open_run_log to close_run_log */

/* The run log OUTDIR/log.txt, opened before the deck runs: everything moraine
 * and the deck print, up to the summary. `append`: the run adds to the log
 * an earlier run left (each run's part starts with its header line).
 * GO_ON, or the exit status. */
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
  /* one run at a time in a directory: a second one would mix its rows and
   * snapshots with this one's */
  mrn_dirlock lock;
  int rc = mrn_dirlock_take(&lock, c->opt.outdir);
  if (rc != MRN_OK) {
    fprintf(stderr, "moraine: %s\n", mrn_error_message());
    return rc == MRN_ERR_IO ? MRN_EXIT_OUTPUT : 1;
  }
  /* an earlier run's log is kept unless its outputs are replaced on purpose */
  if ((rc = open_run_log(c, argc, argv, !c->opt.overwrite)) != GO_ON) {
    mrn_dirlock_release(&lock);
    return rc;
  }
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
  rc = close_run_log(rc);
  mrn_dirlock_release(&lock); /* after the summary: the log is the directory's too */
  return rc;
}

int main(int argc, char **argv) {
  cli c = {0};
  c.opt.outdir = "out";
  c.sets = calloc((size_t)argc + 1, sizeof *c.sets);
  /* getopt_long reorders what it is given: the provenance records the
   * command line as typed */
  char **args = calloc((size_t)argc + 1, sizeof *args);
  if (!c.sets || !args) {
    fprintf(stderr, "moraine: out of memory\n");
    return 1;
  }
  memcpy(args, argv, (size_t)argc * sizeof *args);
  int rc = mrn_comm_init(&argc, &argv); /* under mpirun: one of several processes (doc/parallel.md) */
  if (rc != MRN_OK) {
    fprintf(stderr, "moraine: %s\n", mrn_error_message());
    return 1;
  }
  rc = parse_args(argc, args, &c);
  if (rc == GO_ON) rc = run(argc, argv, &c);
  free(args);
  free(c.sets);
  /* an error met by one process alone leaves the others waiting: stop them */
  if (rc != 0 && rc != MRN_EXIT_INTERRUPTED && mrn_comm_size() > 1 && !mrn_comm_shared_error()) mrn_comm_abort(rc);
  mrn_comm_finalize();
  return rc;
}
