/* moraine: the command line.
 *
 *   moraine DECK.lua [-o OUTDIR] [--set NAME=VALUE ...] [--threads N] [--quiet] [--safe]
 *                    [--restart CHECKPOINT] [--overwrite]
 *   moraine --help | --version | --list-options
 *   moraine --sign-checkpoint FILE...
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/warn.h"
#include "io/atomic_file.h"
#include "io/checkpoint.h"
#include "io/dirlock.h"
#include "io/h5util.h"
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
          "  -o, --output DIR     directory for every output file (default: out)\n"
          "  --set NAME=VALUE     a parameter the deck reads with mpm.param(\"NAME\", default);\n"
          "                       may be repeated\n"
          "  --threads N          number of OpenMP threads (default: all cores)\n"
          "  --restart FILE       continue the run of a checkpoint (<name>_interrupted.h5,\n"
          "                       <name>_checkpoint_N.h5): the deck runs again and its run{}\n"
          "                       the checkpoint was in goes on from it, its outputs appended to\n"
          "  --overwrite          replace the outputs another run left in the output directory\n"
          "                       (without it such a run is refused, naming the files)\n"
          "  -q, --quiet          no thermo lines, progress bar or information messages\n"
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
  } else if (!strcmp(a, "--restart")) {
    c->opt.restart = value;
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
         !strcmp(a, "--threads") || !strcmp(a, "--restart");
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
    } else if (!strcmp(a, "--overwrite")) {
      c->opt.overwrite = 1;
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
  int locked = mrn_dirlock_take(&lock, c->opt.outdir);
  if (locked != MRN_OK) {
    fprintf(stderr, "moraine: %s\n", mrn_error_message());
    return locked == MRN_ERR_IO ? MRN_EXIT_OUTPUT : 1;
  }
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
  int rc = mrn_lua_run_deck(c->deck, &c->opt);
  mrn_dirlock_release(&lock);
  /* a signal stopped the run; unless what it leaves could not be written */
  if (rc && rc != MRN_EXIT_OUTPUT && mrn_interrupt_pending()) rc = MRN_EXIT_INTERRUPTED;
  return rc;
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
