#include "transfer/profile.h"

#include <stddef.h>

double *mrn_profile_seconds = NULL;
