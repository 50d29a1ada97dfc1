/* moraine: a material whose update is supplied at run time.
 *
 * The model "lua" of the registry has no law of its own: its update is a
 * function given by a layer above material/ (the Lua binding fills it with a
 * deck's function, src/lua/lua_material_user.c; a C program can give a C
 * function). Each such material owns a copy of the type, so that the number
 * and names of its history variables are its own.
 *
 * The law may not be called concurrently (a Lua state is not thread-safe):
 * the batches of a user material are run one at a time, inside one OpenMP
 * critical section, while the rest of the step stays parallel. A law that
 * fails records its error; later batches are skipped, and the caller of the
 * material pass collects the error with mrn_material_user_failure(). */
#ifndef MRN_MATERIAL_USER_H
#define MRN_MATERIAL_USER_H

#include <stddef.h>

#include "material/material.h"

#define MRN_USER_MAX_STATE 16

typedef struct mrn_user_law {
  /* the update of n points (material.h's contract); returns 0, or an error
   * code with the message set (core/error.h) */
  int (*update)(void *ctx, const mrn_material *m, mrn_material_point *pt, int n);
  void (*release)(void *ctx); /* called on ctx when the material is freed (may be NULL) */
  void *ctx;
} mrn_user_law;

/* a "lua" material with every parameter at its default, `nstate` history
 * variables named `names` (copied), and the law (copied; NULL: none yet, its
 * update then fails). refcount 1; NULL on error (message set). */
mrn_material *mrn_material_user_new(int nstate, const char *const *names, const mrn_user_law *law);

/* 1 when m's update is a user law (a "lua" material) */
int mrn_material_is_user(const mrn_material *m);
/* 1 when m is a user material that has a law to call */
int mrn_material_user_has_law(const mrn_material *m);

/* The error recorded by m's law since the last call (0: none), its message
 * set in the calling thread's error buffer (core/error.h); the record is
 * cleared. 0 for every other model. */
int mrn_material_user_failure(const mrn_material *m);

/* the type every user material copies (registered as "lua") */
extern const mrn_material_type mrn_material_user;

#endif
