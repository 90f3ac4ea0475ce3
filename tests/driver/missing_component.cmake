# SPDX-License-Identifier: MIT
# A component directory that is gone is a configure error, never a build that silently lacks
# it (cmake/subdirs.cmake): a small project adds one directory that is there and one that is
# not with apci_add_subdirectories; the configure must fail and name the missing one, and
# succeed once both are there.
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... -P missing_component.cmake
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/project/present)
file(WRITE ${WORK_DIR}/project/present/CMakeLists.txt "set(APCI_PRESENT_ADDED ON PARENT_SCOPE)\n")
file(WRITE ${WORK_DIR}/project/CMakeLists.txt
  "cmake_minimum_required(VERSION 3.25)\n"
  "project(missing_component NONE)\n"
  "include(${SOURCE_DIR}/cmake/subdirs.cmake)\n"
  "apci_add_subdirectories(present gone)\n")

function(configure out)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK_DIR}/project -B ${WORK_DIR}/${out}
    RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  set(${out}_rc ${rc} PARENT_SCOPE)
  set(${out}_text "${o}${e}" PARENT_SCOPE)
endfunction()

configure(without)
if(without_rc EQUAL 0)
  message(FATAL_ERROR "a missing subdirectory configured without an error:\n${without_text}")
endif()
if(NOT without_text MATCHES "gone")
  message(FATAL_ERROR "the configure error does not name the missing directory:\n${without_text}")
endif()

file(MAKE_DIRECTORY ${WORK_DIR}/project/gone)
file(WRITE ${WORK_DIR}/project/gone/CMakeLists.txt "")
configure(with)
if(NOT with_rc EQUAL 0)
  message(FATAL_ERROR "with every directory there, the configure failed:\n${with_text}")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
