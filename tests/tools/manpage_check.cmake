# SPDX-License-Identifier: MIT
# Checks a generated man page (cmake/manpage.cmake) against its program:
# NAME and SYNOPSIS present, a COMMANDS entry for every subcommand the
# program's --help lists, and groff renders it without a single warning.
#   cmake -DPROGRAM=... -DPAGE=... -P manpage_check.cmake
if(NOT EXISTS "${PAGE}")
  message(FATAL_ERROR "man page ${PAGE} was not generated")
endif()
file(READ "${PAGE}" page)
foreach(section ".SH NAME" ".SH SYNOPSIS" ".SH OPTIONS")
  string(FIND "${page}" "${section}\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${PAGE}: no '${section}' section")
  endif()
endforeach()

execute_process(COMMAND ${PROGRAM} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} --help failed")
endif()
string(FIND "${help}" "Subcommands:\n" at)
if(NOT at EQUAL -1)
  string(SUBSTRING "${help}" ${at} -1 block)
  string(REGEX MATCHALL "\n  [a-z][a-z0-9-]*" names "${block}")
  foreach(name IN LISTS names)
    string(STRIP "${name}" name)
    string(REPLACE "-" "\\-" troff_name "${name}")
    string(FIND "${page}" ".SS ${troff_name}\n" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${PAGE}: no COMMANDS entry for '${name}'")
    endif()
  endforeach()
endif()

find_program(GROFF groff)
if(GROFF)
  execute_process(COMMAND ${GROFF} -man -ww -z -Tutf8 "${PAGE}"
    ERROR_VARIABLE warnings RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR NOT warnings STREQUAL "")
    message(FATAL_ERROR "groff: ${PAGE} does not render cleanly:\n${warnings}")
  endif()
endif()
