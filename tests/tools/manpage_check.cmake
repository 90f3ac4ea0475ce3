# SPDX-License-Identifier: MIT
# Checks a man page written from its page of docs/ (cmake/manpages.cmake) against its program:
# the sections man-pages(7) asks for, in its order (NAME, SYNOPSIS, DESCRIPTION, ..., EXIT
# STATUS, ENVIRONMENT, FILES, EXAMPLES, SEE ALSO), an entry for every subcommand the
# program's --help lists, each environment variable in ENV named in ENVIRONMENT, no path
# relative to docs/ (the installed pages instead), and groff renders it without a single warning
# and without a hyphenated word.
#   cmake -DPROGRAM=... -DPAGE=... -DDOCDIR=... [-DENV="A;B"] -P manpage_check.cmake
cmake_minimum_required(VERSION 3.25)
if(NOT EXISTS "${PAGE}")
  message(FATAL_ERROR "man page ${PAGE} was not generated")
endif()
file(READ "${PAGE}" page)
# The break points after each "/" of a path (\:, cmake/manpage.lua) print nothing.
string(REPLACE "\\:" "" page "${page}")
set(last -1)
foreach(section "NAME" "SYNOPSIS" "DESCRIPTION" "EXIT STATUS" "ENVIRONMENT" "FILES" "EXAMPLES"
                "SEE ALSO")
  string(FIND "${page}" ".SH ${section}\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${PAGE}: no '${section}' section")
  endif()
  if(at LESS last)
    message(FATAL_ERROR "${PAGE}: '${section}' is not in man-pages(7)'s order")
  endif()
  set(last ${at})
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
    if(name STREQUAL "help")
      continue()  # `help COMMAND` is described with --help, not as a command of its own
    endif()
    string(REPLACE "-" "\\-" troff_name "${name}")
    # "### read" or "### spool, direct, ssf, step (motion)": a subsection naming the command.
    if(NOT page MATCHES "\n\\.SS [^\n]*${troff_name}")
      message(FATAL_ERROR "${PAGE}: no entry for the command '${name}'")
    endif()
  endforeach()
endif()

# Each variable of ENV is named in the ENVIRONMENT section itself (not only elsewhere).
string(FIND "${page}" ".SH ENVIRONMENT\n" env_at)
string(SUBSTRING "${page}" ${env_at} -1 environment)
string(FIND "${environment}" "\n.SH " env_end)
string(SUBSTRING "${environment}" 0 ${env_end} environment)
foreach(variable IN LISTS ENV)
  string(FIND "${environment}" "${variable}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${PAGE}: the environment variable ${variable} is not named in its "
                        "ENVIRONMENT section")
  endif()
endforeach()
if(page MATCHES "[^/a-z]docs/[a-z0-9-]+\\.md")
  message(FATAL_ERROR "${PAGE} names a page relative to docs/ ('${CMAKE_MATCH_0}'); "
                      "the installed one is ${DOCDIR}/...")
endif()
string(REPLACE "-" "\\-" troff_docdir "${DOCDIR}")
string(FIND "${page}" "${troff_docdir}/" at)
string(FIND "${page}" "${DOCDIR}/" plain_at)
if(at EQUAL -1 AND plain_at EQUAL -1)
  message(FATAL_ERROR "${PAGE} does not point at the installed documentation ${DOCDIR}")
endif()

find_program(GROFF groff)
find_program(TBL tbl)
find_program(SED sed)
if(GROFF AND TBL AND SED)
  # tbl (groff 1.22.4) warns that a text block "will not fit on one page" when its height is
  # equal to the room left above the page's footer (`\n[.t]<=\n[3dn]`), a block that fits
  # exactly: whether one lands there depends on every line above it. The check is made strict
  # (`<`), so a block taller than the room still warns, one that fits does not.
  execute_process(COMMAND ${TBL} "${PAGE}"
    COMMAND ${SED} "s/^\\.if \\\\n\\[\\.t\\]<=\\\\n\\[3dn\\]/.if \\\\n[.t]<\\\\n[3dn]/"
    COMMAND ${GROFF} -man -ww -z -Tutf8
    ERROR_VARIABLE warnings RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR NOT warnings STREQUAL "")
    message(FATAL_ERROR "groff: ${PAGE} does not render cleanly:\n${warnings}")
  endif()
  # No word is hyphenated at a line end (groff marks such a break with U+2010), at man's
  # width and at a narrow terminal's: a path or an option is never split.
  foreach(width 80 60)
    execute_process(COMMAND ${TBL} "${PAGE}" COMMAND ${GROFF} -man -Tutf8 -P-bou -rLL=${width}n
      OUTPUT_VARIABLE text ERROR_QUIET)
    if(text MATCHES "([^\n]*)‐\n")
      message(FATAL_ERROR "${PAGE} hyphenates at a line end (${width} columns): "
                          "'${CMAKE_MATCH_1}‐'")
    endif()
  endforeach()
endif()
