/* moraine: the checksum table of a checkpoint (doc/checkpoint-format.md,
 * "Checksums").
 *
 * HDF5 checksums its own metadata but not the values of the datasets, so a
 * damaged byte among them would load as a different number. A checkpoint
 * therefore starts with a table, in an HDF5 user block (bytes HDF5 reserves
 * for the application and never reads), giving the CRC-32 of every byte
 * after it: one per dataset over its values, one over everything else (the
 * metadata: groups, attributes, dataset layouts), and one over the table
 * itself. The loader checks the whole file against the table with plain
 * reads before HDF5 parses any of it: a damaged file is refused naming the
 * dataset, and HDF5 (whose 1.10 releases leak memory on a damaged object
 * header) only ever reads intact files. */
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/crc32.h"
#include "core/error.h"
#include "io/checkpoint.h"
#include "io/checkpoint_internal.h"
#include "io/h5util.h"

#define MAGIC "moraine checkpoint checksums\n"
#define TABLE_LINE 15          /* "table XXXXXXXX\n", the last line */
#define MAX_USERBLOCK (1 << 20)

/* ---- the ranges --------------------------------------------------------- */

static int add_range(ck_ranges *rs, const char *path, uint64_t offset, uint64_t bytes) {
  if (rs->n == rs->cap) {
    int cap = rs->cap ? 2 * rs->cap : 32;
    ck_range *grown = realloc(rs->r, (size_t)cap * sizeof *grown);
    if (!grown) return -1;
    rs->r = grown;
    rs->cap = cap;
  }
  ck_range *r = &rs->r[rs->n++];
  r->offset = offset;
  r->bytes = bytes;
  r->crc = 0;
  snprintf(r->path, sizeof r->path, "%s", path);
  return 0;
}

void ck_ranges_free(ck_ranges *rs) {
  free(rs->r);
  memset(rs, 0, sizeof *rs);
}

static int by_offset(const void *a, const void *b) {
  const ck_range *x = a, *y = b;
  return (x->offset > y->offset) - (x->offset < y->offset);
}

/* A dataset whose values lie in one piece of the file (HDF5's contiguous
 * layout, which is how moraine writes them) is a range; the values of any
 * other dataset (chunked, compact, empty) count with the metadata. */
static herr_t visit_dataset(hid_t root, const char *name, const H5O_info_t *info, void *data) {
  if (info->type != H5O_TYPE_DATASET) return 0;
  ck_ranges *rs = data;
  hid_t d = H5Oopen(root, name, H5P_DEFAULT);
  if (d < 0) return -1;
  haddr_t offset = H5Dget_offset(d);
  hsize_t bytes = H5Dget_storage_size(d);
  H5Oclose(d);
  if (offset == HADDR_UNDEF || bytes == 0) return 0;
  char path[CK_SUM_PATH];
  if (snprintf(path, sizeof path, "/%s", name) >= (int)sizeof path) return -1;
  return add_range(rs, path, offset, bytes) ? -1 : 0;
}

int ck_sum_collect(hid_t file, ck_ranges *rs) {
  memset(rs, 0, sizeof *rs);
  if (H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC, visit_dataset, rs, H5O_INFO_BASIC) < 0) {
    ck_ranges_free(rs);
    return -1;
  }
  if (rs->n) qsort(rs->r, (size_t)rs->n, sizeof *rs->r, by_offset);
  return 0;
}

/* the longest line a table may have: "data", a CRC, two 20-digit numbers, a path */
#define LINE_MAX_BYTES (5 + 9 + 21 + 21 + CK_SUM_PATH + 1)
/* the longest a checkpoint's own lines can be: its longest paths are
 * /particles/user/<name> */
#define LINE_WRITTEN_BYTES (5 + 9 + 21 + 21 + 16 + MRN_USER_FIELD_NAME + 1)

uint64_t ck_sum_userblock(int ndatasets) {
  uint64_t need = 128 + (uint64_t)ndatasets * LINE_WRITTEN_BYTES, size = 4096;
  while (size < need) size *= 2;
  return size;
}

/* ---- summing ----------------------------------------------------------- */

/* where the bytes come from: a file image in memory, or a file read in blocks */
#define BLOCK (1 << 16)
typedef struct source {
  const unsigned char *image;
  FILE *fp;
  unsigned char *block; /* BLOCK bytes */
} source;

/* the CRC of `crc`'s bytes followed by bytes [from, to) of the source */
static int sum_bytes(const source *s, uint64_t from, uint64_t to, uint32_t *crc) {
  if (s->image) {
    *crc = mrn_crc32(*crc, s->image + from, (size_t)(to - from));
    return 0;
  }
  if (fseeko(s->fp, (off_t)from, SEEK_SET) != 0) return -1;
  while (from < to) {
    size_t want = to - from < BLOCK ? (size_t)(to - from) : BLOCK;
    if (fread(s->block, 1, want, s->fp) != want) return -1;
    *crc = mrn_crc32(*crc, s->block, want);
    from += want;
  }
  return 0;
}

/* whether the ranges, sorted, lie inside [userblock, size) without
 * overlapping: a hostile file can claim anything */
static int ranges_fit(const ck_ranges *rs, uint64_t userblock, uint64_t size) {
  uint64_t at = userblock;
  for (int i = 0; i < rs->n; i++) {
    const ck_range *r = &rs->r[i];
    if (r->bytes == 0 || r->offset < at || r->offset > size || r->bytes > size - r->offset) return 0;
    at = r->offset + r->bytes;
  }
  return at <= size;
}

/* The CRC of every range into got[i], and of every other byte from
 * `userblock` to `size`, in file order, into *rest (the ranges fit). */
static int sum_file(const source *s, const ck_ranges *rs, uint64_t userblock, uint64_t size, uint32_t *got,
                    uint32_t *rest) {
  uint64_t at = userblock;
  *rest = 0;
  for (int i = 0; i < rs->n; i++) {
    const ck_range *r = &rs->r[i];
    got[i] = 0;
    if (sum_bytes(s, at, r->offset, rest) || sum_bytes(s, r->offset, r->offset + r->bytes, &got[i])) return -1;
    at = r->offset + r->bytes;
  }
  return sum_bytes(s, at, size, rest);
}

/* ---- writing the table ------------------------------------------------- */

int ck_sum_write_image(unsigned char *image, uint64_t size, uint64_t userblock, ck_ranges *rs) {
  if (userblock < 512 || userblock > size || !ranges_fit(rs, userblock, size)) return -1;
  uint32_t *got = malloc(((size_t)rs->n + 1) * sizeof *got);
  uint32_t rest;
  source s = {image, NULL, NULL};
  if (!got || sum_file(&s, rs, userblock, size, got, &rest)) {
    free(got);
    return -1;
  }
  char *text = (char *)image;
  memset(text, 0, (size_t)userblock);
  size_t used = 0, room = (size_t)userblock - TABLE_LINE - 1; /* the table line and a NUL after it */
#define PUT(...) used += used < room ? (size_t)snprintf(text + used, room - used, __VA_ARGS__) : 0
  PUT(MAGIC "userblock %" PRIu64 "\nfile %" PRIu64 "\n", userblock, size);
  for (int i = 0; i < rs->n; i++) {
    rs->r[i].crc = got[i];
    PUT("data %08" PRIx32 " %" PRIu64 " %" PRIu64 " %s\n", got[i], rs->r[i].offset, rs->r[i].bytes, rs->r[i].path);
  }
  PUT("rest %08" PRIx32 "\n", rest);
#undef PUT
  free(got);
  if (used >= room) {
    memset(text, 0, (size_t)userblock);
    return -1;
  }
  snprintf(text + used, TABLE_LINE + 1, "table %08" PRIx32 "\n", mrn_crc32(0, text, used));
  return 0;
}

/* ---- reading the table -------------------------------------------------- */

typedef struct table {
  uint64_t userblock, size;
  uint32_t rest;
  ck_ranges ranges;
} table;

static int damaged_table(const char *path, uint64_t userblock, const char *what) {
  return mrn_error_code(MRN_ERR_IO, "'%s': the checksum table in its first %" PRIu64 " bytes is damaged (%s)", path,
                        userblock, what);
}

/* one "data CRC OFFSET BYTES PATH" line */
static int parse_range(table *t, const char *line, size_t len) {
  uint32_t crc;
  uint64_t offset, bytes;
  int at = 0;
  if (sscanf(line, "data %8" SCNx32 " %" SCNu64 " %" SCNu64 " %n", &crc, &offset, &bytes, &at) != 3 || at == 0)
    return -1;
  const char *path = line + at;
  size_t plen = len - (size_t)at;
  if (plen == 0 || plen >= CK_SUM_PATH || path[0] != '/' || memchr(path, ' ', plen)) return -1;
  char name[CK_SUM_PATH];
  memcpy(name, path, plen);
  name[plen] = '\0';
  if (add_range(&t->ranges, name, offset, bytes)) return -1;
  t->ranges.r[t->ranges.n - 1].crc = crc;
  return 0;
}

/* the lines between "file" and "table"; 0 or -1 (damaged) */
static int parse_lines(table *t, const char *text, size_t len) {
  const char *end = text + len;
  int line_no = 0, have_rest = 0;
  for (const char *p = text; p < end; line_no++) {
    const char *nl = memchr(p, '\n', (size_t)(end - p));
    if (!nl) return -1;
    size_t n = (size_t)(nl - p);
    char line[LINE_MAX_BYTES + 1];
    if (n > LINE_MAX_BYTES || memchr(p, '\0', n)) return -1;
    memcpy(line, p, n);
    line[n] = '\0';
    p = nl + 1;
    uint64_t value;
    if (line_no == 0) {
      if (strcmp(line, "moraine checkpoint checksums")) return -1;
    } else if (line_no == 1) {
      if (sscanf(line, "userblock %" SCNu64, &value) != 1 || value != t->userblock) return -1;
    } else if (line_no == 2) {
      if (sscanf(line, "file %" SCNu64, &t->size) != 1 || t->size < t->userblock) return -1;
    } else if (have_rest) {
      return -1; /* "rest" is the last line before "table" */
    } else if (strncmp(line, "rest ", 5) == 0) {
      if (sscanf(line, "rest %8" SCNx32, &t->rest) != 1) return -1;
      have_rest = 1;
    } else if (parse_range(t, line, n)) {
      return -1;
    }
  }
  return have_rest && ranges_fit(&t->ranges, t->userblock, t->size) ? 0 : -1;
}

/* The user block: the table's text, its own CRC on the last line, then
 * zeros to the end, every byte of it checked. */
static int read_table(const char *path, FILE *fp, const char *head, table *t) {
  uint64_t userblock = 0;
  if (sscanf(head + strlen(MAGIC), "userblock %" SCNu64, &userblock) != 1 || userblock < 512 ||
      userblock > MAX_USERBLOCK || (userblock & (userblock - 1)))
    return damaged_table(path, userblock, "no valid 'userblock' line");
  t->userblock = userblock;
  char *block = malloc((size_t)userblock);
  if (!block) return mrn_error_code(MRN_ERR_IO, "'%s': out of memory reading its checksum table", path);
  int rc = MRN_OK;
  size_t len = 0;
  if (fseeko(fp, 0, SEEK_SET) != 0 || fread(block, 1, (size_t)userblock, fp) != userblock) {
    rc = mrn_error_code(MRN_ERR_IO, "'%s': truncated or corrupted HDF5 file (shorter than its %" PRIu64
                        "-byte checksum table)", path, userblock);
  } else if ((len = strnlen(block, (size_t)userblock)) == userblock || len < TABLE_LINE ||
             strncmp(block + len - TABLE_LINE, "table ", 6)) {
    rc = damaged_table(path, userblock, "no 'table' line at its end");
  } else {
    /* the last line, byte for byte as the writer makes it */
    char last[TABLE_LINE + 1];
    size_t body = len - TABLE_LINE;
    snprintf(last, sizeof last, "table %08" PRIx32 "\n", mrn_crc32(0, block, body));
    int zeros = 1;
    for (size_t i = len; i < userblock && zeros; i++) zeros = block[i] == 0;
    if (memcmp(block + body, last, TABLE_LINE) != 0)
      rc = damaged_table(path, userblock, "it fails its own checksum");
    else if (!zeros)
      rc = damaged_table(path, userblock, "bytes after the table are not zero");
    else if (parse_lines(t, block, body))
      rc = damaged_table(path, userblock, "a line does not read as expected");
  }
  free(block);
  return rc;
}

/* ---- verifying ----------------------------------------------------------- */

/* the first dataset, in file order, whose bytes differ from the table; the rest after them */
static int compare(const char *path, const table *t, const uint32_t *got, uint32_t rest) {
  for (int i = 0; i < t->ranges.n; i++)
    if (got[i] != t->ranges.r[i].crc)
      return mrn_error_code(MRN_ERR_IO,
                            "'%s': %s fails its checksum: its values are damaged (CRC-32 %08" PRIx32
                            ", the file's table says %08" PRIx32 ")",
                            path, t->ranges.r[i].path, got[i], t->ranges.r[i].crc);
  if (rest != t->rest)
    return mrn_error_code(MRN_ERR_IO,
                          "'%s': the HDF5 metadata (groups, attributes, dataset layouts) fails its checksum: the file "
                          "is damaged or was changed by another program (CRC-32 %08" PRIx32
                          ", the file's table says %08" PRIx32 ")",
                          path, rest, t->rest);
  return MRN_OK;
}

/* the file is as long as the table says */
static int check_size(const char *path, FILE *fp, uint64_t want) {
  struct stat st;
  if (fstat(fileno(fp), &st) != 0)
    return mrn_error_code(MRN_ERR_IO, "'%s': cannot read the file to check its checksums", path);
  if ((uint64_t)st.st_size < want)
    return mrn_error_code(MRN_ERR_IO, "'%s': truncated or corrupted HDF5 file (%lld bytes of the %" PRIu64
                          " its checksum table lists)", path, (long long)st.st_size, want);
  if ((uint64_t)st.st_size > want)
    return mrn_error_code(MRN_ERR_IO, "'%s': %lld bytes, more than the %" PRIu64 " its checksum table lists: the "
                          "file is damaged or was changed by another program", path, (long long)st.st_size, want);
  return MRN_OK;
}

/* every byte after the user block against the table */
static int check_sums(const char *path, FILE *fp, const table *t) {
  uint32_t *got = malloc(((size_t)t->ranges.n + 1) * sizeof *got);
  uint32_t rest = 0;
  source s = {NULL, fp, malloc(BLOCK)};
  int rc = got && s.block && sum_file(&s, &t->ranges, t->userblock, t->size, got, &rest) == 0
               ? compare(path, t, got, rest)
               : mrn_error_code(MRN_ERR_IO, "'%s': cannot read the file to check its checksums", path);
  free(s.block);
  free(got);
  return rc;
}

static int verify_open(const char *path, FILE *fp, const char *head, int *present) {
  table t = {0};
  *present = 1;
  int rc = read_table(path, fp, head, &t);
  if (rc == MRN_OK) rc = check_size(path, fp, t.size);
  if (rc == MRN_OK) rc = check_sums(path, fp, &t);
  ck_ranges_free(&t.ranges);
  return rc;
}

int ck_sum_verify(const char *path, int *present) {
  *present = 0;
  FILE *fp = path && *path ? fopen(path, "rb") : NULL;
  if (!fp) return MRN_OK; /* the HDF5 reader says what is wrong with the file */
  char head[512] = "";
  size_t got = fread(head, 1, sizeof head - 1, fp);
  head[got] = '\0';
  int rc = MRN_OK;
  /* a file starting with HDF5's signature (or anything but the table) has
   * none: written before checksums, or not a checkpoint */
  if (got >= strlen(MAGIC) && memcmp(head, MAGIC, strlen(MAGIC)) == 0) rc = verify_open(path, fp, head, present);
  fclose(fp);
  return rc;
}

/* ---- signing an existing file -------------------------------------------- */

/* Write the table of the file at `path` into `image`, its bytes; the size
 * of its user block in *userblock. */
static int sign_image(const char *path, unsigned char *image, uint64_t size, uint64_t *userblock) {
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl >= 0) H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, fapl >= 0 ? fapl : H5P_DEFAULT);
  if (fapl >= 0) H5Pclose(fapl);
  if (file < 0) return mrn_error_code(MRN_ERR_IO, "'%s': HDF5 cannot open it", path);
  hsize_t ub = 0;
  hid_t fcpl = H5Fget_create_plist(file);
  if (fcpl >= 0) H5Pget_userblock(fcpl, &ub);
  if (fcpl >= 0) H5Pclose(fcpl);
  ck_ranges rs;
  int collected = ck_sum_collect(file, &rs);
  H5Fclose(file);
  if (collected) return mrn_error_code(MRN_ERR_IO, "'%s': cannot list its datasets", path);
  int rc = MRN_OK;
  *userblock = ub;
  if (ub == 0 || ub > size)
    rc = mrn_error_code(MRN_ERR_IO, "'%s': has no user block to hold a checksum table", path);
  else if (ck_sum_write_image(image, size, ub, &rs))
    rc = mrn_error_code(MRN_ERR_IO, "'%s': its checksum table does not fit in its %llu-byte user block", path,
                        (unsigned long long)ub);
  ck_ranges_free(&rs);
  return rc;
}

int mrn_checkpoint_sign(const char *path) {
  FILE *fp = fopen(path, "r+b");
  if (!fp) return mrn_error_code(MRN_ERR_IO, "'%s': cannot open: %s", path, strerror(errno));
  struct stat st;
  unsigned char *image = fstat(fileno(fp), &st) == 0 && st.st_size > 0 ? malloc((size_t)st.st_size) : NULL;
  int rc = image && fread(image, 1, (size_t)st.st_size, fp) == (size_t)st.st_size
               ? MRN_OK
               : mrn_error_code(MRN_ERR_IO, "'%s': cannot read it", path);
  uint64_t userblock = 0;
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  if (rc == MRN_OK) rc = sign_image(path, image, (uint64_t)st.st_size, &userblock);
  mrn_h5_restore(&quiet);
  /* only the user block changes */
  if (rc == MRN_OK && (fseeko(fp, 0, SEEK_SET) != 0 || fwrite(image, 1, (size_t)userblock, fp) != userblock))
    rc = mrn_error_code(MRN_ERR_IO, "'%s': cannot write its checksum table", path);
  free(image);
  if (fclose(fp) != 0 && rc == MRN_OK) rc = mrn_error_code(MRN_ERR_IO, "'%s': cannot write its checksum table", path);
  return rc;
}
