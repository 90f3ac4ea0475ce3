# SPDX-License-Identifier: MIT
# apci_add_manpage(TARGET DOCS docs/NAME.md SUMMARY text): the section-1 man page
# man/man1/TARGET.1, written by pandoc from the page of docs/ that documents the program
# (cmake/manpage.lua arranges it: NAME, SYNOPSIS, DESCRIPTION, the page's sections, EXIT
# STATUS, ENVIRONMENT, FILES, EXAMPLES, SEE ALSO; paths of docs/ become the installed pages in
# CMAKE_INSTALL_FULL_DOCDIR), installed to share/man/man1. It reads only the source: nothing
# that was built runs, so a cross build makes the same page. pandoc (Debian: pandoc) is found
# at configure time; without it the pages are left out, with a message, unless
# APCI_BUILD_MANPAGES=ON requires them (a package build does).
set(APCI_BUILD_MANPAGES AUTO CACHE STRING "Build the man pages with pandoc: AUTO, ON or OFF")
set_property(CACHE APCI_BUILD_MANPAGES PROPERTY STRINGS AUTO ON OFF)
set(APCI_MANPAGE_FILTER ${CMAKE_CURRENT_LIST_DIR}/manpage.lua)
if(NOT APCI_BUILD_MANPAGES STREQUAL "OFF")
  find_program(APCI_PANDOC pandoc)
  if(NOT APCI_PANDOC)
    if(APCI_BUILD_MANPAGES STREQUAL "ON")
      message(FATAL_ERROR "APCI_BUILD_MANPAGES=ON, but pandoc was not found (Debian: pandoc)")
    endif()
    message(STATUS "man pages: left out, pandoc was not found (Debian: pandoc)")
  endif()
endif()

function(apci_add_manpage target)
  cmake_parse_arguments(M "" "DOCS;SUMMARY" "" ${ARGN})
  if(NOT M_DOCS MATCHES "^docs/[^/]+\\.md$" OR NOT EXISTS ${PROJECT_SOURCE_DIR}/${M_DOCS})
    message(FATAL_ERROR "apci_add_manpage(${target}): DOCS ${M_DOCS} is not a page of docs/")
  endif()
  if(NOT M_SUMMARY)
    message(FATAL_ERROR "apci_add_manpage(${target}): SUMMARY is required")
  endif()
  if(APCI_BUILD_MANPAGES STREQUAL "OFF" OR NOT APCI_PANDOC)
    return()
  endif()
  string(TOUPPER "${target}" title)
  # The date of the page: the last change of its source would need git; the build's date
  # honours SOURCE_DATE_EPOCH (reproducible builds, as dpkg-buildpackage sets it).
  string(TIMESTAMP date "%Y-%m-%d" UTC)
  set(page ${CMAKE_BINARY_DIR}/man/man1/${target}.1)
  # Left-adjusted and never hyphenated (.nh): a path, an option or an object name broken at a
  # line end would be copied wrong. pandoc's man writer hyphenates unless the variable
  # hyphenate is empty (any text, "false" too, turns it on).
  add_custom_command(OUTPUT ${page}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/man/man1
    COMMAND ${APCI_PANDOC} --standalone --from=gfm --to=man
            --lua-filter=${APCI_MANPAGE_FILTER}
            -M title=${title} -M section=1 -M date=${date} -V adjusting=l -V hyphenate=
            -M "footer=apci8001 ${PROJECT_VERSION}" -M "header=User Commands"
            -M program=${target} -M "summary=${M_SUMMARY}"
            -M docdir=${CMAKE_INSTALL_FULL_DOCDIR}
            -o ${page} ${PROJECT_SOURCE_DIR}/${M_DOCS}
    DEPENDS ${PROJECT_SOURCE_DIR}/${M_DOCS} ${APCI_MANPAGE_FILTER}
    COMMENT "Writing man page ${target}.1 from ${M_DOCS}"
    VERBATIM)
  add_custom_target(${target}_manpage ALL DEPENDS ${page})
  set_property(TARGET ${target} PROPERTY APCI_MANPAGE ${page})
  install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endfunction()
