/* moraine fuzzing: a main() for the harnesses when they are built without
 * libFuzzer (the quick test suite). It feeds LLVMFuzzerTestOneInput every
 * file of the corpus directories given on the command line, then COUNT
 * pseudo-random inputs: random bytes, and corpus files with a few bytes
 * changed, inserted or cut off. The generator is seeded so a failure
 * repeats.
 *
 *   replay [-n COUNT] [-s SEED] DIR_OR_FILE...
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

#define MAX_FILES 4096
static char *names[MAX_FILES];
static uint8_t *datas[MAX_FILES];
static size_t sizes[MAX_FILES];
static int nfiles = 0;

static void load(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f || nfiles >= MAX_FILES) {
    fprintf(stderr, "replay: cannot read %s\n", path);
    exit(2);
  }
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  datas[nfiles] = malloc(n > 0 ? (size_t)n : 1);
  sizes[nfiles] = fread(datas[nfiles], 1, (size_t)n, f);
  names[nfiles++] = strdup(path);
  fclose(f);
}

static int by_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static void load_path(const char *path) {
  struct stat st;
  if (stat(path, &st) != 0) {
    fprintf(stderr, "replay: no such file or directory: %s\n", path);
    exit(2);
  }
  if (!S_ISDIR(st.st_mode)) {
    load(path);
    return;
  }
  DIR *d = opendir(path);
  struct dirent *e;
  char *found[MAX_FILES];
  int nfound = 0;
  while ((e = readdir(d)) && nfound < MAX_FILES)
    if (e->d_name[0] != '.') {
      found[nfound] = malloc(strlen(path) + strlen(e->d_name) + 2);
      sprintf(found[nfound++], "%s/%s", path, e->d_name);
    }
  closedir(d);
  qsort(found, (size_t)nfound, sizeof found[0], by_name); /* the same order every time */
  for (int i = 0; i < nfound; i++) {
    load(found[i]);
    free(found[i]);
  }
}

/* xorshift64*: small and the same on every platform */
static uint64_t state = 0x9E3779B97F4A7C15ull;
static uint64_t next(void) {
  state ^= state >> 12;
  state ^= state << 25;
  state ^= state >> 27;
  return state * 2685821657736338717ull;
}

int main(int argc, char **argv) {
  long count = 200;
  int first = 1;
  for (; first < argc && argv[first][0] == '-'; first += 2) {
    if (first + 1 >= argc) break;
    if (!strcmp(argv[first], "-n")) count = atol(argv[first + 1]);
    else if (!strcmp(argv[first], "-s")) state = strtoull(argv[first + 1], NULL, 10) | 1;
  }
  LLVMFuzzerInitialize(&argc, &argv);
  for (int i = first; i < argc; i++) load_path(argv[i]);
  for (int i = 0; i < nfiles; i++) {
    fprintf(stderr, "replay: %s (%zu bytes)\n", names[i], sizes[i]);
    LLVMFuzzerTestOneInput(datas[i], sizes[i]);
  }
  uint8_t *buf = malloc(1 << 16);
  for (long k = 0; k < count; k++) {
    size_t n;
    if (nfiles == 0 || k % 4 == 0) { /* random bytes */
      n = next() % 512;
      for (size_t i = 0; i < n; i++) buf[i] = (uint8_t)next();
    } else { /* a corpus file, mutated */
      int f = (int)(next() % (uint64_t)nfiles);
      n = sizes[f] < (1 << 16) ? sizes[f] : (1 << 16);
      memcpy(buf, datas[f], n);
      int edits = 1 + (int)(next() % 8);
      for (int e = 0; e < edits && n > 0; e++) {
        size_t at = next() % n;
        switch (next() % 4) {
        case 0: buf[at] = (uint8_t)next(); break;
        case 1: buf[at] ^= (uint8_t)(1u << (next() % 8)); break;
        case 2: n = at + 1; break; /* cut */
        case 3:                    /* insert */
          if (n < (1 << 16)) {
            memmove(buf + at + 1, buf + at, n - at);
            buf[at] = (uint8_t)next();
            n++;
          }
          break;
        }
      }
    }
    LLVMFuzzerTestOneInput(buf, n);
  }
  fprintf(stderr, "replay: %d corpus files and %ld generated inputs, no crash\n", nfiles, count);
  free(buf);
  for (int i = 0; i < nfiles; i++) {
    free(datas[i]);
    free(names[i]);
  }
  return 0;
}
