# SPDX-License-Identifier: MIT
# apci_files_compiled_with(DIR FLAG FILES_VAR TOTAL_VAR option...): configures SOURCE_DIR into DIR
# with the options (no build) and reads its compile_commands.json: FILES_VAR is the list of the
# files (relative to SOURCE_DIR) whose command carries FLAG as a word of its own, TOTAL_VAR the
# number of files compiled. A failed configure fails the calling test with its output. Included
# by the build.* tests that read compile commands.
function(apci_files_compiled_with dir flag files_var total_var)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${dir} ${ARGN}
      -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
    RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configure ${ARGN} failed (${rc}):\n${o}\n${e}")
  endif()
  file(READ ${dir}/compile_commands.json json)
  string(JSON n LENGTH "${json}")
  set(with "")
  math(EXPR last "${n} - 1")
  foreach(i RANGE ${last})
    string(JSON command GET "${json}" ${i} command)
    if(command MATCHES " ${flag}( |$)")
      string(JSON file GET "${json}" ${i} file)
      file(RELATIVE_PATH file ${SOURCE_DIR} ${file})
      list(APPEND with ${file})
    endif()
  endforeach()
  set(${files_var} ${with} PARENT_SCOPE)
  set(${total_var} ${n} PARENT_SCOPE)
endfunction()
