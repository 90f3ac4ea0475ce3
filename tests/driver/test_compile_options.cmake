# SPDX-License-Identifier: MIT
# APCI_TEST_COMPILE_OPTIONS (cmake/test_programs.cmake) reaches the test programs' own sources
# and nothing else: not the libraries and tools under test, not tests/support, not the sources
# a program names OPTIMIZED; without it no file gets the option; and an OPTIMIZED source the
# program does not compile is a configure error naming it. Configures SOURCE_DIR twice (no
# build) and reads the compile commands, then a one-line project.
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... -P test_compile_options.cmake
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/compile_commands.cmake)
set(option -fno-apci-test-marker)  # never compiled: configure only
function(files_with out)
  apci_files_compiled_with(${WORK_DIR}/${out} ${option} with n ${ARGN}
    -DAPCI_BUILD_TESTS=ON -DAPCI_BUILD_BENCH=OFF -DAPCI_BUILD_PYTHON=OFF)
  set(${out}_total ${n} PARENT_SCOPE)
  set(${out} ${with} PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
files_with(none)
if(none)
  message(FATAL_ERROR "without APCI_TEST_COMPILE_OPTIONS, ${none} compile with ${option}")
endif()
files_with(marked -DAPCI_TEST_COMPILE_OPTIONS=${option})
list(LENGTH marked count)
# Most of the suite's sources are test programs' own.
if(count LESS 100)
  message(FATAL_ERROR "only ${count} of ${marked_total} files compile with ${option}: ${marked}")
endif()
foreach(file IN LISTS marked)
  if(NOT file MATCHES "^tests/")
    message(FATAL_ERROR "${file}, not a test program's source, compiles with ${option}")
  endif()
endforeach()
# A test program's source, each of another program; tests/support and what is tested; the
# sources named OPTIMIZED.
foreach(file tests/geometry/plane_test.cpp tests/tools/self_approach_rules_test.cpp
             tests/objif/frame_test.cpp)
  if(NOT file IN_LIST marked)
    message(FATAL_ERROR "${file} compiles without ${option}")
  endif()
endforeach()
foreach(file tests/support/stock_oracle.cpp geometry/src/element.cpp
             tools/runlib/src/self_approach.cpp tests/geometry/property_test.cpp
             tests/geometry/rounded_property_test.cpp tests/tools/plane_distance_test.cpp
             tests/tools/self_approach_hold_test.cpp tests/tools/stock_oracle_test.cpp)
  if(file IN_LIST marked)
    message(FATAL_ERROR "${file} compiles with ${option}")
  endif()
endforeach()

# A source named OPTIMIZED that the program does not compile is a configure error naming it.
set(project ${WORK_DIR}/optimized_not_a_source)
file(WRITE ${project}/CMakeLists.txt
  "cmake_minimum_required(VERSION 3.25)\n"
  "project(optimized_not_a_source NONE)\n"
  "include(${SOURCE_DIR}/cmake/test_programs.cmake)\n"
  "apci_test_program(probe_test SOURCES probe_test.cpp OPTIMIZED probe_tset.cpp)\n")
execute_process(COMMAND ${CMAKE_COMMAND} -S ${project} -B ${project}/build
  RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
if(rc EQUAL 0 OR NOT e MATCHES "apci_test_program\\(probe_test\\): OPTIMIZED probe_tset.cpp is not in SOURCES")
  message(FATAL_ERROR "an OPTIMIZED source not in SOURCES was not refused by name (${rc}):\n${o}\n${e}")
endif()
