/* moraine: sparse linear systems of the implicit integrator.
 *
 * The rest of the code sees only this interface: a square matrix in
 * compressed sparse column form (rows sorted within each column) and a
 * direct solve. The factorisation is done by SuiteSparse UMFPACK (unsymmetric
 * multifrontal LU with partial pivoting); doc/implicit.md explains the choice.
 * The Jacobian of the implicit step (001 §3.4) is not symmetric in general
 * (the second term of 001 Eq. A.9 and the algorithmic stress are not), so a
 * symmetric factorisation would not do. */
#ifndef MRN_IMPLICIT_LINEAR_SOLVER_H
#define MRN_IMPLICIT_LINEAR_SOLVER_H

#include <stddef.h>

typedef struct mrn_csc {
  int n;        /* rows = columns */
  int *colptr;  /* n + 1 */
  int *rowind;  /* nnz */
  double *val;  /* nnz */
  size_t cap;   /* allocated entries of rowind and val */
} mrn_csc;

/* reset to an n x n matrix with no entries; 0 or error (message set) */
int mrn_csc_reset(mrn_csc *A, int n);
/* append entry (row, value) to the column being filled; columns are filled
 * in order, each closed by mrn_csc_end_column(A, col) */
int mrn_csc_push(mrn_csc *A, int row, double value);
void mrn_csc_end_column(mrn_csc *A, int col);
void mrn_csc_free(mrn_csc *A);

/* y = A x */
void mrn_csc_multiply(const mrn_csc *A, const double *x, double *y);

/* A factorisation kept for several right-hand sides */
typedef struct mrn_lu {
  void *numeric;
} mrn_lu;
int mrn_lu_factor(mrn_lu *lu, const mrn_csc *A);
int mrn_lu_solve(const mrn_lu *lu, const mrn_csc *A, const double *b, double *x);
void mrn_lu_free(mrn_lu *lu);

/* Solve A x = b by LU factorisation. Returns 0, or an error (message set)
 * when the matrix is singular or the factorisation fails. */
int mrn_linear_solve(const mrn_csc *A, const double *b, double *x);

#endif
