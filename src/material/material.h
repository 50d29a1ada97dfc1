/* moraine: constitutive models, registered by name.
 *
 * A model is an mrn_material_type: its parameters (mrn_spec, with units and
 * ranges), the number of history variables it keeps per particle, and an
 * update function called once per batch of particles of that material per
 * step (the model writes its one-point update; MRN_MATERIAL_BATCH_UPDATE
 * makes the batch loop). A model is added by writing one file that defines
 * its type and listing it in material.c's registry. A deck creates an mrn_material (a type plus parameter values)
 * through mpm.material.<name>{...}. */
#ifndef MRN_MATERIAL_MATERIAL_H
#define MRN_MATERIAL_MATERIAL_H

#include <stddef.h>

#include "core/spec.h"
#include "core/tensor.h"

#define MRN_MATERIAL_MAX_PARAMS 24
#define MRN_MATERIAL_MAX_DERIVED 16
/* the most points one call of a model's update receives */
#define MRN_MATERIAL_BATCH 32

struct mrn_material;

/* What the step hands to a model for one particle. Rate-form models
 * (`rate_form` set) receive `stress` already co-rotated with the Jaumann
 * spin (002, Eq. 28) and return the new stress; hyperelastic models compute
 * the stress from F. */
typedef struct mrn_material_point {
  double stress[6];       /* in: start-of-step stress (rotated); out: new stress */
  double dstrain[6];      /* strain increment sym(L) dt (002, Eq. 29) */
  const double *F;        /* deformation gradient at the end of the step */
  double J;               /* det F at the end of the step */
  double J_old;           /* det F at the start of the step */
  double dt;
  double *state;          /* history variables (`nstate` values) */
  double de_elastic;      /* out: elastic energy increment per unit volume (000, Eq. 64); the step
                           * multiplies it by the mid-step volume V0 (J_old + J) / 2, so a model
                           * with a stored-energy density psi per reference volume returns
                           * (psi_new - psi_old) / ((J_old + J) / 2) */
  double dw_plastic;      /* out: plastic work increment per unit volume, <= 0 (000, Eq. 65) */
} mrn_material_point;

/* The constitutive law of the implicit integrator (implicit/, paper 001):
 * Hencky elasticity, tau = lambda tr(e) I + 2 G e on the logarithmic elastic
 * strain e = ln(b_e) / 2, with von Mises plasticity and linear isotropic
 * hardening, return-mapped in principal logarithmic strains (001 Eqs.
 * 62-63), when the yield stress is > 0. These are a model's values of it. */
typedef struct mrn_implicit_law {
  double lambda, G; /* Lame constants (Pa) */
  double yield;     /* uniaxial yield stress sigma_y (Pa); 0: elastic */
  double hardening; /* linear isotropic hardening modulus H (Pa) */
} mrn_implicit_law;

/* What a model runs as in an implicit simulation; a model without one
 * (mrn_material_type.implicit NULL) is refused there. The law is finite
 * strain whatever the model is in explicit runs. */
typedef struct mrn_implicit_form {
  const char *law; /* in words, for messages and doc/implicit.md */
  /* the law's values for a prepared material m */
  void (*law_of)(const struct mrn_material *m, mrn_implicit_law *out);
} mrn_implicit_form;

typedef struct mrn_material_type {
  const char *name;
  const char *summary;
  const mrn_spec *params;
  int nparams;
  int nstate;
  const char *const *state_names;
  int rate_form;
  /* 1 when `update` is exactly mrn_hooke_update with lambda = derived[0],
   * G = derived[1] and no history or plastic work: material/advance.c then
   * runs that update inline, straight on the particle arrays */
  int pure_hooke;
  /* derive constants from the parameters and check their consistency;
   * return 0 or an error (message set) */
  int (*prepare)(struct mrn_material *m);
  /* the update of n points of this material (one call per batch of points,
   * so that the per-point work is a loop the compiler sees whole) */
  void (*update)(const struct mrn_material *m, mrn_material_point *pt, int n);
  /* speed of the fastest elastic wave (m/s), for time-step estimates */
  double (*wave_speed)(const struct mrn_material *m);
  /* viscous time-step limit (s) for a grid spacing h, h^2 / nu (002, Eq. 36);
   * NULL for models without viscosity */
  double (*viscous_dt)(const struct mrn_material *m, double h);
  /* its form in the implicit integrator; NULL: it has none */
  const mrn_implicit_form *implicit;
} mrn_material_type;

typedef struct mrn_material {
  const mrn_material_type *type;
  char name[64];                               /* user label, defaults to the type name */
  double param[MRN_MATERIAL_MAX_PARAMS];       /* in the order of type->params */
  double derived[MRN_MATERIAL_MAX_DERIVED];    /* set by prepare() */
  int refcount;
  struct mrn_user_box *user;                   /* a user material's law and type (user.h); else NULL */
} mrn_material;

int mrn_material_type_count(void);
const mrn_material_type *mrn_material_type_at(int i);
const mrn_material_type *mrn_material_type_find(const char *name);

/* a material with every parameter at its default; refcount 1 */
mrn_material *mrn_material_new(const mrn_material_type *type);
/* set a parameter by key with range checking; 0 or error (message set) */
int mrn_material_set(mrn_material *m, const char *key, double value);
/* check that required parameters were set and derive constants */
int mrn_material_prepare(mrn_material *m);
void mrn_material_ref(mrn_material *m);
void mrn_material_unref(mrn_material *m);
/* parameter value by key (NAN if unknown) */
double mrn_material_get(const mrn_material *m, const char *key);
double mrn_material_density(const mrn_material *m);
/* Young's modulus used by the a_tau time step (000, Eq. 29) */
double mrn_material_young(const mrn_material *m);

/* "hencky, von_mises": the models that have an implicit form */
const char *mrn_material_implicit_names(char *buf, size_t cap);

/* P-wave speed sqrt((lambda + 2G) / rho) of the isotropic elastic models,
 * which all keep density as their first parameter and lambda, G as their
 * first two derived constants (so one function serves them all) */
double mrn_material_isotropic_wave_speed(const mrn_material *m);

/* the models */
extern const mrn_material_type mrn_material_linear_elastic;
extern const mrn_material_type mrn_material_mohr_coulomb;
extern const mrn_material_type mrn_material_drucker_prager;
extern const mrn_material_type mrn_material_von_mises;
extern const mrn_material_type mrn_material_newtonian;
extern const mrn_material_type mrn_material_hencky;
extern const mrn_material_type mrn_material_neo_hookean;
extern const mrn_material_type mrn_material_mu_i;
extern const mrn_material_type mrn_material_cam_clay;
extern const mrn_material_type mrn_material_user;
/* frees what a user material owns (user.c) */
void mrn_material_user_free(mrn_material *m);

/* defines a model's batch `update` from its one-point update `point_fn` */
#define MRN_MATERIAL_BATCH_UPDATE(point_fn)                                    \
  static void update(const mrn_material *m, mrn_material_point *pt, int n) { \
    for (int i = 0; i < n; i++) point_fn(m, pt + i);                           \
  }

/* Isotropic linear elasticity shared by every small-strain model:
 * ds = lambda tr(de) I + 2 G de. */
static inline void mrn_hooke_increment(double lambda, double shear, const double de[6], double ds[6]) {
  double tr = de[0] + de[1] + de[2];
  for (int k = 0; k < 3; k++) ds[k] = lambda * tr + 2.0 * shear * de[k];
  for (int k = 3; k < 6; k++) ds[k] = 2.0 * shear * de[k];
}

/* The rate-form Hooke update of a point: s <- s + ds (s the rotated
 * start-of-step stress), returning the elastic energy increment per unit
 * volume (000, Eq. 64) with the stress averaged over the step (000 §5.1.4). */
static inline double mrn_hooke_update(double lambda, double shear, const double de[6], double s[6]) {
  double ds[6], old[6];
  for (int k = 0; k < 6; k++) old[k] = s[k];
  mrn_hooke_increment(lambda, shear, de, ds);
  for (int k = 0; k < 6; k++) s[k] += ds[k];
  double mid[6];
  for (int k = 0; k < 6; k++) mid[k] = 0.5 * (old[k] + s[k]);
  return sym_ddot(mid, de);
}

#endif
