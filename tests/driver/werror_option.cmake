# SPDX-License-Identifier: MIT
# Warnings are errors only where we choose: a build configured without
# APCI_WERROR compiles without -Werror (a newer compiler's new warning does not
# break a user's or a package's build); -DAPCI_WERROR=ON, as CI configures,
# compiles every file with it. Configures SOURCE_DIR twice (no build) and reads
# the compile commands.
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... -P werror_option.cmake
include(${CMAKE_CURRENT_LIST_DIR}/compile_commands.cmake)
function(compile_commands out)
  apci_files_compiled_with(${WORK_DIR}/${out} -Werror with n ${ARGN}
    -DAPCI_BUILD_TESTS=OFF -DAPCI_BUILD_BENCH=OFF)
  if(n LESS 50)
    message(FATAL_ERROR "${out}: only ${n} compile commands")
  endif()
  list(LENGTH with count)
  set(${out}_total ${n} PARENT_SCOPE)
  set(${out}_werror ${count} PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
# The default, also where this test runs under CI (which exports APCI_WERROR=ON).
unset(ENV{APCI_WERROR})
compile_commands(default)
if(NOT default_werror EQUAL 0)
  message(FATAL_ERROR "without APCI_WERROR, ${default_werror} of ${default_total} files compile with -Werror")
endif()
compile_commands(ci -DAPCI_WERROR=ON)
if(NOT ci_werror EQUAL ci_total)
  message(FATAL_ERROR "with -DAPCI_WERROR=ON, only ${ci_werror} of ${ci_total} files compile with -Werror")
endif()
# The environment variable gives the default (.ci/run: every stage, the package stage too).
set(ENV{APCI_WERROR} ON)
compile_commands(env)
if(NOT env_werror EQUAL env_total)
  message(FATAL_ERROR "with APCI_WERROR=ON in the environment, only ${env_werror} of ${env_total} "
                      "files compile with -Werror")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
message(STATUS "-Werror: none of ${default_total} files by default, all ${ci_total} with "
               "-DAPCI_WERROR=ON, all ${env_total} with APCI_WERROR=ON in the environment")
