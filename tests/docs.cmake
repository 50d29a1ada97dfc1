# Documentation checks, included from tests/CMakeLists.txt.
# doc.api_reference_complete: doc/lua-api.md documents every option group and
# key that `moraine --list-options` prints, and every material model, shape
# function, transfer preset, stress update, boundary kind, output field,
# diagnostics column, method and command-line option found in the sources
# (rules in tests/python/check_api_doc.py). Needs only the Python standard library.
add_test(NAME doc.api_reference_complete
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_api_doc.py
                 $<TARGET_FILE:moraine> ${CMAKE_SOURCE_DIR}/doc/lua-api.md)
set_tests_properties(doc.api_reference_complete PROPERTIES LABELS "doc;python")

# doc.decks_*: every code block of the user documentation whose fence is
# "```lua deck" runs as a deck and must exit 0 (tests/python/check_doc_decks.py),
# so the examples cannot rot; one test per document so they run in parallel.
foreach(doc README.md doc/getting-started.md doc/tutorial-column-collapse.md doc/lua-api.md)
  get_filename_component(stem ${doc} NAME_WE)
  string(REPLACE "-" "_" stem ${stem})
  add_test(NAME doc.decks_${stem}
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_doc_decks.py
                   $<TARGET_FILE:moraine> ${CMAKE_CURRENT_BINARY_DIR}/out/doc_decks ${CMAKE_SOURCE_DIR}/${doc})
  set_tests_properties(doc.decks_${stem} PROPERTIES LABELS "doc;python" ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
endforeach()
# the tutorial's two decks settle and collapse a column four times (10-20 s):
# the sanitizer pass leaves them to the release pass
set_tests_properties(doc.decks_tutorial_column_collapse PROPERTIES LABELS "doc;python;long")

# doc.api_reference_selftest: check_api_doc.py notices a missing material model,
# shape function, strategy, stress update, boundary condition, time-step policy
# and deck key (it removes one of each from a copy of lua-api.md)
add_test(NAME doc.api_reference_selftest
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_api_doc_selftest.py
                 $<TARGET_FILE:moraine> ${CMAKE_SOURCE_DIR}/doc/lua-api.md)
set_tests_properties(doc.api_reference_selftest PROPERTIES LABELS "doc;python" ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
