/* moraine: the simulation's persistent scalars, in one list.
 *
 * Each row is one value of a simulation that a checkpoint keeps, as the
 * attribute of /simulation of the same name (doc/checkpoint-format.md). From
 * this list follow the members of mrn_sim (simulation.h) and their values in
 * a new simulation, the checkpoint writer and reader with their checks
 * (io/checkpoint.c, io/checkpoint_read.c) and the value a file written before
 * a row existed loads with. A new persistent scalar is one row here (and one
 * line of the format's table).
 *
 *   X(ctype, name, kind, check, since, initial, units, doc)
 *
 *   ctype    the member's C type
 *   name     the member, and the attribute of /simulation
 *   kind     how the file stores it: F64 (float64), F64X3 (float64[3], ctype
 *            the element), I32 (int32), I64 (int64), NAME (a string, one of
 *            the names of `check`, for an enum)
 *   check    what a file's value must be: MRN_ANY (a finite number),
 *            MRN_AT_LEAST(min), MRN_IN(lo, hi) (integers), MRN_COUNTER (a
 *            step or particle counter), MRN_ONE_OF(names function)
 *   since    the first format version whose files always hold it
 *   initial  its value in a new simulation, which is also what a file of a
 *            version before `since` that lacks it loads with (before the
 *            feature existed the run behaved as with that value)
 *   units    in a 3D simulation; 2D simulations are per metre of thickness
 *   doc      what it is
 *
 * dim, shape, kernel_boundary and gravity come from mrn_sim_config, which
 * sets them after the initial values. */
#ifndef MRN_SOLVER_SIM_SCALARS_H
#define MRN_SOLVER_SIM_SCALARS_H

#include <math.h>
#include <stdint.h>

/* clang-format off */
#define MRN_SIM_SCALARS(X)                                                                                       \
  X(int, dim, I32, MRN_IN(2, 3), 1, 0, "", "2 or 3")                                                       \
  X(mrn_shape_kind, shape, NAME, MRN_ONE_OF(mrn_shape_names), 1, 0, "", "shape function")                 \
  X(mrn_kernel_boundary, kernel_boundary, NAME, MRN_ONE_OF(mrn_kernel_boundary_names), 1, 0, "",           \
    "how the kernels treat the faces")                                                                            \
  X(double, time, F64, MRN_ANY, 1, 0.0, "s", "model time")                                                  \
  X(long, step, I64, MRN_COUNTER, 1, 0, "", "steps taken")                                                  \
  X(double, dt, F64, MRN_AT_LEAST(0.0), 1, 0.0, "s", "the step size of the last (or next) step")           \
  X(double, gravity, F64X3, MRN_ANY, 1, 0.0, "m/s^2", "gravitational acceleration (z = 0 in 2D)")          \
  X(double, damping_cundall, F64, MRN_AT_LEAST(0.0), 1, 0.0, "",                                            \
    "D of Cundall's local non-viscous damping of the grid forces (000, Eqs. 61-62)")                              \
  X(double, damping_viscous, F64, MRN_AT_LEAST(0.0), 1, 0.0, "1/s",                                         \
    "alpha of the mass-proportional viscous damping f = -alpha m v")                                              \
  X(double, work_friction, F64, MRN_ANY, 1, 0.0, "J", "work of friction (000, Eq. 66), <= 0")              \
  X(double, work_damping, F64, MRN_ANY, 1, 0.0, "J", "work of the damping forces, <= 0")                   \
  X(double, work_external, F64, MRN_ANY, 2, 0.0, "J", "work of the point forces (solver/point_force.h)")    \
  X(double, work_walls, F64, MRN_ANY, 3, 0.0, "J", "work the rigid walls did on the material (grid/wall.h)")  \
  X(double, work_contact, F64, MRN_ANY, 3, 0.0, "J", "work of friction between bodies (solver/contact.h), <= 0")  \
  X(double, load_factor, F64, MRN_ANY, 2, 1.0, "", "factor on every point force")                          \
  X(double, energy_ref, F64, MRN_ANY, 1, 0.0, "J",                                                          \
    "E_k + E_g + E_el when the energy balance started (000, Eq. 68)")                                             \
  X(int, energy_ref_set, I32, MRN_IN(0, 1), 1, 0, "", "1 once the energy balance has started")             \
  X(mrn_leave_policy, on_leave, NAME, MRN_ONE_OF(mrn_leave_policy_names), 2, MRN_LEAVE_STOP, "",           \
    "what a particle leaving the grid does")                                                                      \
  X(long, outflow_particles, I64, MRN_COUNTER, 2, 0, "", "particles deleted on leaving the grid")           \
  X(double, outflow_mass, F64, MRN_AT_LEAST(0.0), 2, 0.0, "kg", "their mass")                               \
  X(double, energy_outflow, F64, MRN_ANY, 2, 0.0, "J",                                                      \
    "their E_k + E_g + E_el - W_pl when deleted, added back in W_MPM")                                            \
  X(long, inflow_particles, I64, MRN_COUNTER, 3, 0, "", "particles added by sources or during a run")          \
  X(double, inflow_mass, F64, MRN_AT_LEAST(0.0), 3, 0.0, "kg", "their mass")                                \
  X(double, energy_inflow, F64, MRN_ANY, 3, 0.0, "J",                                                       \
    "their E_k + E_g + E_el when added, taken off in W_MPM")                                                      \
  X(double, work_inflow, F64, MRN_ANY, 3, 0.0, "J", "work of the sources' inlet nodes on the material")    \
  X(double, mass_scaling, F64, MRN_AT_LEAST(1.0), 3, 1.0, "",                                               \
    "factor on the inertial mass of every particle (gravity acts on the true mass)")                              \
  X(double, mass_floor, F64, MRN_AT_LEAST(0.0), 1, 0.0, "kg", "nodes lighter than this count as empty")    \
  X(long, sort_every, I64, MRN_COUNTER, 2, 0, "steps",                                                   \
    "reorder the particles by grid block every this many steps, 0: never")                                        \
  X(int, affine_pending, I32, MRN_IN(0, 1), 1, 0, "",                                                      \
    "1: initial velocities were assigned, grad v and B are initialised at the next run")                       \
  X(double, split_stretch, F64, MRN_AT_LEAST(0.0), 3, 0.0, "",                                              \
    "split a particle whose domain stretched beyond this (solver/split.h); 0: never")                             \
  X(int, split_max_level, I32, MRN_IN(0, MRN_SPLIT_MAX_LEVEL), 3, 0, "",                                    \
    "the most splits in a particle's ancestry")                                                                   \
  X(long, split_count, I64, MRN_COUNTER, 3, 0, "", "particles split so far")
/* clang-format on */
/* the deepest split_max_level (a particle's volume halves at each split) */
#define MRN_SPLIT_MAX_LEVEL 20

/* what a file's value must be (the `check` column); the macros expand to
 * the initialisers of an mrn_scalar_check */
typedef struct mrn_scalar_check {
  double min;                          /* reals: at least this */
  int64_t lo, hi;                      /* integers: in [lo, hi] */
  const char *const *(*names)(void);   /* NAME: the enum's names, NULL-terminated */
} mrn_scalar_check;
#define MRN_ANY .min = -HUGE_VAL
#define MRN_AT_LEAST(x) .min = (x)
#define MRN_IN(l, h) .lo = (l), .hi = (h)
/* a step or particle counter: far beyond any run, far below overflow (the
 * engine increments its counters without checks) */
#define MRN_MAX_COUNTER ((int64_t)1 << 53)
#define MRN_COUNTER .lo = 0, .hi = MRN_MAX_COUNTER
#define MRN_ONE_OF(f) .names = (f)

/* a row's member declaration: the F64X3 kind is an array of three */
#define MRN_SIM_DECLARE(ctype, name, kind, ...) MRN_SIM_DECLARE_##kind(ctype, name)
#define MRN_SIM_DECLARE_F64(ctype, name) ctype name;
#define MRN_SIM_DECLARE_F64X3(ctype, name) ctype name[3];
#define MRN_SIM_DECLARE_I32(ctype, name) ctype name;
#define MRN_SIM_DECLARE_I64(ctype, name) ctype name;
#define MRN_SIM_DECLARE_NAME(ctype, name) ctype name;

/* the members of mrn_sim */
#define MRN_SIM_MEMBER(ctype, name, kind, ...) MRN_SIM_DECLARE_##kind(ctype, name)

#endif
