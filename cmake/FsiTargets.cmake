# Helpers that give every target of ours the same warnings, sanitizers and test registration.

function(fsi_configure_target target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
    -Woverloaded-virtual -Wcast-align -Wdouble-promotion -Wformat=2
    -Wimplicit-fallthrough
    # GCC 12 reports false -Wrestrict positives on std::string concatenation at -O2 (GCC bug 105329).
    $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
  if(FSI_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(FSI_FUZZ)
    fsi_fuzz_instrument(${target})
  endif()
  if(FSI_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=${FSI_SANITIZE} -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=${FSI_SANITIZE})
  endif()
endfunction()

# fsi_add_unit_test(NAME SOURCES... LIBS ...): a GoogleTest executable registered with CTest,
# every test case its own CTest test carrying the label "unit".
function(fsi_add_unit_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  fsi_configure_target(${name})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  gtest_discover_tests(${name} PROPERTIES LABELS unit DISCOVERY_TIMEOUT 60)
endfunction()
