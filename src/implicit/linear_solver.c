/* moraine: the UMFPACK behind implicit/linear_solver.h. */
#include "implicit/linear_solver.h"

#include <stdlib.h>
#include <umfpack.h>

#include "core/error.h"

int mrn_csc_reset(mrn_csc *A, int n) {
  int *cp = realloc(A->colptr, (size_t)(n + 1) * sizeof(int));
  if (!cp) return mrn_error_code(MRN_ERR, "implicit: out of memory for a %d x %d matrix", n, n);
  A->colptr = cp;
  A->n = n;
  A->colptr[0] = 0;
  A->colptr[n] = 0;
  return 0;
}

int mrn_csc_push(mrn_csc *A, int row, double value) {
  /* the column being filled starts at colptr[col] and the next free entry is
   * tracked in colptr[n] until the column is closed */
  size_t k = (size_t)A->colptr[A->n];
  if (k >= A->cap) {
    size_t cap = A->cap ? 2 * A->cap : 4096;
    int *ri = realloc(A->rowind, cap * sizeof(int));
    if (!ri) return mrn_error_code(MRN_ERR, "implicit: out of memory for the sparse matrix");
    A->rowind = ri;
    double *v = realloc(A->val, cap * sizeof(double));
    if (!v) return mrn_error_code(MRN_ERR, "implicit: out of memory for the sparse matrix");
    A->val = v;
    A->cap = cap;
  }
  A->rowind[k] = row;
  A->val[k] = value;
  A->colptr[A->n] = (int)k + 1;
  return 0;
}

void mrn_csc_end_column(mrn_csc *A, int col) {
  A->colptr[col + 1] = A->colptr[A->n]; /* colptr[n] holds the running count */
}

void mrn_csc_free(mrn_csc *A) {
  free(A->colptr);
  free(A->rowind);
  free(A->val);
  A->colptr = A->rowind = NULL;
  A->val = NULL;
  A->cap = 0;
  A->n = 0;
}

void mrn_csc_multiply(const mrn_csc *A, const double *x, double *y) {
  for (int i = 0; i < A->n; i++) y[i] = 0.0;
  for (int c = 0; c < A->n; c++)
    for (int k = A->colptr[c]; k < A->colptr[c + 1]; k++) y[A->rowind[k]] += A->val[k] * x[c];
}

int mrn_lu_factor(mrn_lu *lu, const mrn_csc *A) {
  lu->numeric = NULL;
  if (A->n == 0) return 0;
  void *symbolic = NULL;
  double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
  umfpack_di_defaults(control);
  int st = umfpack_di_symbolic(A->n, A->n, A->colptr, A->rowind, A->val, &symbolic, control, info);
  if (st != UMFPACK_OK) return mrn_error_code(MRN_ERR, "implicit: UMFPACK symbolic analysis failed (status %d)", st);
  st = umfpack_di_numeric(A->colptr, A->rowind, A->val, symbolic, &lu->numeric, control, info);
  umfpack_di_free_symbolic(&symbolic);
  if (st != UMFPACK_OK) {
    mrn_lu_free(lu);
    return mrn_error_code(MRN_ERR, "implicit: the %d x %d system is singular (UMFPACK status %d); "
                                   "an active node may be supported by too few material points",
                          A->n, A->n, st);
  }
  return 0;
}

int mrn_lu_solve(const mrn_lu *lu, const mrn_csc *A, const double *b, double *x) {
  if (A->n == 0) return 0;
  double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
  umfpack_di_defaults(control);
  int st = umfpack_di_solve(UMFPACK_A, A->colptr, A->rowind, A->val, x, b, lu->numeric, control, info);
  if (st != UMFPACK_OK) return mrn_error_code(MRN_ERR, "implicit: UMFPACK solve failed (status %d)", st);
  return 0;
}

void mrn_lu_free(mrn_lu *lu) {
  if (lu->numeric) umfpack_di_free_numeric(&lu->numeric);
  lu->numeric = NULL;
}

int mrn_linear_solve(const mrn_csc *A, const double *b, double *x) {
  mrn_lu lu;
  int rc = mrn_lu_factor(&lu, A);
  if (!rc) rc = mrn_lu_solve(&lu, A, b, x);
  mrn_lu_free(&lu);
  return rc;
}
