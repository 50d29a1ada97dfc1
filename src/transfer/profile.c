#include "transfer/profile.h"

#include <stddef.h>
#ifdef _OPENMP
#include <omp.h>
#endif

double *mrn_profile_seconds = NULL;

int mrn_profile_threads(int parallel) {
#ifdef _OPENMP
  return parallel ? omp_get_max_threads() : 1;
#else
  (void)parallel;
  return 1;
#endif
}
