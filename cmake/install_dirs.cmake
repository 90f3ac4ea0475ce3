# SPDX-License-Identifier: MIT
# Where the udev rule and the systemd user unit are installed (udev/).
#
# Both go under the prefix by default, so `cmake --install build --prefix DIR`
# writes nothing outside DIR (test install.WritesNothingOutsideThePrefix). A
# package puts them where udev and systemd look by setting these two cache
# variables to absolute paths (docs/hardening.md, "Debian package"), e.g.
#   -DAPCI_UDEV_RULES_DIR=/usr/lib/udev/rules.d
#   -DAPCI_SYSTEMD_USER_UNIT_DIR=/usr/lib/systemd/user
# The defaults keep ${CMAKE_INSTALL_PREFIX} unexpanded, so they follow the
# prefix given at install time. A path under the prefix (a leading
# ${CMAKE_INSTALL_PREFIX}/, literal or as configured) or a relative path is
# installed relative to the prefix, as every other install destination is; any
# other absolute path is installed as it is (under DESTDIR, if set).
set(APCI_UDEV_RULES_DIR "\${CMAKE_INSTALL_PREFIX}/lib/udev/rules.d" CACHE STRING
  "Where the udev rule 60-apci8001.rules is installed (absolute, or under the prefix)")
set(APCI_SYSTEMD_USER_UNIT_DIR "\${CMAKE_INSTALL_PREFIX}/lib/systemd/user" CACHE STRING
  "Where the systemd user unit rwmos-emu.service is installed (absolute, or under the prefix)")

# apci_install_destination(VAR DIR): DIR as an install() destination, relative
# when DIR lies under the prefix.
function(apci_install_destination out dir)
  foreach(prefix "\${CMAKE_INSTALL_PREFIX}/" "${CMAKE_INSTALL_PREFIX}/")
    string(LENGTH "${prefix}" n)
    string(SUBSTRING "${dir}" 0 ${n} head)
    if(head STREQUAL prefix)
      string(SUBSTRING "${dir}" ${n} -1 dir)
      break()
    endif()
  endforeach()
  if(dir STREQUAL "" OR dir MATCHES "\\$")
    message(FATAL_ERROR "install directory '${dir}': give an absolute path, or one under the "
                        "prefix (\${CMAKE_INSTALL_PREFIX}/... or relative); no other variable is expanded")
  endif()
  set(${out} "${dir}" PARENT_SCOPE)
endfunction()

apci_install_destination(APCI_UDEV_RULES_DESTINATION "${APCI_UDEV_RULES_DIR}")
apci_install_destination(APCI_SYSTEMD_USER_UNIT_DESTINATION "${APCI_SYSTEMD_USER_UNIT_DIR}")
# Everything installs under the prefix unless one of them is set outside it.
if(IS_ABSOLUTE "${APCI_UDEV_RULES_DESTINATION}" OR IS_ABSOLUTE "${APCI_SYSTEMD_USER_UNIT_DESTINATION}")
  set(APCI_INSTALLS_OUTSIDE_PREFIX ON)
else()
  set(APCI_INSTALLS_OUTSIDE_PREFIX OFF)
endif()
