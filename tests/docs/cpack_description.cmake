# SPDX-License-Identifier: MIT
# CPACK_PACKAGE_DESCRIPTION of the configured CPackConfig.cmake (cmake/packaging.cmake) has no
# ';': set() of several strings would have joined them with one at the start of each line.
include(${CONFIG})
if(NOT CPACK_PACKAGE_DESCRIPTION)
  message(FATAL_ERROR "${CONFIG} sets no CPACK_PACKAGE_DESCRIPTION")
endif()
string(FIND "${CPACK_PACKAGE_DESCRIPTION}" ";" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "CPACK_PACKAGE_DESCRIPTION holds a ';':\n${CPACK_PACKAGE_DESCRIPTION}")
endif()
