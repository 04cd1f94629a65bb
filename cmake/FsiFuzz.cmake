# FSI_FUZZ=ON: every library of ours is compiled with libFuzzer's coverage instrumentation and
# AddressSanitizer + UBSan (any report aborts); fsi_add_fuzzer() links a libFuzzer target.
# Configured by scripts/run-fuzzers in build-fuzz/ with clang++ (docs/testing.md, "Fuzzing").

if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "FSI_FUZZ=ON needs clang (libFuzzer), but CMAKE_CXX_COMPILER is "
    "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER}: configure a separate build directory with "
    "-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang, or run scripts/run-fuzzers")
endif()

set(FSI_FUZZ_SANITIZERS address,undefined)

function(fsi_fuzz_instrument target)
  target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,${FSI_FUZZ_SANITIZERS}
    -fno-sanitize-recover=all -fno-omit-frame-pointer -g)
  target_link_options(${target} PRIVATE -fsanitize=${FSI_FUZZ_SANITIZERS})
endfunction()

# fsi_add_fuzzer(NAME SOURCES... LIBS ...): a libFuzzer executable (it brings libFuzzer's main),
# with common/fuzz/fuzz_target.hpp, what every target shares, on its include path.
add_custom_target(fsi_fuzzers)
function(fsi_add_fuzzer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  fsi_configure_target(${name})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/common/fuzz)
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
  target_link_options(${name} PRIVATE -fsanitize=fuzzer)
  add_dependencies(fsi_fuzzers ${name})
endfunction()
