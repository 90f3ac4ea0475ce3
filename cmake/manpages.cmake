# SPDX-License-Identifier: MIT
# apci_add_manpage(TARGET [SEE_ALSO text] [DOCS path]): generates TARGET.1
# from the program's own --help at build time (cmake/manpage.cmake) and
# installs it to share/man/man1, so the page never drifts from the program.
set(APCI_MANPAGE_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/manpage.cmake)

function(apci_add_manpage target)
  cmake_parse_arguments(M "" "SEE_ALSO;DOCS" "" ${ARGN})
  set(page ${CMAKE_BINARY_DIR}/man/${target}.1)
  add_custom_command(OUTPUT ${page}
    COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${target}> -DNAME=${target}
            -DOUTPUT=${page} -DVERSION=${PROJECT_VERSION}
            -DSEE_ALSO=${M_SEE_ALSO} -DDOCS=${M_DOCS} -P ${APCI_MANPAGE_SCRIPT}
    DEPENDS ${target} ${APCI_MANPAGE_SCRIPT}
    COMMENT "Generating man page ${target}.1"
    VERBATIM)
  add_custom_target(${target}_manpage ALL DEPENDS ${page})
  set_property(TARGET ${target} PROPERTY APCI_MANPAGE ${page})
  install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endfunction()
