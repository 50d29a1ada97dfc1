/* moraine: the checks behind the warnings for legal but suspicious choices
 * (core/warn.h). They look at a simulation about to run or at a seeding and
 * print a warning; nothing is changed. */
#ifndef MRN_SOLVER_SUSPICIOUS_H
#define MRN_SOLVER_SUSPICIOUS_H

#include "solver/simulation.h"

/* before a run: the time-step policy against the stability estimates */
void mrn_suspicious_run(const mrn_sim *sim);
/* after seeding `count` particles with `per_axis` per cell and axis */
void mrn_suspicious_seed(const mrn_sim *sim, int per_axis, long count);

#endif
