# Distributed runs under mpirun (scripts/mpirun: Open MPI, oversubscribed),
# registered when the build has MPI (doc/parallel.md). Each runs one thread
# per process; the label `mpi` selects them.
set(MORAINE_PAR_DIR ${CMAKE_CURRENT_SOURCE_DIR}/parallel)
set(MORAINE_PAR_DECK ${MORAINE_PAR_DIR}/equivalence.lua)

# 1, 2 and 3 processes: the same diagnostics and particle states to 1e-12 after 1000 steps
add_test(NAME mpi.equivalence_collapse2d
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence collapse2d 1000 2 3)
# the same in 3D, and with the slabs re-cut every 50 steps
add_test(NAME mpi.equivalence_cube3d
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence cube3d 1000 2 3 --rebalance 50)
# XPIC(2): each smoothing pass with its own halo sum
add_test(NAME mpi.equivalence_xpic
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_xpic collapse2d 500 2 3 --transfer XPIC2)
# scheme volumetric = "fbar": the divergence's scatter with its own halo sum, USF in 2D and USL in 3D
add_test(NAME mpi.equivalence_fbar
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_fbar collapse2d 500 2 3 --volumetric fbar)
add_test(NAME mpi.equivalence_fbar3d
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_fbar3d cube3d 300 3 --volumetric fbar)
# scheme holds = "particles": FLIP's V before its holds, from the momentum of the halo sum
add_test(NAME mpi.equivalence_holds
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_holds collapse2d 500 2 3 --set holds=particles)
# APIC's initial affine field of a block added after 100 steps, found over every process's particles
add_test(NAME mpi.equivalence_late_affine
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_late cube3d 300 2 3 --set late=100)
# particles made or loaded during the run (tests/parallel/particles.lua): inflow sources over the cuts (and
# the slabs re-cut every 50 steps), particles split across them, point forces on particles of every process
set(MORAINE_PAR_PARTICLES ${MORAINE_PAR_DIR}/particles.lua)
foreach(spec "source 400 2 3 --rebalance 50" "split 400 2 3" "point 600 2 3")
  separate_arguments(args UNIX_COMMAND "${spec}")
  list(GET args 0 case)
  add_test(NAME mpi.equivalence_${case}
           COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine>
                   ${MORAINE_PAR_PARTICLES} ${MORAINE_TEST_OUT}/mpi_particles ${args})
endforeach()
# walls, rigid bodies and contact between bodies with the contact across the cuts (tests/parallel/walls.lua):
# a block sliding on a moving inclined friction wall (re-cut every 20 steps as well), a box body pushed
# into a column, two blocks colliding with friction
set(MORAINE_PAR_WALLS ${MORAINE_PAR_DIR}/walls.lua)
add_test(NAME mpi.equivalence_incline
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_WALLS}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_walls incline 300 2 3 --rebalance 20)
add_test(NAME mpi.equivalence_push
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_WALLS}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_walls push 300 2 3)
add_test(NAME mpi.equivalence_blocks
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_WALLS}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_walls blocks 300 2 3)
# a wall's and a rigid body's state and contacts saved on 3 processes, continued on 1 and on 2
foreach(case incline push)
  add_test(NAME mpi.restart_${case}
           COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/restart.py $<TARGET_FILE:moraine> ${MORAINE_PAR_WALLS}
                   ${MORAINE_TEST_OUT}/mpi_restart_${case} ${case} 150)
endforeach()
# periodic along y: the last slab and the first sum their band through the wrap (with 2 processes the
# same peer on both sides), particles wrap from one to the other
add_test(NAME mpi.equivalence_periodic
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_periodic periodic2d 1000 2 3)
# CPDI: a bar stretching along y, its domains widening the halo band to h = 2 (asserted by the deck)
add_test(NAME mpi.equivalence_cpdi
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_cpdi cpdi2d 250 2 3)
# CPDI2: the same bar, its tracked corners (a particle field) migrating with the particles
add_test(NAME mpi.equivalence_cpdi2
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_cpdi2 cpdi2d 250 2 3 --set shape=cpdi2)
# cpGIMP: the same bar, its boxes widening the band to h = 2 (asserted by the deck)
add_test(NAME mpi.equivalence_cpgimp
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_cpgimp cpgimp2d 250 2 3)
# gap_check on a friction wall along the cut axis: a disk rolling down it across the cuts (the deck
# asserts that gap_check changes the run)
add_test(NAME mpi.equivalence_gap_check
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/equivalence.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                 ${MORAINE_TEST_OUT}/mpi_equivalence_gap_check rolling2d 1000 2 3)
# the VTK series of the 3-process collapse read by ParaView's readers: a .pvtp per snapshot declaring its
# pieces' arrays, every particle once, as on one process; the grid snapshots equal the one-process run's
add_test(NAME mpi.vtk_series
         COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/check_vtk.py
                 ${MORAINE_TEST_OUT}/mpi_equivalence/collapse2d_np1 collapse2d_np1
                 ${MORAINE_TEST_OUT}/mpi_equivalence/collapse2d_np3 collapse2d_np3 3)
set_tests_properties(mpi.vtk_series PROPERTIES DEPENDS mpi.equivalence_collapse2d)
# saved on 3 processes, continued on 1 and on 2: the straight run's state
foreach(case collapse2d cube3d)
  add_test(NAME mpi.restart_${case}
           COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/restart.py $<TARGET_FILE:moraine> ${MORAINE_PAR_DECK}
                   ${MORAINE_TEST_OUT}/mpi_restart_${case} ${case} 500)
endforeach()
# the same with sources (their books and progress in the checkpoint) and with particles split
foreach(case source split)
  add_test(NAME mpi.restart_${case}
           COMMAND ${Python3_EXECUTABLE} ${MORAINE_PAR_DIR}/restart.py $<TARGET_FILE:moraine> ${MORAINE_PAR_PARTICLES}
                   ${MORAINE_TEST_OUT}/mpi_restart_${case} ${case} 200)
endforeach()
# crossing two slabs in a step, empty processes, a particle leaving (a stop; a deletion booked as
# outflow), a Lua error on one process,
# a grid too thin, CPDI domains too wide for the slabs, SIGINT to mpirun; the crossing's VTK pieces, empty
# ones among them; a VTK series saved on 3 processes and continued on 2 from an earlier checkpoint (the later
# pieces replaced)
add_test(NAME mpi.robust COMMAND ${MORAINE_PAR_DIR}/robust.sh $<TARGET_FILE:moraine> ${MORAINE_TEST_OUT}/mpi_robust
                                 ${Python3_EXECUTABLE})
# the cases share the two equivalence directories' one-process runs: one at a time
set_tests_properties(mpi.equivalence_collapse2d mpi.equivalence_cube3d mpi.equivalence_xpic mpi.equivalence_fbar mpi.equivalence_holds
                     mpi.equivalence_fbar3d mpi.equivalence_late_affine mpi.equivalence_source
                     mpi.equivalence_split mpi.equivalence_point mpi.equivalence_incline mpi.equivalence_push
                     mpi.equivalence_blocks mpi.restart_incline mpi.restart_push mpi.equivalence_periodic
                     mpi.equivalence_cpdi mpi.equivalence_cpdi2 mpi.equivalence_cpgimp mpi.equivalence_gap_check mpi.vtk_series
                     mpi.restart_collapse2d mpi.restart_cube3d mpi.restart_source mpi.restart_split mpi.robust
                     PROPERTIES LABELS mpi RUN_SERIAL TRUE ENVIRONMENT "OMP_NUM_THREADS=1;OMP_WAIT_POLICY=PASSIVE")
