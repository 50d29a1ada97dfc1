/* moraine: the provenance files of an output directory (io/provenance.h). */
#include <regex.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "testfs.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/provenance.h"

/* 1 when some whole line of text matches the extended regex */
static int has_line(const char *text, const char *pattern) {
  regex_t re;
  if (regcomp(&re, pattern, REG_EXTENDED | REG_NEWLINE | REG_NOSUB) != 0) return 0;
  int found = regexec(&re, text, 0, NULL, 0) == 0;
  regfree(&re);
  return found;
}

/* a deck with every byte value, so the copy must be byte for byte */
static char *write_deck(const char *dir, size_t *len) {
  char *path = mrn_path_join(dir, "my deck.lua");
  FILE *fp = fopen(path, "wb");
  fputs("-- a deck\nlocal sim = mpm.simulation{}\n", fp);
  for (int b = 0; b < 256; b++) fputc(b, fp);
  *len = (size_t)ftell(fp);
  fclose(fp);
  return path;
}

static void test_full(const char *dir) {
  size_t deck_len;
  char *deck = write_deck(dir, &deck_len);
  char *out = mrn_path_join(dir, "out/nested");
  const char *argv[] = {"moraine", deck, "-o", out, "--set", "cells=32", "--set", "note=it's\ntwo lines", "-q"};
  const char *sets[] = {"cells=32", "note=it's\ntwo lines"};
  CHECK(mrn_provenance_write(out, deck, 9, argv, sets, 2) == MRN_OK);

  char *copy_path = mrn_path_join(out, "provenance/deck.lua");
  char *run_path = mrn_path_join(out, "provenance/run.txt");
  size_t copy_len = 0, orig_len = 0;
  char *copy = read_all(copy_path, &copy_len);
  char *orig = read_all(deck, &orig_len);
  CHECK(copy && orig && copy_len == deck_len && orig_len == deck_len && memcmp(copy, orig, deck_len) == 0);

  char *run = read_all(run_path, NULL);
  CHECK(run != NULL);
  if (run) {
    CHECK(has_line(run, "^moraine_version: " MORAINE_VERSION "$"));
    CHECK(has_line(run, "^git_commit: " MORAINE_GIT_COMMIT "$"));
    CHECK(has_line(run, "^started_utc: [0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z$"));
    CHECK(has_line(run, "^hostname: .+$"));
    CHECK(has_line(run, "^threads: [1-9][0-9]*$"));
    CHECK(has_line(run, "^working_directory: /.*$"));
    CHECK(has_line(run, "^deck_copy: provenance/deck.lua$"));
    CHECK(has_line(run, "^set: cells=32$"));
    CHECK(has_line(run, "^set: note=it's\\\\ntwo lines$")); /* one line, the newline escaped */
    /* each word that needs it in single quotes, so the line can be pasted back */
    char expect[1024];
    snprintf(expect, sizeof expect, "command: moraine '%s' -o %s --set cells=32 --set 'note=it'\\''s\\ntwo lines' -q\n",
             deck, out);
    CHECK(strstr(run, expect) != NULL);
    if (!strstr(run, expect)) fprintf(stderr, "run.txt:\n%s\nexpected:\n%s", run, expect);
  }
  char *prov = mrn_path_join(out, "provenance");
  CHECK(count_temp_files(prov) == 0);

  /* a second run into the same directory replaces both files */
  CHECK(mrn_provenance_write(out, deck, 1, argv, NULL, 0) == MRN_OK);
  free(run);
  run = read_all(run_path, NULL);
  CHECK(run && !has_line(run, "^set: ") && has_line(run, "^command: moraine$"));

  free(prov);
  free(run);
  free(copy);
  free(orig);
  free(copy_path);
  free(run_path);
  free(out);
  free(deck);
}

static void test_no_deck_and_errors(const char *dir) {
  char *out = mrn_path_join(dir, "nodeck");
  CHECK(mrn_provenance_write(out, NULL, 0, NULL, NULL, 0) == MRN_OK);
  char *run_path = mrn_path_join(out, "provenance/run.txt");
  char *copy_path = mrn_path_join(out, "provenance/deck.lua");
  char *run = read_all(run_path, NULL);
  CHECK(run && has_line(run, "^deck: \\(none given; no copy\\)$") && has_line(run, "^command: $"));
  CHECK(!exists(copy_path));
  free(run);

  /* a deck that cannot be read: an error naming it, and no run.txt */
  char *out2 = mrn_path_join(dir, "missing");
  char *gone = mrn_path_join(dir, "no_such_deck.lua");
  mrn_error_clear();
  CHECK(mrn_provenance_write(out2, gone, 0, NULL, NULL, 0) == MRN_ERR_IO);
  CHECK(strstr(mrn_error_message(), gone) != NULL);
  char *run2 = mrn_path_join(out2, "provenance/run.txt");
  CHECK(!exists(run2));

  /* an output directory that cannot be made */
  char *file = mrn_path_join(dir, "plain");
  make_empty_file(file);
  CHECK(mrn_provenance_write(file, NULL, 0, NULL, NULL, 0) == MRN_ERR_IO);
  free(file);
  free(run2);
  free(gone);
  free(out2);
  free(copy_path);
  free(run_path);
  free(out);
}

int main(void) {
  char dir[64];
  if (make_temp_dir(dir, sizeof dir, "/tmp/moraine_test_provenance") != 0) return 1;
  test_full(dir);
  test_no_deck_and_errors(dir);
  remove_tree(dir);
  CHECK_DONE();
}
