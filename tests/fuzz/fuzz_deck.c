/* moraine fuzzing: the deck API.
 *
 * Each input is decoded by tests/fuzz/deck_driver.lua into a sequence of
 * calls of the real `moraine` Lua module (materials, regions, simulations and
 * every simulation method) with arguments drawn from the input: numbers
 * including NaN, infinities, negatives and huge values, strings, booleans,
 * functions, objects, and tables with known and unknown keys. The known keys
 * come from the engine's own option tables (mrn_spec groups), so new options
 * are fuzzed as soon as they exist. Each call runs under pcall: an error
 * message is the expected answer to a bad call; a crash, a hang or a
 * sanitizer report is a finding.
 *
 * Runs are bounded: a timer triggers moraine's own interrupt after one
 * second of CPU time in one input, so a legal but long run (run{time = 1e6})
 * stops at the end of its current step as after SIGINT. */
#include <lauxlib.h>
#include <lualib.h>
#include <signal.h>
#include <sys/time.h>
#include <unistd.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/spec.h"
#include "io/output.h"
#include "lua/moraine_lua.h"

#include "fuzz_common.h"

#ifndef MORAINE_FUZZ_DIR
#error "MORAINE_FUZZ_DIR (tests/fuzz) must be defined"
#endif

static char workdir[64];
static char *driver;     /* the source of deck_driver.lua */
static size_t driver_len;
static volatile sig_atomic_t budget_spent;
static void (*moraine_on_signal)(int); /* moraine's SIGTERM handler */

/* The first timer tick of an input asks the run to stop, exactly as one
 * SIGTERM would: moraine's handler is called directly, because the signals
 * themselves belong to libFuzzer (and SIGALRM to its -timeout). */
static void on_budget(int sig) {
  (void)sig;
  if (!budget_spent) {
    budget_spent = 1;
    moraine_on_signal(SIGTERM);
  }
}

static void remove_tree(const char *dir) {
  char cmd[160];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "fuzz: could not remove %s\n", dir);
}

static void cleanup(void) { remove_tree(workdir); }

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
  fuzz_make_workdir(workdir, sizeof workdir, "deck");
  atexit(cleanup);
  FILE *f = fopen(MORAINE_FUZZ_DIR "/deck_driver.lua", "rb");
  if (!f) fuzz_die("cannot read %s/deck_driver.lua", MORAINE_FUZZ_DIR);
  fseek(f, 0, SEEK_END);
  driver_len = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  driver = malloc(driver_len);
  if (fread(driver, 1, driver_len, f) != driver_len) fuzz_die("short read of deck_driver.lua");
  fclose(f);
  struct sigaction before_int, before_term, moraine;
  sigaction(SIGINT, NULL, &before_int);
  sigaction(SIGTERM, NULL, &before_term);
  mrn_interrupt_install();
  sigaction(SIGTERM, NULL, &moraine);
  moraine_on_signal = moraine.sa_handler;
  sigaction(SIGINT, &before_int, NULL);
  sigaction(SIGTERM, &before_term, NULL);
  struct sigaction sa = {0};
  sa.sa_handler = on_budget;
  sa.sa_flags = SA_RESTART;
  sigaction(SIGVTALRM, &sa, NULL);
  return 0;
}

/* specs["simulation{} grid"] = {{key = "cell", type = "number"}, ...} */
static void push_specs(lua_State *L) {
  lua_newtable(L);
  for (int g = 0; g < mrn_spec_group_count(); g++) {
    const mrn_spec_group *grp = mrn_spec_group_at(g);
    lua_createtable(L, grp->count, 0);
    for (int i = 0; i < grp->count; i++) {
      lua_createtable(L, 0, 2);
      lua_pushstring(L, grp->specs[i].key);
      lua_setfield(L, -2, "key");
      lua_pushstring(L, mrn_spec_type_name(grp->specs[i].type));
      lua_setfield(L, -2, "type");
      lua_rawseti(L, -2, i + 1);
    }
    lua_setfield(L, -2, grp->name);
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 4096) return 0; /* longer call sequences add nothing but time */
  mrn_interrupt_clear();
  budget_spent = 0;
  struct itimerval budget = {{0, 0}, {1, 0}}; /* one second of CPU time */
  setitimer(ITIMER_VIRTUAL, &budget, NULL);

  lua_State *L = luaL_newstate();
  luaL_openlibs(L);
  mrn_deck_options opt = {.outdir = workdir};
  mrn_lua_open(L, &opt);
  if (luaL_loadbuffer(L, driver, driver_len, "deck_driver.lua") != LUA_OK || lua_pcall(L, 0, 1, 0) != LUA_OK)
    fuzz_die("deck_driver.lua: %s", lua_tostring(L, -1));
  lua_pushlstring(L, (const char *)data, size);
  push_specs(L);
  lua_pushstring(L, workdir);
  /* the driver catches every error of the API itself; one escaping here is a
   * driver bug or an error raised where pcall cannot catch it */
  if (lua_pcall(L, 3, 0, 0) != LUA_OK) fuzz_die("deck driver failed: %s", lua_tostring(L, -1));
  lua_close(L);
  mrn_output_forget_files();

  struct itimerval off = {{0, 0}, {0, 0}};
  setitimer(ITIMER_VIRTUAL, &off, NULL);
  mrn_interrupt_clear();
  return 0;
}
