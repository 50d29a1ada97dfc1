#include "io/h5image.h"

#include <stdlib.h>
#include <string.h>

/* The image is taken when the in-memory file is closed, complete: the core
 * driver hands its buffer to these callbacks, and the one for freeing it at
 * close keeps it instead. (An image taken from the open file carries a
 * superblock that HDF5 1.10 leaves with a wrong checksum.) */

static void *image_malloc(size_t size, H5FD_file_image_op_t op, void *udata) {
  (void)op;
  mrn_h5_image *c = udata;
  void *p = malloc(size);
  if (p) {
    c->buf = p;
    c->size = size;
  }
  return p;
}

static void *image_realloc(void *ptr, size_t size, H5FD_file_image_op_t op, void *udata) {
  (void)op;
  mrn_h5_image *c = udata;
  void *p = realloc(ptr, size);
  if (p) {
    c->buf = p;
    c->size = size;
  }
  return p;
}

static void *image_memcpy(void *dest, const void *src, size_t size, H5FD_file_image_op_t op, void *udata) {
  (void)op;
  (void)udata;
  return memcpy(dest, src, size);
}

/* HDF5 also opens and closes a short-lived image of its own through these
 * callbacks; the file's buffer is the last one closed, and any buffer kept
 * before it is released. */
static herr_t image_free(void *ptr, H5FD_file_image_op_t op, void *udata) {
  mrn_h5_image *c = udata;
  if (op == H5FD_FILE_IMAGE_OP_FILE_CLOSE && ptr && ptr == c->buf) {
    if (c->kept && c->kept_buf != ptr) free(c->kept_buf);
    c->kept_buf = ptr;
    c->kept = 1;
    return 0;
  }
  if (ptr == c->buf) c->buf = NULL;
  free(ptr);
  return 0;
}

static void *image_udata_copy(void *udata) { return udata; }
static herr_t image_udata_free(void *udata) {
  (void)udata;
  return 0;
}

/* HDF5 first opens a file it is asked to create as an existing one, to see
 * whether it is open already: the core driver would open and read a file of
 * that name on disk (a whole old checkpoint, the last series) to throw it
 * away. A name ending in '/' is a directory, which no open for writing takes. */
static char *unopenable_name(const char *name) {
  size_t len = strlen(name);
  char *dir = malloc(len + 2);
  if (dir) {
    memcpy(dir, name, len);
    memcpy(dir + len, "/", 2);
  }
  return dir;
}

hid_t mrn_h5_image_create(mrn_h5_image *img, const char *name, hid_t fcpl) {
  memset(img, 0, sizeof *img);
  char *memory_name = unopenable_name(name);
  H5FD_file_image_callbacks_t callbacks = {image_malloc, image_memcpy, image_realloc, image_free,
                                           image_udata_copy, image_udata_free, img};
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  int ok = fapl >= 0 && H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG) >= 0 &&
           H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18) >= 0 &&
           H5Pset_fapl_core(fapl, 1 << 20, 0) >= 0 && H5Pset_file_image_callbacks(fapl, &callbacks) >= 0;
  hid_t file = ok && memory_name ? H5Fcreate(memory_name, H5F_ACC_TRUNC, fcpl, fapl) : H5I_INVALID_HID;
  if (fapl >= 0) H5Pclose(fapl);
  free(memory_name);
  return file;
}

int mrn_h5_image_close(mrn_h5_image *img, hid_t file, void **bytes, size_t *size) {
  *bytes = NULL;
  *size = 0;
  /* the size of the file once everything is flushed; the core driver's
   * buffer beyond it is spare */
  ssize_t eof = H5Fflush(file, H5F_SCOPE_GLOBAL) >= 0 ? H5Fget_file_image(file, NULL, 0) : -1;
  /* the buffer holds a user block before HDF5's part, which eof leaves out */
  hsize_t userblock = 0;
  hid_t fcpl = H5Fget_create_plist(file);
  if (fcpl < 0 || H5Pget_userblock(fcpl, &userblock) < 0) eof = -1;
  if (fcpl >= 0) H5Pclose(fcpl);
  int closed = H5Fclose(file) >= 0;
  const size_t total = (size_t)userblock + (size_t)(eof > 0 ? eof : 0);
  if (closed && eof > 0 && img->kept && img->kept_buf == img->buf && total <= img->size) {
    *bytes = img->buf;
    *size = total;
    return 0;
  }
  if (img->kept) free(img->kept_buf);
  return -1;
}
