/* moraine: the motion-integration strategy and stress-update scheme.
 *
 * 000 (§3, Table 1) factors every strategy into three independent choices,
 * and moraine exposes them that way:
 *   1. grid velocity from the particles: plain mass-weighted (000, Eq. 17);
 *   2. particle velocity update: PIC (000, Eq. 31), FLIP (000, Eq. 33) or the
 *      blend X FLIP + (1 - X) PIC (000, Eq. 37);
 *   3. position update: with the grid velocity (000, Eq. 32) or with the new
 *      particle velocity (000, Eqs. 36 and 38).
 * Named presets (PIC, FLIP, FLIPX such as "FLIP0.99", NFLIP, NFLIPX such as
 * "NFLIP0.95") set all three. The stress update happens first (USF), last
 * with the updated grid velocity (USL) or last with a velocity re-mapped from
 * the updated particle velocities (MUSL) (000 §3.4). */
#ifndef MRN_TRANSFER_SCHEME_H
#define MRN_TRANSFER_SCHEME_H

typedef enum { MRN_VGRID_PLAIN = 0 } mrn_grid_velocity_kind;
typedef enum { MRN_VUPDATE_PIC = 0, MRN_VUPDATE_FLIP, MRN_VUPDATE_BLEND } mrn_velocity_update_kind;
typedef enum { MRN_XUPDATE_GRID = 0, MRN_XUPDATE_PARTICLE } mrn_position_update_kind;
typedef enum { MRN_STRESS_USF = 0, MRN_STRESS_USL, MRN_STRESS_MUSL } mrn_stress_update_kind;

typedef struct mrn_scheme {
  mrn_grid_velocity_kind grid_velocity;
  mrn_velocity_update_kind velocity_update;
  mrn_position_update_kind position_update;
  double flip_fraction; /* X of 000, Eq. 37 (1 = FLIP, 0 = PIC) */
  mrn_stress_update_kind stress_update;
  char name[32];        /* the preset name, or "custom" */
} mrn_scheme;

/* default: FLIP + USF */
void mrn_scheme_default(mrn_scheme *s);
/* Set the three choices from a preset name. Returns 0, or an error listing
 * the valid names. */
int mrn_scheme_from_preset(const char *name, mrn_scheme *s);
/* Recompute s->name from the three choices */
void mrn_scheme_describe(mrn_scheme *s);
/* names, NULL-terminated (the FLIPX/NFLIPX presets take a number suffix) */
const char *const *mrn_scheme_preset_names(void);
const char *const *mrn_stress_update_names(void);
int mrn_stress_update_from_name(const char *name, mrn_stress_update_kind *out);
const char *const *mrn_velocity_update_names(void);
const char *const *mrn_position_update_names(void);
const char *const *mrn_grid_velocity_names(void);

#endif
