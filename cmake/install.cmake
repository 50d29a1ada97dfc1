# moraine: what `cmake --install` puts under the prefix (doc/c-api.md).
#
#   bin/moraine, bin/moraine-plot           the program and its plotting helper
#   lib/libmoraine.so.*                     the engine
#   include/moraine/moraine.h, */*.h        the engine's C API
#   lib/pkgconfig/moraine.pc                pkg-config --cflags --libs moraine
#   lib/cmake/moraine/                      find_package(moraine): moraine::moraine
#   lib/lua/5.4/moraine.so                  the Lua C module (require "moraine" in lua5.4)
#   share/moraine/lua/moraine/*.lua         the pure-Lua library
#   share/man/man1/moraine.1                the man page, made from moraine --help
#   share/doc/moraine/                      doc/, as moraine --help says
include(CMakePackageConfigHelpers)

# The C API: src/moraine.h and the headers it includes, directly or not. The
# headers keep their module directories and include one another as
# "module/file.h", so a program compiles with -I<prefix>/include/moraine
# (the pkg-config file and the CMake target give it) and writes
# #include <moraine/moraine.h>. tests/install_c_api.sh compiles against
# the installed tree: a header missing here fails it.
set(MORAINE_PUBLIC_HEADERS
  core/error.h core/interrupt.h core/log.h core/parallel.h core/spec.h core/tensor.h core/warn.h
  shape/shape.h
  grid/active.h grid/boundary.h grid/constraint.h grid/grid.h
  particles/particles.h particles/region.h particles/seed.h particles/domain.h
  transfer/blocks.h transfer/context.h transfer/scheme.h
  material/material.h
  solver/contact.h solver/diagnostics.h solver/run.h solver/sim_scalars.h solver/simulation.h solver/source.h
  solver/split.h
  solver/timestep.h
  solver/watchdog.h
  implicit/implicit.h
  io/checkpoint.h io/output.h io/series_h5.h io/stash.h io/vtk.h)
install(FILES src/moraine.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/moraine)
foreach(h IN LISTS MORAINE_PUBLIC_HEADERS)
  get_filename_component(dir ${h} DIRECTORY)
  install(FILES src/${h} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/moraine/${dir})
endforeach()

install(TARGETS moraine_engine EXPORT moraine-targets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} NAMELINK_COMPONENT Development
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS moraine RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS moraine_lua_module LIBRARY DESTINATION ${MORAINE_LUA_CMOD_DIR})
install(DIRECTORY lua/ DESTINATION ${MORAINE_LUA_INSTALL_REL})
install(DIRECTORY doc/ DESTINATION ${CMAKE_INSTALL_DOCDIR}) # Markdown and figures, as `moraine --help` says
install(PROGRAMS scripts/moraine-plot DESTINATION ${CMAKE_INSTALL_BINDIR})

# pkg-config: the prefix found from the file's own place, so that the tree
# may be installed with --prefix or DESTDIR anywhere, or moved
file(RELATIVE_PATH MORAINE_PC_TO_PREFIX "/p/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/p")
string(REGEX REPLACE "/$" "" MORAINE_PC_TO_PREFIX "${MORAINE_PC_TO_PREFIX}")
set(MORAINE_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
set(MORAINE_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
configure_file(cmake/moraine.pc.in ${CMAKE_BINARY_DIR}/moraine.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/moraine.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# find_package(moraine [VERSION]) and the imported target moraine::moraine
set_target_properties(moraine_engine PROPERTIES EXPORT_NAME moraine)
set(MORAINE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/moraine)
install(EXPORT moraine-targets NAMESPACE moraine:: DESTINATION ${MORAINE_CMAKE_DIR})
configure_package_config_file(cmake/moraineConfig.cmake.in ${CMAKE_BINARY_DIR}/moraineConfig.cmake
                              INSTALL_DESTINATION ${MORAINE_CMAKE_DIR})
# 0.x: a minor version may change the API, so only the same minor matches
write_basic_package_version_file(${CMAKE_BINARY_DIR}/moraineConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/moraineConfig.cmake ${CMAKE_BINARY_DIR}/moraineConfigVersion.cmake
        DESTINATION ${MORAINE_CMAKE_DIR})

# The man page: help2man turns moraine --help and --version into moraine.1 at
# build time, so it says what the program says.
if(MORAINE_MAN)
  find_program(HELP2MAN help2man)
  if(NOT HELP2MAN)
    message(FATAL_ERROR "help2man not found: scripts/install-deps.sh installs it, or configure with -DMORAINE_MAN=OFF")
  endif()
  add_custom_command(OUTPUT ${CMAKE_BINARY_DIR}/moraine.1
    COMMAND ${HELP2MAN} --no-info --section=1 --name "Material Point Method simulations described by Lua decks"
            --output=${CMAKE_BINARY_DIR}/moraine.1 $<TARGET_FILE:moraine>
    DEPENDS moraine VERBATIM)
  add_custom_target(man ALL DEPENDS ${CMAKE_BINARY_DIR}/moraine.1)
  install(FILES ${CMAKE_BINARY_DIR}/moraine.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endif()
