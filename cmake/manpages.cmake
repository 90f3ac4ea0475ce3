# SPDX-License-Identifier: MIT
# apci_add_manpage(TARGET [SEE_ALSO text] [DOCS docs/NAME.md]): generates
# man/man1/TARGET.1 in the build tree from the program's own --help at build
# time (cmake/manpage.cmake) and installs it to share/man/man1, so the page
# never drifts from the program. DOCS names a page of docs/, which is
# installed to CMAKE_INSTALL_DOCDIR (cmake/docs.cmake): the man page points at
# the installed copy, and a DOCS that does not exist fails the configure.
# SEE_ALSO names other man pages of this project (installed with it).
set(APCI_MANPAGE_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/manpage.cmake)

function(apci_add_manpage target)
  cmake_parse_arguments(M "" "SEE_ALSO;DOCS" "" ${ARGN})
  set(installed_doc "")
  if(M_DOCS)
    if(NOT EXISTS ${PROJECT_SOURCE_DIR}/${M_DOCS} OR NOT M_DOCS MATCHES "^docs/[^/]+\\.md$")
      message(FATAL_ERROR "apci_add_manpage(${target}): DOCS ${M_DOCS} is not a page of docs/")
    endif()
    get_filename_component(doc_name ${M_DOCS} NAME)
    set(installed_doc ${CMAKE_INSTALL_FULL_DOCDIR}/${doc_name})
  endif()
  set(page ${CMAKE_BINARY_DIR}/man/man1/${target}.1)
  add_custom_command(OUTPUT ${page}
    COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${target}> -DNAME=${target}
            -DOUTPUT=${page} -DVERSION=${PROJECT_VERSION}
            -DSEE_ALSO=${M_SEE_ALSO} -DDOCS=${installed_doc} -P ${APCI_MANPAGE_SCRIPT}
    DEPENDS ${target} ${APCI_MANPAGE_SCRIPT}
    COMMENT "Generating man page ${target}.1"
    VERBATIM)
  add_custom_target(${target}_manpage ALL DEPENDS ${page})
  set_property(TARGET ${target} PROPERTY APCI_MANPAGE ${page})
  install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endfunction()
