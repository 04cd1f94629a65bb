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

# fsi_add_module_library(TARGET ALIAS fsi::NAME SOURCES... [PUBLIC libs...] [PRIVATE libs...]):
# a module's library as every module folder has it: the namespaced alias, the folder's include/
# as its public headers (where the folder has one), and our warnings and sanitizers.
function(fsi_add_module_library target)
  cmake_parse_arguments(ARG "" "ALIAS" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(${target} ${ARG_SOURCES})
  add_library(${ARG_ALIAS} ALIAS ${target})
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/include)
    target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  endif()
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  fsi_configure_target(${target})
endfunction()

# fsi_add_unit_test(NAME SOURCES... LIBS ... [INCLUDES dirs...] [DEFINITIONS defs...]): a GoogleTest
# executable registered with CTest, every test case its own CTest test carrying the label "unit";
# INCLUDES and DEFINITIONS are private to the test (a module's src/, paths to its test data).
function(fsi_add_unit_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;INCLUDES;DEFINITIONS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  fsi_configure_target(${name})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  # common/test_support: the helpers every module's tests share (fsi/test_support/*.hpp).
  target_include_directories(${name} PRIVATE ${ARG_INCLUDES} ${PROJECT_SOURCE_DIR}/common/test_support)
  target_compile_definitions(${name} PRIVATE ${ARG_DEFINITIONS})
  gtest_discover_tests(${name} PROPERTIES LABELS unit DISCOVERY_TIMEOUT 60)
endfunction()
