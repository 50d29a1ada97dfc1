/* moraine: the engine's C API, for programs that drive it without Lua.
 *
 *   #include <moraine/moraine.h>
 *   cc prog.c $(pkg-config --cflags --libs moraine)
 *
 * A simulation (solver/simulation.h) is built from a grid, materials
 * (material/material.h) and particles seeded in regions
 * (particles/region.h), and run (solver/run.h) with its outputs
 * (io/output.h) as observers; checkpoints are io/checkpoint.h; bodies and
 * their contact, solver/contact.h; particle splitting, solver/split.h. Every
 * call that can fail returns an error code of core/error.h with a message
 * from mrn_error_message(). doc/c-api.md walks through examples/c_api/drop.c. */
#ifndef MRN_MORAINE_H
#define MRN_MORAINE_H

#include "core/error.h"
#include "core/log.h"
#include "core/warn.h"
#include "implicit/implicit.h"
#include "io/checkpoint.h"
#include "io/output.h"
#include "material/material.h"
#include "particles/region.h"
#include "solver/contact.h"
#include "solver/run.h"
#include "solver/simulation.h"
#include "solver/split.h"

#endif
