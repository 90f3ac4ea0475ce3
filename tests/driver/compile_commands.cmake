# SPDX-License-Identifier: MIT
# apci_compile_commands(DIR JSON_VAR option...): configures SOURCE_DIR into DIR with the options
# (no build) and sets JSON_VAR to its compile_commands.json; a failed configure fails the
# calling test with its output. Included by the build.* tests that read compile commands.
function(apci_compile_commands dir json_var)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${dir} ${ARGN}
      -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
    RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configure ${ARGN} failed (${rc}):\n${o}\n${e}")
  endif()
  file(READ ${dir}/compile_commands.json json)
  set(${json_var} "${json}" PARENT_SCOPE)
endfunction()
