/* moraine: the motion-integration strategy and stress-update scheme.
 *
 * 000 (§3, Table 1) factors every strategy into three independent choices,
 * and moraine exposes them that way:
 *   1. grid velocity from the particles: plain mass-weighted (000, Eq. 17),
 *      affine APIC (000, Eqs. 23-27) or Taylor (000, Eqs. 19-22);
 *   2. particle velocity update: PIC (000, Eq. 31), FLIP (000, Eq. 33), the
 *      blend X FLIP + (1 - X) PIC (000, Eq. 37) or XPIC(m) (000, Eq. 40);
 *   3. position update: with the grid velocity (000, Eq. 32), with the new
 *      particle velocity (000, Eqs. 36 and 38) or XPIC's second-order update
 *      (000, Eq. 41).
 * Named presets set all three (000 Table 1, 002 Fig. 1): PIC, FLIP, FLIPX
 * (e.g. "FLIP0.99"), NFLIP, NFLIPX, APIC, AFLIP, AFLIPX, ANFLIP, ANFLIPX, TPIC,
 * TFLIP, TFLIPX, XPIC(m), MLS (APIC with the MLS kernel gradient, 002 Remark 1).
 * The stress update happens first (USF), last with the updated grid velocity
 * (USL), last with a velocity re-mapped from the updated particle velocities
 * (MUSL), or half first and half last (USAVG) (000 §3.4). */
#ifndef MRN_TRANSFER_SCHEME_H
#define MRN_TRANSFER_SCHEME_H

typedef enum { MRN_VGRID_PLAIN = 0, MRN_VGRID_AFFINE, MRN_VGRID_TAYLOR } mrn_grid_velocity_kind;
typedef enum { MRN_VUPDATE_PIC = 0, MRN_VUPDATE_FLIP, MRN_VUPDATE_BLEND, MRN_VUPDATE_XPIC } mrn_velocity_update_kind;
typedef enum { MRN_XUPDATE_GRID = 0, MRN_XUPDATE_PARTICLE, MRN_XUPDATE_XPIC } mrn_position_update_kind;
typedef enum { MRN_STRESS_USF = 0, MRN_STRESS_USL, MRN_STRESS_MUSL, MRN_STRESS_USAVG } mrn_stress_update_kind;
/* the volumetric part of the velocity gradient the material update takes:
 * each particle's own, or averaged over the nodes (F-bar, solver/update.c) */
typedef enum { MRN_VOLUMETRIC_STANDARD = 0, MRN_VOLUMETRIC_FBAR } mrn_volumetric_kind;
/* where the holds of the step's first V (faces, walls, constraints, inlets)
 * reach FLIP's increment V~ - V: left out of it, so that a particle keeps
 * the normal velocity a face stopped on the grid (000, CB-Geo), or taken
 * into it, V being the velocity before its holds (the two-stage contact of
 * Nairn, Hammerquist and Smith 2020; solver/step.c, release_holds) */
typedef enum { MRN_HOLDS_GRID = 0, MRN_HOLDS_PARTICLES } mrn_holds_kind;

#define MRN_XPIC_MAX_ORDER 16

typedef struct mrn_scheme {
  mrn_grid_velocity_kind grid_velocity;
  mrn_velocity_update_kind velocity_update;
  mrn_position_update_kind position_update;
  double flip_fraction; /* X of 000, Eq. 37 (1 = FLIP, 0 = PIC) */
  int xpic_order;       /* m of 000, Eqs. 39-41 */
  int mls_gradient;     /* 1: MLS kernel gradient (002, Eq. 62 everywhere) */
  mrn_stress_update_kind stress_update;
  mrn_volumetric_kind volumetric; /* kept by a preset, as the stress update */
  mrn_holds_kind holds;           /* kept by a preset; matters where the update has a FLIP part */
  char name[32];        /* the preset name, or a description of the three choices */
} mrn_scheme;

/* default: FLIP + USF */
void mrn_scheme_default(mrn_scheme *s);
/* Set the three choices from a preset name (the stress update is kept).
 * Returns 0, or an error listing the valid names. */
int mrn_scheme_from_preset(const char *name, mrn_scheme *s);
/* Check that the three choices fit together; 0 or an error */
int mrn_scheme_validate(const mrn_scheme *s);
/* Recompute s->name from the three choices */
void mrn_scheme_describe(mrn_scheme *s);
/* names, NULL-terminated (FLIPX-style presets take a number suffix, XPIC an order) */
const char *const *mrn_scheme_preset_names(void);
const char *const *mrn_stress_update_names(void);
int mrn_stress_update_from_name(const char *name, mrn_stress_update_kind *out);
const char *const *mrn_velocity_update_names(void);
const char *const *mrn_position_update_names(void);
const char *const *mrn_grid_velocity_names(void);
const char *const *mrn_volumetric_names(void);
const char *const *mrn_holds_names(void);
/* index of name in a NULL-terminated list, or -1 */
int mrn_name_index(const char *const *names, const char *name);

#endif
