# Documentation checks, included from tests/CMakeLists.txt.
# doc.api_reference_complete: doc/lua-api.md documents every option group and
# key that `moraine --list-options` prints, and every material model, shape
# function, transfer preset, stress update, boundary kind, output field,
# diagnostics column, method and command-line option found in the sources
# (rules in tests/python/check_api_doc.py). Needs only the Python standard library.
add_test(NAME doc.api_reference_complete
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/python/check_api_doc.py
                 $<TARGET_FILE:moraine> ${CMAKE_SOURCE_DIR}/doc/lua-api.md)
set_tests_properties(doc.api_reference_complete PROPERTIES LABELS "doc;python")
