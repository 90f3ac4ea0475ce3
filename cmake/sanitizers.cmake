# SPDX-License-Identifier: MIT
# Sanitizer and fuzzing builds (docs/hardening.md).
#
# APCI_SANITIZE: a -fsanitize= list applied to every target, e.g.
#   -DAPCI_SANITIZE=address,undefined   the whole suite under ASan + UBSan
#   -DAPCI_SANITIZE=thread              the threaded tests under TSan
# APCI_FUZZ=ON (clang only): every library is built with libFuzzer coverage
#   plus ASan + UBSan, and tests/fuzz builds real libFuzzer programs. Without
#   it, tests/fuzz builds the same fuzz targets with a replay main that runs
#   the seed corpus and every kept crash as ordinary tests.
set(APCI_SANITIZE "" CACHE STRING "Sanitizers for every target (-fsanitize= list), empty for none")
option(APCI_FUZZ "Build the libFuzzer programs (needs clang)" OFF)

if(APCI_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "APCI_FUZZ needs clang (libFuzzer): configure with "
                        "-DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14")
  endif()
  if(APCI_SANITIZE)
    message(FATAL_ERROR "APCI_FUZZ brings its own sanitizers (address,undefined); leave APCI_SANITIZE empty")
  endif()
  set(APCI_FUZZ_SANITIZERS address,undefined)
  add_compile_options(-fsanitize=fuzzer-no-link,${APCI_FUZZ_SANITIZERS}
                      -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${APCI_FUZZ_SANITIZERS})
elseif(APCI_SANITIZE)
  # No recovery: the first report fails the test that caused it.
  add_compile_options(-fsanitize=${APCI_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${APCI_SANITIZE})
  # clang links a C program with the C part of UBSan's runtime only; one that links libapci,
  # whose C++ is instrumented, needs the C++ part too, and the C++ library that part uses
  # (examples/pcap_tc_init.c, tests/driver/consumer).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang" AND APCI_SANITIZE MATCHES "undefined")
    add_link_options("$<$<LINK_LANGUAGE:C>:-fsanitize-link-c++-runtime;-lstdc++>")
  endif()
  # gcc 12's flow-sensitive warnings see the sanitizers' instrumentation: it
  # reports std::regex's internal std::function as maybe uninitialized
  # (libstdc++ code, not ours). The warning stays an error in every build
  # without sanitizers, where it means what it says.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-Wno-maybe-uninitialized)
  endif()
endif()

# clang links a sanitizer runtime into executables only; a shared library then
# has undefined sanitizer symbols, so it cannot be linked with --no-undefined.
if((APCI_FUZZ OR APCI_SANITIZE) AND CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  set(APCI_SANITIZER_RUNTIME_IN_EXECUTABLE ON)
else()
  set(APCI_SANITIZER_RUNTIME_IN_EXECUTABLE OFF)
endif()

# apci_threaded_gtest(TARGET [gtest_discover_tests arguments]): discovers the
# tests of a GoogleTest program that runs threads (daemon, transports, the
# driver's thread tests) with the ctest label "threaded", and registers the
# program, so the ThreadSanitizer stage builds only these (target
# threaded_tests) and runs only them (ctest -L threaded).
define_property(GLOBAL PROPERTY APCI_THREADED_TESTS
  BRIEF_DOCS "test programs that run threads" FULL_DOCS "built and run by the TSan stage")
function(apci_threaded_gtest target)
  gtest_discover_tests(${target} ${ARGN} PROPERTIES LABELS threaded)
  set_property(GLOBAL APPEND PROPERTY APCI_THREADED_TESTS ${target})
endfunction()
