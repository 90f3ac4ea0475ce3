# SPDX-License-Identifier: MIT
# Builds the extension apci._apci with the project's CMake build for meson.build (the pip
# build, pyproject.toml) and copies it, with the libapci it loads (LIBRARY: its SONAME), to
# OUTPUT_DIR:
#   cmake -DSOURCE_DIR=checkout -DBUILD_DIR=dir -DOUTPUT_DIR=dir -DPYTHON=python
#         -DEXTENSION=_apci.cpython-311-x86_64-linux-gnu.so -DLIBRARY=libapci.so.1
#         -P build_extension.cmake
# Configured as ./test.sh configures (Release; ccache when installed; warnings as errors
# when $APCI_WERROR says so), without tests and benchmarks, for the interpreter that runs pip,
# with the extension's RPATH $ORIGIN (APCI_PYTHON_BUNDLE_LIBAPCI). BUILD_DIR is build-pip/ in
# the checkout, beside ./test.sh's build/: the same sources compiled with the same flags from
# the same depth hit ./test.sh's compiler cache (ccache, relative to the checkout), and a second
# pip install rebuilds only what changed. The copies are stripped of their debug information.
foreach(var SOURCE_DIR BUILD_DIR OUTPUT_DIR PYTHON EXTENSION LIBRARY)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "build_extension.cmake: ${var} is required")
  endif()
endforeach()

set(launcher "")
find_program(CCACHE ccache)
if(CCACHE)
  # Paths relative to the checkout in ccache's hash: a rebuild in another build directory hits.
  set(ENV{CCACHE_BASEDIR} "${SOURCE_DIR}")
  set(ENV{CCACHE_NOHASHDIR} "true")
  set(launcher -DCMAKE_C_COMPILER_LAUNCHER=${CCACHE} -DCMAKE_CXX_COMPILER_LAUNCHER=${CCACHE})
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BUILD_DIR}
          -DCMAKE_BUILD_TYPE=Release ${launcher}
          -DAPCI_BUILD_TESTS=OFF -DAPCI_BUILD_BENCH=OFF -DAPCI_BUILD_PYTHON=ON
          -DAPCI_PYTHON_BUNDLE_LIBAPCI=ON -DPython3_EXECUTABLE=${PYTHON}
  OUTPUT_QUIET
  COMMAND_ERROR_IS_FATAL ANY)
cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
execute_process(
  COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target apci_python --parallel ${cores}
  COMMAND_ERROR_IS_FATAL ANY)
if(NOT EXISTS ${BUILD_DIR}/python/apci/${EXTENSION})
  message(FATAL_ERROR "build_extension.cmake: the build made no ${BUILD_DIR}/python/apci/"
                      "${EXTENSION}: is ${PYTHON} the interpreter CMake built it for?")
endif()
file(COPY_FILE ${BUILD_DIR}/python/apci/${EXTENSION} ${OUTPUT_DIR}/${EXTENSION})
# The library itself under its SONAME (not the symlink).
if(NOT EXISTS ${BUILD_DIR}/lib/${LIBRARY})
  message(FATAL_ERROR "build_extension.cmake: the build made no ${BUILD_DIR}/lib/${LIBRARY}: "
                      "is LIBRARY the SONAME driver/driver.cmake sets?")
endif()
file(REAL_PATH ${BUILD_DIR}/lib/${LIBRARY} library)
file(COPY_FILE ${library} ${OUTPUT_DIR}/${LIBRARY})
find_program(STRIP strip)
if(STRIP)
  execute_process(COMMAND ${STRIP} --strip-debug ${OUTPUT_DIR}/${EXTENSION} ${OUTPUT_DIR}/${LIBRARY}
    COMMAND_ERROR_IS_FATAL ANY)
endif()
