# SPDX-License-Identifier: MIT
# ctest python.installed: `cmake --install BUILD_DIR --prefix TMP` puts the package apci into
# TMP/PYTHON_INSTALL_DIR, and Python imports it from there (not from the build tree) and runs
# a program with it: the extension finds the installed libapci by its RPATH, relative to itself.
#   cmake -DBUILD_DIR=... -DWORK_DIR=... -DPYTHON=... -DPYTHON_INSTALL_DIR=... (relative)
#         -DPROGRAM=examples/wr_quad_disc.nc -DTOOLS=... -P installed_package_imports.cmake
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install --prefix ${prefix} failed (${rc}):\n${out}\n${err}")
endif()
set(package ${prefix}/${PYTHON_INSTALL_DIR}/apci)
foreach(f __init__.py _board.py _errors.py _run.py _status.py)
  if(NOT EXISTS ${package}/${f})
    message(FATAL_ERROR "${package}/${f} is not installed")
  endif()
endforeach()
file(GLOB extension ${package}/_apci*.so)
if(NOT extension)
  message(FATAL_ERROR "the extension _apci*.so is not installed in ${package}")
endif()

# Only the installed package: PYTHONPATH names the prefix, the build tree is not reachable.
set(check "
import pathlib, apci
where = pathlib.Path(apci.__file__).resolve()
assert where.is_relative_to(pathlib.Path('${prefix}').resolve()), where
r = apci.run('${PROGRAM}', tools='${TOOLS}', samples=False)
assert r.ok and r.blocks == 11 and len(r.segments) > 0, r.summary()
print('imported', where, 'ran', len(r.segments), 'segments')
")
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH PYTHONPATH=${prefix}/${PYTHON_INSTALL_DIR}
          ${PYTHON} -c "${check}"
  WORKING_DIRECTORY ${WORK_DIR}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed package does not import and run (${rc}):\n${out}\n${err}")
endif()
# The extension loads the installed libapci, not the build tree's.
execute_process(COMMAND ldd ${extension} OUTPUT_VARIABLE deps)
string(REGEX MATCH "libapci\\.so\\.[0-9]+ => ([^ ]*)" _ "${deps}")
if(NOT CMAKE_MATCH_1 MATCHES "^${prefix}/")
  message(FATAL_ERROR "the installed extension uses '${CMAKE_MATCH_1}', not the libapci "
                      "installed in ${prefix}:\n${deps}")
endif()
message(STATUS "${out}")
file(REMOVE_RECURSE ${WORK_DIR})
