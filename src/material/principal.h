/* moraine: eigen-decomposition of small symmetric matrices.
 *
 * The plasticity models return-map in principal stresses, the hyperelastic
 * models take the logarithm of the left stretch from the eigenvectors of
 * b = F F^T, and the material-point driver solves its Newton steps with a
 * pseudo-inverse. All of them use one cyclic Jacobi solver: slow for large
 * matrices, but accurate to the last bits for the 3x3 (and up to 6x6) ones
 * used here, even when eigenvalues coincide (isotropic stress, b = I). */
#ifndef MRN_MATERIAL_PRINCIPAL_H
#define MRN_MATERIAL_PRINCIPAL_H

#define MRN_JACOBI_MAX 6

/* Eigenvalues of the symmetric n x n matrix A (row-major, n <= 6) in
 * descending order, and the matching orthonormal eigenvectors as the columns
 * of V (row-major: V[n*a+i] is component a of vector i). */
void mrn_jacobi_eigen(int n, const double *A, double *lam, double *V);

/* Principal values (descending, lam[0] the most tensile stress) and
 * directions of a symmetric tensor in 6-component storage. */
void mrn_sym_eigen(const double s[6], double lam[3], double V[9]);

/* s = sum_i lam_i v_i (x) v_i, the inverse of mrn_sym_eigen */
void mrn_sym_from_principal(const double lam[3], const double V[9], double s[6]);

/* x = A^+ b for an n x n matrix (row-major, n <= 6): the least-squares,
 * minimum-norm solution, singular values below rcond times the largest
 * being treated as zero. Returns the numerical rank. */
int mrn_pinv_solve(int n, const double *A, const double *b, double rcond, double *x);

#endif
