/* moraine: the run log (core/log.h): what reaches the file, appending, a
 * symbolic link refused, and the failure of a write. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "testfs.h"
#include "core/error.h"
#include "core/log.h"

static char *log_text(const char *path) {
  size_t len;
  return read_all(path, &len);
}

/* every kind of message, and the quiet screen: the file gets them all */
static void test_messages(const char *path) {
  CHECK(mrn_log_open(path, 0) == MRN_OK);
  mrn_log_set_quiet(1);
  mrn_info("info %d", 1);
  mrn_log_printf(NULL, "log only\n");
  mrn_log_text(NULL, "text\n", 5);
  mrn_log_error("an error: %s", "why");
  mrn_log_set_quiet(0);
  CHECK(strcmp(mrn_log_last_error(), "an error: why") == 0);
  CHECK(!mrn_log_failed());
  CHECK(mrn_log_close() == MRN_OK);
  char *text = log_text(path);
  CHECK(text && strcmp(text, "info 1\nlog only\ntext\nmoraine: an error: why\n") == 0);
  free(text);
}

/* a second open truncates; with `append` it adds to the end */
static void test_append(const char *path) {
  CHECK(mrn_log_open(path, 1) == MRN_OK);
  mrn_log_printf(NULL, "appended\n");
  CHECK(mrn_log_close() == MRN_OK);
  char *text = log_text(path);
  CHECK(text && strcmp(text, "info 1\nlog only\ntext\nmoraine: an error: why\nappended\n") == 0);
  free(text);
  CHECK(mrn_log_open(path, 0) == MRN_OK);
  mrn_log_printf(NULL, "new\n");
  CHECK(mrn_log_close() == MRN_OK);
  text = log_text(path);
  CHECK(text && strcmp(text, "new\n") == 0);
  free(text);
}

/* a link in place of the log is not followed */
static void test_link(const char *dir) {
  char *target = mrn_path_join(dir, "elsewhere.txt"), *link = mrn_path_join(dir, "link.txt");
  CHECK(symlink(target, link) == 0);
  CHECK(mrn_log_open(link, 0) == MRN_ERR_IO);
  CHECK(strstr(mrn_error_message(), "cannot write '") && strstr(mrn_error_message(), "link.txt'"));
  CHECK(access(target, F_OK) != 0);
  CHECK(mrn_log_fd() == -1);
  free(target);
  free(link);
}

/* a write that fails (the descriptor closed under the log) is kept, the log
 * stops, and closing reports it */
static void test_failure(const char *path) {
  CHECK(mrn_log_open(path, 0) == MRN_OK);
  mrn_log_printf(NULL, "kept\n");
  close(mrn_log_fd());
  mrn_log_printf(NULL, "lost\n");
  CHECK(mrn_log_failed());
  CHECK(strstr(mrn_log_failure(), "cannot write '") && strstr(mrn_log_failure(), "Bad file descriptor"));
  CHECK(mrn_log_fd() == -1);
  CHECK(mrn_log_close() == MRN_ERR_IO);
  char *text = log_text(path);
  CHECK(text && strcmp(text, "kept\n") == 0);
  free(text);
  CHECK(mrn_log_open(path, 0) == MRN_OK); /* a new log starts clean */
  CHECK(!mrn_log_failed());
  CHECK(mrn_log_close() == MRN_OK);
}

int main(void) {
  char dir[256];
  if (make_temp_dir(dir, sizeof dir, "/tmp/moraine_test_log") != 0) return 1;
  char *path = mrn_path_join(dir, "log.txt");
  test_messages(path);
  test_append(path);
  test_link(dir);
  test_failure(path);
  free(path);
  remove_tree(dir);
  CHECK_DONE();
}
