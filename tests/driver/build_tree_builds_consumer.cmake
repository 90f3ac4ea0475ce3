# SPDX-License-Identifier: MIT
# The build tree, uninstalled, is a package a consumer can build against
# (driver/driver.cmake): find_package(apci) with apci_DIR=BUILD_DIR
# (BUILD_DIR/apciConfig.cmake, apciTargets.cmake) and pkg-config apci with
# PKG_CONFIG_PATH=BUILD_DIR (BUILD_DIR/apci-uninstalled.pc). Builds and runs
# the consumer programs (tests/driver/consumer) both ways and the example
# examples/pcap_tc_init.c through pkg-config. Headers must come from the
# source tree and the library from the build tree.
#   cmake -DBUILD_DIR=... -DWORK_DIR=... -DSOURCE_DIR=tests/driver/consumer
#         -DPROJECT_SOURCE_DIR=... -P build_tree_builds_consumer.cmake
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
function(expect_output pattern what)
  if(NOT last_output MATCHES "${pattern}")
    message(FATAL_ERROR "${what} printed '${last_output}', expected '${pattern}'")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
foreach(f apciConfig.cmake apciConfigVersion.cmake apciTargets.cmake apci-uninstalled.pc)
  if(NOT EXISTS ${BUILD_DIR}/${f})
    message(FATAL_ERROR "the build tree has no ${f}")
  endif()
endforeach()

# ---- find_package(apci) with apci_DIR=BUILD_DIR; nothing else to find it by.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/consumer -Dapci_DIR=${BUILD_DIR}
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_BUILD_TYPE=Release)
file(STRINGS ${WORK_DIR}/consumer/CMakeCache.txt apci_dir REGEX "^apci_DIR:")
string(REGEX REPLACE "^apci_DIR:[A-Z]+=" "" apci_dir "${apci_dir}")
if(NOT apci_dir STREQUAL BUILD_DIR)
  message(FATAL_ERROR "the consumer found apci at '${apci_dir}', not in ${BUILD_DIR}")
endif()
run(${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
# The imported target's library is the build tree's, reached through the build RPATH.
run(${WORK_DIR}/consumer/consumer_c)
expect_output("TcPlane 17 \\(Ok\\)" "find_package consumer (C)")
run(${WORK_DIR}/consumer/consumer_cpp)
expect_output("TcPlane 17 \\(Ok\\)" "find_package consumer (C++)")

# ---- pkg-config apci with PKG_CONFIG_PATH=BUILD_DIR: apci-uninstalled.pc.
find_program(PKG_CONFIG pkg-config REQUIRED)
find_program(CC NAMES cc gcc REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${BUILD_DIR})
unset(ENV{PKG_CONFIG_LIBDIR})
unset(ENV{PKG_CONFIG_DISABLE_UNINSTALLED})
run(${PKG_CONFIG} --cflags apci)
string(STRIP "${last_output}" cflags)
if(NOT cflags STREQUAL "-I${PROJECT_SOURCE_DIR}/driver/include")
  message(FATAL_ERROR "pkg-config --cflags apci gave '${cflags}', expected the source tree's "
                      "-I${PROJECT_SOURCE_DIR}/driver/include")
endif()
run(${PKG_CONFIG} --variable=libdir apci)
string(STRIP "${last_output}" libdir)
if(NOT EXISTS ${libdir}/libapci.so OR NOT IS_DIRECTORY ${libdir})
  message(FATAL_ERROR "pkg-config's libdir '${libdir}' holds no libapci.so")
endif()
file(REAL_PATH ${libdir} libdir_real)
file(REAL_PATH ${BUILD_DIR} build_real)
string(FIND "${libdir_real}/" "${build_real}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "pkg-config's libdir '${libdir}' is not in the build tree ${BUILD_DIR}")
endif()
run(${PKG_CONFIG} --cflags --libs apci)
string(STRIP "${last_output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${CC} -std=c11 -Wall -Wextra -Werror ${SOURCE_DIR}/consumer.c ${flags} -o ${WORK_DIR}/consumer_pc)
run(${CC} -std=c11 -Wall -Wextra -Werror -pedantic ${PROJECT_SOURCE_DIR}/examples/pcap_tc_init.c
  ${flags} -o ${WORK_DIR}/pcap_tc_init_pc)
set(ENV{LD_LIBRARY_PATH} ${libdir})
run(${WORK_DIR}/consumer_pc)
expect_output("TcPlane 17 \\(Ok\\)" "pkg-config consumer")
run(${WORK_DIR}/pcap_tc_init_pc)
expect_output("compensation on: tool" "pkg-config pcap_tc_init")
unset(ENV{LD_LIBRARY_PATH})
message(STATUS "the build tree builds consumers through find_package and pkg-config")
