# SPDX-License-Identifier: MIT
# apci_test_program(NAME SOURCES file... [LIBRARIES lib...] [RUNS program...]
#                   [DEFINITIONS def...] [INCLUDES dir...] [PREFIX prefix] [THREADED]
#                   [EMULATOR program] [DISCOVERY_TIMEOUT seconds] [PROPERTIES name value...]
#                   [OPTIMIZED file...])
# One GoogleTest program of the suite and its tests, as every tests/*/CMakeLists.txt adds them:
# - tests/support on the include path (the shared helpers), GTest::gtest_main linked with LIBRARIES;
# - APCI_SOURCE_DIR, the source tree, defined;
# - for each program it RUNS as a child (apcictl, rwmos-emu, ...), that program built first and
#   its path defined as <NAME>_PATH (apcictl: APCICTL_PATH, rwmos-emu: RWMOS_EMU_PATH);
# - run (its tests discovered and each test run) under EMULATOR where one is given, e.g.
#   umockdev-wrapper for the emulated USB board (tests/support/CMakeLists.txt);
# - its tests discovered as PREFIX<suite>.<test> with PROPERTIES (TIMEOUT, LABELS, ...); THREADED
#   ones through apci_threaded_gtest (cmake/sanitizers.cmake), so the TSan stage runs them.
#
# APCI_TEST_COMPILE_OPTIONS: options for the test programs' own sources only (not for the
# libraries they test, nor tests/support), after the build type's: the sanitizer stages pass
# -O0, which halves what compiling a test program costs under ASan/TSan (scripts/ci/sanitizers.sh),
# and ./test.sh -O1 (scripts/deps.sh, apci_build), while the code under test keeps the build
# type's optimisation (docs/hardening.md). The sources a program names OPTIMIZED are left out:
# those whose own code computes the references (brute-force sampling, property sweeps over
# thousands of cases), which at -O0 under ASan would run for minutes.
set(APCI_TEST_COMPILE_OPTIONS "" CACHE STRING
    "Compile options of the test programs' own sources, e.g. -O0 (empty: the build type's)")
function(apci_test_program name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "THREADED" "PREFIX;DISCOVERY_TIMEOUT;EMULATOR"
                        "SOURCES;LIBRARIES;RUNS;DEFINITIONS;INCLUDES;PROPERTIES;OPTIMIZED")
  if(arg_UNPARSED_ARGUMENTS OR NOT arg_SOURCES)
    message(FATAL_ERROR "apci_test_program(${name}): SOURCES needed; not understood: "
                        "${arg_UNPARSED_ARGUMENTS}")
  endif()
  foreach(source IN LISTS arg_OPTIMIZED)
    if(NOT source IN_LIST arg_SOURCES)
      message(FATAL_ERROR "apci_test_program(${name}): OPTIMIZED ${source} is not in SOURCES")
    endif()
  endforeach()
  add_executable(${name} ${arg_SOURCES})
  if(APCI_TEST_COMPILE_OPTIONS)
    set(reduced ${arg_SOURCES})
    list(REMOVE_ITEM reduced ${arg_OPTIMIZED})
    set_property(SOURCE ${reduced} APPEND PROPERTY COMPILE_OPTIONS ${APCI_TEST_COMPILE_OPTIONS})
  endif()
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support ${arg_INCLUDES})
  target_link_libraries(${name} PRIVATE ${arg_LIBRARIES} GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE APCI_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                             ${arg_DEFINITIONS})
  foreach(program IN LISTS arg_RUNS)
    string(TOUPPER "${program}" macro)
    string(REPLACE "-" "_" macro "${macro}")
    target_compile_definitions(${name} PRIVATE ${macro}_PATH="$<TARGET_FILE:${program}>")
    add_dependencies(${name} ${program})
  endforeach()
  if(arg_EMULATOR)
    set_target_properties(${name} PROPERTIES CROSSCOMPILING_EMULATOR ${arg_EMULATOR})
  endif()
  set(discover)
  if(DEFINED arg_PREFIX)
    list(APPEND discover TEST_PREFIX "${arg_PREFIX}")
  endif()
  if(DEFINED arg_DISCOVERY_TIMEOUT)
    list(APPEND discover DISCOVERY_TIMEOUT ${arg_DISCOVERY_TIMEOUT})
  endif()
  if(arg_PROPERTIES)
    list(APPEND discover PROPERTIES ${arg_PROPERTIES})
  endif()
  if(arg_THREADED)
    apci_threaded_gtest(${name} ${discover})
  else()
    gtest_discover_tests(${name} ${discover})
  endif()
endfunction()
