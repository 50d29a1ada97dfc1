/* moraine: particle <-> grid transfer kernels, specialised for 2D and 3D.
 *
 * The same source (kernels_impl.h) is compiled twice, with DIM = 2 and 3;
 * these wrappers pick the right one. */
#ifndef MRN_TRANSFER_KERNELS_H
#define MRN_TRANSFER_KERNELS_H

struct mrn_sim;

/* P2G: nodal mass and momentum (000, Eqs. 6 and 16) when `momentum` is set,
 * internal force -sum V sigma . grad N (002, Fig. 1 step 3) when `force` is set.
 * The grid arrays touched are cleared first. */
void mrn_p2g_2d(struct mrn_sim *sim, int momentum, int force);
void mrn_p2g_3d(struct mrn_sim *sim, int momentum, int force);

/* velocity gradient L_p = sum_i v_i (x) grad N_i (000, Eqs. 44-45) from the
 * nodal velocity array `gvel`, stored in particles.gradv */
void mrn_gradient_2d(struct mrn_sim *sim, const double *gvel);
void mrn_gradient_3d(struct mrn_sim *sim, const double *gvel);

/* G2P: new particle velocities by the scheme (000, Eqs. 31, 33, 37) and the
 * position increments (000, Eqs. 32, 36, 38). When `dx` is NULL positions are
 * moved at once, otherwise the increments are stored there (3 per particle). */
void mrn_g2p_2d(struct mrn_sim *sim, double dt, double *dx);
void mrn_g2p_3d(struct mrn_sim *sim, double dt, double *dx);

static inline void mrn_p2g(struct mrn_sim *sim, int dim, int momentum, int force) {
  if (dim == 2) mrn_p2g_2d(sim, momentum, force); else mrn_p2g_3d(sim, momentum, force);
}
static inline void mrn_gradient(struct mrn_sim *sim, int dim, const double *gvel) {
  if (dim == 2) mrn_gradient_2d(sim, gvel); else mrn_gradient_3d(sim, gvel);
}
static inline void mrn_g2p(struct mrn_sim *sim, int dim, double dt, double *dx) {
  if (dim == 2) mrn_g2p_2d(sim, dt, dx); else mrn_g2p_3d(sim, dt, dx);
}

#endif
