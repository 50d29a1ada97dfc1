/* moraine: the weighted-least-squares kernel correction (002, Eqs. 53-63).
 *
 * For a particle with kernel values N_i at nodes offset b_i = x_i - x_p:
 *   M = sum_i N_i P(b_i)^T P(b_i),  P(b) = [1, b]        (002, Eqs. 55-56)
 *   M^-1 = [[C1, C2^T], [C2, C3]]                        (002, Eq. 57)
 *   N^_i = (C1 + C2 . b_i) N_i                           (002, Eq. 58)
 *   grad N^_i = (C2 + C3 b_i) N_i                        (002, Eq. 62)
 * The corrected kernel reproduces constant and linear fields exactly
 * (002, Eqs. 38-41). With a full interior support C1 = 1, C2 = 0 and the
 * gradient is the MLS-MPM one, D^-1 b_i N_i (002 Remark 4). */
#ifndef MRN_TRANSFER_WLS_H
#define MRN_TRANSFER_WLS_H

/* N (count), dN (count x dim), offset (count x dim) are updated in place:
 * the values when `values` is set, the gradients when `gradients` is set.
 * Returns 0, or 1 when the moment matrix is singular (nothing is changed). */
int mrn_wls_correct(int dim, int count, double *N, double *dN, const double *offset, int values, int gradients);

#endif
