# SPDX-License-Identifier: MIT
# The documentation, installed to CMAKE_INSTALL_DOCDIR (share/doc/apci8001):
# README.md, LICENSE, the pages of docs/ with their figures (docs/NAME.md ->
# DOCDIR/NAME.md, the figures to DOCDIR/figures, where the pages' links find
# them) and the examples (DOCDIR/examples: C programs, NC programs, tool lists,
# PLC scripts). The man pages and the systemd unit point at these installed
# pages (cmake/manpages.cmake, udev/rwmos-emu.service.in).
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}
  FILES_MATCHING PATTERN "*.md" REGEX "/figures/[^/]+$")
# The examples as a user reads and copies them; their build rules stay behind.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples
  PATTERN "CMakeLists.txt" EXCLUDE PATTERN "*.cmake" EXCLUDE)
