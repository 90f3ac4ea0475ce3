# SPDX-License-Identifier: MIT
# `cmake --install BUILD_DIR --prefix TMP` (DESTDIR unset) writes nothing
# outside TMP: every file it writes is listed, and any outside TMP fails the
# test. Run as root, the install runs as user nobody (setpriv), so it also
# shows that installing needs no root; either way install_manifest.txt lists
# every file written. Then the installed tree: the udev rule (alone where udev
# reads rules; the opt-in raw-BAR rule elsewhere), the systemd units, the shell
# completion where bash-completion and zsh look, the documentation and the man
# pages are there, and every reference the man pages (DOCUMENTATION, SEE ALSO)
# and the unit (Documentation=) make names an installed file.
#   cmake -DBUILD_DIR=... -DWORK_DIR=... -DCONFIGURED_PREFIX=${CMAKE_INSTALL_PREFIX}
#         -DDOCDIR=${CMAKE_INSTALL_DOCDIR} -DMANDIR=${CMAKE_INSTALL_MANDIR}
#         -DDATADIR=${CMAKE_INSTALL_DATADIR}
#         -DUDEV_RULES_DESTINATION=... -DSYSTEMD_USER_UNIT_DESTINATION=... (relative)
#         -P install_stays_in_prefix.cmake
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(manifest ${BUILD_DIR}/install_manifest.txt)
file(REMOVE ${manifest})
unset(ENV{DESTDIR})

execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
find_program(SETPRIV setpriv)
if(uid STREQUAL "0" AND SETPRIV)
  # nobody may write the prefix's parent and the manifest, nothing else of ours.
  file(CHMOD ${WORK_DIR} PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_WRITE
    GROUP_EXECUTE WORLD_READ WORLD_WRITE WORLD_EXECUTE)
  file(TOUCH ${manifest})
  file(CHMOD ${manifest} PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ GROUP_WRITE WORLD_READ
    WORLD_WRITE)
  set(as_user ${SETPRIV} --reuid=65534 --regid=65534 --clear-groups env HOME=${WORK_DIR})
  message(STATUS "installing as user nobody (uid 65534)")
else()
  set(as_user "")
  message(STATUS "installing as uid ${uid}")
endif()
execute_process(COMMAND ${as_user} ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(EXISTS ${manifest})
  file(CHMOD ${manifest} PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD_DIR} --prefix ${prefix} failed (${rc}):\n${out}\n${err}")
endif()

# Every file written, and none outside the prefix.
file(STRINGS ${manifest} written)
list(LENGTH written n)
if(n EQUAL 0)
  message(FATAL_ERROR "the install wrote nothing (${manifest} is empty)")
endif()
set(outside "")
foreach(f IN LISTS written)
  message(STATUS "written: ${f}")
  string(FIND "${f}" "${prefix}/" at)
  if(NOT at EQUAL 0)
    list(APPEND outside "${f}")
  elseif(NOT EXISTS "${f}" AND NOT IS_SYMLINK "${f}")
    message(FATAL_ERROR "listed as installed but not there: ${f}")
  endif()
endforeach()
if(outside)
  list(JOIN outside "\n  " outside)
  message(FATAL_ERROR "the install wrote outside the prefix ${prefix}:\n  ${outside}")
endif()
# Nothing in the prefix that the manifest does not list.
file(GLOB_RECURSE found LIST_DIRECTORIES false ${prefix}/*)
list(LENGTH found n_found)
if(NOT n_found EQUAL n)
  message(FATAL_ERROR "the prefix holds ${n_found} files, the manifest lists ${n}")
endif()
message(STATUS "${n} files written, all under ${prefix}")

# What must be there.
foreach(f
    ${UDEV_RULES_DESTINATION}/60-apci8001.rules
    ${DATADIR}/apci8001/udev/61-apci8001-raw-bar.rules
    ${SYSTEMD_USER_UNIT_DESTINATION}/rwmos-emu.service
    ${SYSTEMD_USER_UNIT_DESTINATION}/rwmos-emu.socket
    ${DATADIR}/bash-completion/completions/apcictl
    ${DATADIR}/bash-completion/completions/rwmos-emu
    ${DATADIR}/zsh/vendor-completions/_apcictl
    ${DATADIR}/zsh/vendor-completions/_rwmos-emu
    ${MANDIR}/man1/apcictl.1
    ${MANDIR}/man1/rwmos-emu.1
    ${DOCDIR}/README.md
    ${DOCDIR}/rwmos-emu.md
    ${DOCDIR}/apcictl.md
    ${DOCDIR}/figures/otc-modes.svg
    ${DOCDIR}/examples/pcap_tc_init.c
    ${DOCDIR}/examples/wr_quad_disc.nc)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
# Where udev reads rules, only the rules for USB boards: the raw-BAR grant is opt-in
# (docs/transports.md, "Permissions for real boards").
file(GLOB rules RELATIVE ${prefix}/${UDEV_RULES_DESTINATION} ${prefix}/${UDEV_RULES_DESTINATION}/*)
if(NOT rules STREQUAL "60-apci8001.rules")
  message(FATAL_ERROR "installed where udev reads rules: ${rules} (only 60-apci8001.rules)")
endif()
if(EXISTS ${prefix}/${DOCDIR}/examples/CMakeLists.txt)
  message(FATAL_ERROR "the examples' build rules were installed with them")
endif()

# A path in an installed file names the configured prefix; in this install it is under TMP.
function(expect_installed path what)
  string(FIND "${path}" "${CONFIGURED_PREFIX}/" at)
  if(NOT at EQUAL 0)
    message(FATAL_ERROR "${what} names ${path}, which is not under the prefix ${CONFIGURED_PREFIX}")
  endif()
  string(LENGTH "${CONFIGURED_PREFIX}/" skip)
  string(SUBSTRING "${path}" ${skip} -1 rest)
  if(NOT EXISTS ${prefix}/${rest})
    message(FATAL_ERROR "${what} names ${path}, which is not installed (${prefix}/${rest})")
  endif()
endfunction()
function(expect_man_page name section what)
  if(NOT EXISTS ${prefix}/${MANDIR}/man${section}/${name}.${section})
    message(FATAL_ERROR "${what} names ${name}(${section}), which is not installed")
  endif()
endfunction()

file(GLOB pages ${prefix}/${MANDIR}/man1/*.1)
foreach(page IN LISTS pages)
  get_filename_component(page_name ${page} NAME)
  file(READ ${page} text)
  string(REPLACE "\\-" "-" text "${text}")
  string(REPLACE "\\:" "" text "${text}")  # a path's break points (cmake/manpage.lua)
  # The pages of docs/ it names (written from docs/, cmake/manpages.cmake) are installed.
  string(REGEX MATCHALL "${CONFIGURED_PREFIX}/[^ \n\\)\"]*\\.md" docs "${text}")
  if(NOT docs)
    message(FATAL_ERROR "${page_name} names no installed documentation page")
  endif()
  list(REMOVE_DUPLICATES docs)
  foreach(doc IN LISTS docs)
    expect_installed("${doc}" "${page_name}")
  endforeach()
  string(FIND "${text}" "\n.SH SEE ALSO\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${page_name} has no SEE ALSO section")
  endif()
  string(SUBSTRING "${text}" ${at} -1 see_also)
  string(REGEX REPLACE "^\n\\.SH SEE ALSO\n" "" see_also "${see_also}")
  string(REGEX REPLACE "\n\\.SH .*" "" see_also "${see_also}")
  set(CMAKE_MATCH_1 "${see_also}")
  string(REGEX MATCHALL "[a-z0-9_-]+\\([0-9]\\)" refs "${CMAKE_MATCH_1}")
  if(NOT refs)
    message(FATAL_ERROR "${page_name}: SEE ALSO names no page")
  endif()
  foreach(ref IN LISTS refs)
    string(REGEX REPLACE "^(.*)\\(([0-9])\\)$" "\\1;\\2" name_section "${ref}")
    expect_man_page(${name_section} "${page_name} (SEE ALSO)")
  endforeach()
  message(STATUS "${page_name}: its documentation pages and SEE ALSO name installed files")
endforeach()

file(STRINGS ${prefix}/${SYSTEMD_USER_UNIT_DESTINATION}/rwmos-emu.service docs REGEX "^Documentation=")
if(NOT docs)
  message(FATAL_ERROR "rwmos-emu.service has no Documentation=")
endif()
foreach(line IN LISTS docs)
  string(REGEX REPLACE "^Documentation=" "" uris "${line}")
  separate_arguments(uris UNIX_COMMAND "${uris}")
  foreach(uri IN LISTS uris)
    if(uri MATCHES "^man:([a-z0-9_-]+)\\(([0-9])\\)$")
      expect_man_page(${CMAKE_MATCH_1} ${CMAKE_MATCH_2} "rwmos-emu.service (Documentation=)")
    elseif(uri MATCHES "^file://(/.*)$")
      expect_installed("${CMAKE_MATCH_1}" "rwmos-emu.service (Documentation=)")
    else()
      message(FATAL_ERROR "rwmos-emu.service: Documentation=${uri} is neither man: nor file:")
    endif()
  endforeach()
endforeach()
message(STATUS "rwmos-emu.service: Documentation= names installed files")
