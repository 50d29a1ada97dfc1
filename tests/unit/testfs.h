/* moraine: small file helpers shared by the C unit tests.
 *
 * Each test that writes files works in a fresh directory under /tmp
 * (make_temp_dir), reads what moraine wrote back whole (read_all), checks
 * that the atomic file layer left no temporary file behind
 * (count_temp_files) and removes the directory at the end (remove_tree).
 * The functions are static inline so that a test that does not use one of
 * them builds without an unused-function warning. */
#ifndef MRN_TESTS_TESTFS_H
#define MRN_TESTS_TESTFS_H

#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/atomic_file.h"

/* Makes a fresh directory `prefix` + "_XXXXXX" (mkdtemp) and leaves its name
 * in dir[size]; 0 on success, -1 (after perror) on failure. */
static inline int make_temp_dir(char *dir, size_t size, const char *prefix) {
  snprintf(dir, size, "%s_XXXXXX", prefix);
  if (!mkdtemp(dir)) {
    perror("mkdtemp");
    return -1;
  }
  return 0;
}

/* The whole file, NUL-terminated, in a malloc'd buffer (its length without
 * the NUL in *len when len is not NULL), or NULL when it cannot be opened. */
static inline char *read_all(const char *path, size_t *len) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  long size = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  char *buf = malloc((size_t)size + 1);
  size_t got = fread(buf, 1, (size_t)size, fp);
  fclose(fp);
  buf[got] = '\0';
  if (len) *len = got;
  return buf;
}

/* 1 when something (file or directory) exists at path */
static inline int exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

/* Creates (or empties) a plain file at path; nothing happens when it cannot. */
static inline void make_empty_file(const char *path) {
  FILE *fp = fopen(path, "w");
  if (fp) fclose(fp);
}

/* The number of atomic-file temporaries (names with ".tmp.") left in dir, or
 * -1 when dir cannot be opened. */
static inline int count_temp_files(const char *dir) {
  DIR *d = opendir(dir);
  if (!d) return -1;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)) != NULL)
    if (strstr(e->d_name, ".tmp.")) n++;
  closedir(d);
  return n;
}

/* How many times needle occurs in text (overlapping ones included) */
static inline int count_occurrences(const char *text, const char *needle) {
  int n = 0;
  for (const char *p = strstr(text, needle); p; p = strstr(p + 1, needle)) n++;
  return n;
}

/* Removes a directory tree made by a test (files and subdirectories only);
 * a path that is not a directory is unlinked. */
static inline void remove_tree(const char *path) {
  DIR *d = opendir(path);
  if (!d) {
    unlink(path);
    return;
  }
  struct dirent *e;
  while ((e = readdir(d)) != NULL) {
    if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
    char *child = mrn_path_join(path, e->d_name);
    remove_tree(child);
    free(child);
  }
  closedir(d);
  rmdir(path);
}

/* In a VTK XML file of len bytes written by moraine with raw appended data:
 * the raw block of the DataArray named `name`. Returns a pointer to its bytes
 * and sets *nbytes from the block's UInt64 header, or returns NULL when the
 * array, its offset or the whole block cannot be found within the file. */
static inline const unsigned char *appended_block(const char *file, size_t len, const char *name,
                                                  uint64_t *nbytes) {
  char key[128];
  snprintf(key, sizeof key, "Name=\"%s\"", name);
  const char *tag = strstr(file, key);
  const char *data = strstr(file, "<AppendedData encoding=\"raw\">");
  if (!tag || !data) return NULL;
  const char *off = strstr(tag, "offset=\"");
  const char *end = strchr(tag, '>');
  if (!off || !end || off > end) return NULL;
  uint64_t offset = strtoull(off + 8, NULL, 10);
  const char *base = strchr(data, '_');
  if (!base) return NULL;
  base++;
  if ((size_t)(base - file) + offset + 8 > len) return NULL;
  memcpy(nbytes, base + offset, 8); /* the test host is little-endian, as the file */
  if ((size_t)(base - file) + offset + 8 + *nbytes > len) return NULL;
  return (const unsigned char *)base + offset + 8;
}

#endif
