# SPDX-License-Identifier: MIT
# ctest python.ConfigureWithoutNumPyLeavesThePackageOut: a configure whose Python cannot import
# NumPy (here /bin/false as the interpreter) still succeeds, leaves the package out and says
# why and what to change; -DAPCI_BUILD_PYTHON=OFF leaves it out without a word. Configures
# SOURCE_DIR (no build) and reads the compile commands.
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... -P configure_without_python.cmake
function(configure out)
  set(dir ${WORK_DIR}/${out})
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${dir} ${ARGN}
      -DAPCI_BUILD_TESTS=OFF -DAPCI_BUILD_BENCH=OFF -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
    RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configure ${ARGN} failed (${rc}):\n${o}\n${e}")
  endif()
  file(READ ${dir}/compile_commands.json json)
  if(json MATCHES "python/src/module\\.cpp")
    message(FATAL_ERROR "configure ${ARGN}: the extension module is built anyway")
  endif()
  set(${out}_output "${o}${e}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
configure(no_numpy -DPython3_EXECUTABLE=/bin/false)
string(CONCAT expected "Python package apci: left out: no Python 3 interpreter that can import "
       "NumPy (tried: /bin/false); install python3-numpy or set -DPython3_EXECUTABLE=...")
string(FIND "${no_numpy_output}" "${expected}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "the configure output does not say why the package is left out:\n"
                      "${no_numpy_output}")
endif()
configure(off -DAPCI_BUILD_PYTHON=OFF)
if(off_output MATCHES "Python package apci")
  message(FATAL_ERROR "with APCI_BUILD_PYTHON=OFF the configure still speaks of the package:\n"
                      "${off_output}")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
message(STATUS "without NumPy: left out with the reason; with APCI_BUILD_PYTHON=OFF: left out")
