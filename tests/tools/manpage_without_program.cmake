# SPDX-License-Identifier: MIT
# The man pages are written from the source alone: in a fresh build directory, building only
# the targets apcictl_manpage and rwmos-emu_manpage makes both pages and builds no program (a
# cross build, whose programs cannot run on the build machine, makes the same pages).
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... -P manpage_without_program.cmake
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -DAPCI_BUILD_TESTS=OFF
          -DAPCI_BUILD_BENCH=OFF -DAPCI_BUILD_PYTHON=OFF -DAPCI_BUILD_MANPAGES=ON
  OUTPUT_QUIET RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configure failed: ${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR} --target apcictl_manpage
                        rwmos-emu_manpage
  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the man pages failed:\n${out}\n${err}")
endif()
foreach(page apcictl rwmos-emu)
  if(NOT EXISTS ${WORK_DIR}/man/man1/${page}.1)
    message(FATAL_ERROR "${page}.1 was not written")
  endif()
endforeach()
file(GLOB built ${WORK_DIR}/bin/* ${WORK_DIR}/lib/*)
if(built)
  message(FATAL_ERROR "writing the man pages built programs or libraries: ${built}")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
