/* moraine: the group /resume of a checkpoint — the named values of a stash
 * (io/stash.h), one attribute each: float64, int64 or a string. */
#include <hdf5.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "io/checkpoint.h"
#include "io/checkpoint_internal.h"
#include "io/h5util.h"

#define STASH_GROUP "/resume"

void ck_save_stash(mrn_h5w *w, const mrn_stash *s) {
  if (!s || s->n == 0) return;
  hid_t g = mrn_h5w_group(w, w->file, "resume");
  if (g < 0) return;
  for (int i = 0; i < s->n; i++) {
    const mrn_stash_value *e = &s->v[i];
    if (e->kind == MRN_STASH_REAL) mrn_h5w_double(w, g, e->name, e->real);
    else if (e->kind == MRN_STASH_INT) mrn_h5w_int64(w, g, e->name, e->integer);
    else mrn_h5w_string(w, g, e->name, e->text ? e->text : "");
  }
  H5Gclose(g);
}

typedef struct read_ctx {
  mrn_h5r *r;
  mrn_stash *s;
} read_ctx;

/* one attribute of /resume into the stash, by the class of its type */
static int read_one(void *user, const char *name) {
  read_ctx *c = user;
  hid_t a = H5Aopen_by_name(c->r->file, STASH_GROUP, name, H5P_DEFAULT, H5P_DEFAULT);
  hid_t t = a >= 0 ? H5Aget_type(a) : H5I_INVALID_HID;
  H5T_class_t cls = t >= 0 ? H5Tget_class(t) : H5T_NO_CLASS;
  if (t >= 0) H5Tclose(t);
  if (a >= 0) H5Aclose(a);
  double real = 0;
  int64_t integer = 0;
  char text[4096] = "";
  mrn_stash_kind kind;
  if (cls == H5T_FLOAT) kind = MRN_STASH_REAL, mrn_h5r_double(c->r, STASH_GROUP, name, &real);
  else if (cls == H5T_INTEGER) kind = MRN_STASH_INT, mrn_h5r_int(c->r, STASH_GROUP, name, &integer);
  else if (cls == H5T_STRING) kind = MRN_STASH_TEXT, mrn_h5r_string(c->r, STASH_GROUP, name, text, sizeof text);
  else return mrn_h5r_fail(c->r, "attribute '%s' of %s is neither a number nor a string", name, STASH_GROUP);
  if (c->r->failed) return 1;
  if (mrn_stash_put(c->s, name, kind, real, integer, text) != 0) return mrn_h5r_fail(c->r, "out of memory");
  return 0;
}

int mrn_checkpoint_read_stash(const char *path, mrn_stash *s) {
  mrn_stash_init(s, 1);
  int present;
  mrn_h5_quiet quiet;
  mrn_h5_silence(&quiet);
  int rc = ck_sum_verify(path, &present);
  mrn_h5r r;
  if (rc == MRN_OK && mrn_h5r_open(&r, path) == MRN_OK) {
    read_ctx c = {&r, s};
    if (mrn_h5r_exists(&r, STASH_GROUP) == 1 && mrn_h5r_group(&r, STASH_GROUP) == MRN_OK)
      mrn_h5r_each_attr(&r, STASH_GROUP, read_one, &c);
    mrn_h5r_close(&r);
    rc = r.failed ? MRN_ERR_IO : MRN_OK;
  } else {
    rc = MRN_ERR_IO;
  }
  mrn_h5_restore(&quiet);
  if (rc != MRN_OK) mrn_stash_free(s);
  return rc;
}
