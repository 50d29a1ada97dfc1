/* moraine: contact between deformable bodies (multi-velocity field).
 *
 * A body is a group of particles (add_particles{body = "name"}); particles
 * given no body belong to the body "default". Its index is the registered
 * particle field "body", so that it follows the particles through sorting,
 * deletion, checkpoints and outputs. Without a contact pair the step is the
 * single-field step and the body field is only a label.
 *
 * With contact (Bardenhagen et al. 2000, 2001; Nairn's average normal),
 * each body gets its own nodal field, its mass, momentum, force and mass
 * gradient, scattered from its particles alone. Where two or more bodies
 * have mass, each body's velocity is compared with the node's
 * centre-of-mass velocity along the contact normal: a body approaching the
 * others has its normal velocity set to the common one and Coulomb friction
 * (its pair's mu) bounds the change of its tangential velocity; a body
 * moving away is left free. Every particle then takes its velocity,
 * gradient and position from its own body's field. See doc/numerics.md,
 * "Contact between bodies". */
#ifndef MRN_SOLVER_CONTACT_H
#define MRN_SOLVER_CONTACT_H

#include "grid/grid.h"
#include "transfer/context.h"

struct mrn_sim;

#define MRN_MAX_BODIES 16
#define MRN_BODY_NAME 32
#define MRN_BODY_FIELD "body" /* the registered particle field of the body index */

typedef enum { MRN_CONTACT_FRICTION = 0, MRN_CONTACT_BONDED } mrn_contact_kind;

typedef struct mrn_contact_pair {
  int a, b;              /* body indices, a != b */
  mrn_contact_kind kind; /* friction (mu = 0: frictionless) or bonded (one field, as without contact) */
  double mu;             /* Coulomb coefficient */
  int has_normal;        /* 1: `normal` is the contact normal everywhere (a flat interface) */
  double normal[3];      /* unit, from body a into body b */
} mrn_contact_pair;

typedef struct mrn_contact {
  int nbodies;                              /* body 0 is "default" */
  char name[MRN_MAX_BODIES][MRN_BODY_NAME];
  int npairs;                               /* 0: the single-field step */
  mrn_contact_pair pair[MRN_MAX_BODIES * (MRN_MAX_BODIES - 1) / 2];
  /* the per-body nodal fields, nbodies blocks of the grid's size; view[b] is
   * the grid with its nodal arrays replaced by body b's */
  size_t nnode;
  double *mass, *mom, *vel, *vel_new, *force, *grad;
  mrn_grid view[MRN_MAX_BODIES];
  double *L; /* 9 per particle: the velocity gradients of a pass */
  size_t L_cap;
} mrn_contact;

/* The index of body `name`, registered (with the body field) if new; -1 on
 * error (too many bodies, a bad name; message set). */
int mrn_sim_body(struct mrn_sim *sim, const char *name);
/* the body of particles first .. first + count - 1 */
void mrn_sim_set_body(struct mrn_sim *sim, size_t first, size_t count, int body);
/* the index of an existing body, or -1 */
int mrn_sim_body_find(const struct mrn_sim *sim, const char *name);
/* Contact between bodies a and b (names of existing bodies); `normal`, when
 * not NULL, is the contact normal from a into b at every node (a flat
 * interface), else the average mass-gradient normal is taken. Replaces an
 * earlier law for the pair. 0 or an error. */
int mrn_sim_add_contact(struct mrn_sim *sim, const char *a, const char *b, mrn_contact_kind kind, double mu,
                        const double *normal);
void mrn_contact_free(mrn_contact *c);

/* One explicit step on the per-body fields, any stress update and PIC,
 * FLIP, blend or APIC/TPIC (not XPIC). The particles are moved; the end of
 * step check is the caller's. 0 or an error. */
int mrn_contact_step(struct mrn_sim *sim, mrn_transfer *tr, double dt);

/* The grid stages of the explicit step (solver/step.c) on the nodal arrays
 * of g, the simulation's grid or a body's view of it */
void mrn_grid_velocity_on(struct mrn_sim *sim, mrn_grid *g);
/* the simulation's conditions on a velocity field of its grid (faces,
 * walls, constraints, inlets; mrn_transfer.hold); ctx is the simulation,
 * `weight` that of the field in the particles' velocities, with which the
 * walls book the impulses of these holds */
void mrn_sim_hold_velocity(void *ctx, double *vel, double weight);
void mrn_grid_update_on(struct mrn_sim *sim, mrn_grid *g, double dt);
/* the share of a change of V (before the forces) that reaches the
 * particles' momentum under scheme s: 1 for PIC-like updates, 0 for FLIP,
 * 1 - X for a blend (solver/step.c) */
double mrn_hold_share(const mrn_scheme *s);

#endif
