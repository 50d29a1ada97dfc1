#include "core/memory.h"

#include <unistd.h>

#include "core/error.h"

double mrn_memory_total(void) {
  long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? (double)pages * (double)page : 0.0;
}

int mrn_memory_check(const char *what, double need, const char *hint) {
  double total = mrn_memory_total();
  if (total > 0 && need > total)
    return mrn_error("%s need %.1f GB, more than this machine's %.1f GB of memory%s", what, need / 1e9, total / 1e9,
                     hint);
  return MRN_OK;
}
