# SPDX-License-Identifier: MIT
# One package of everything the install rules install (libapci with its
# headers, pkg-config file and CMake package, apcictl, rwmos-emu, their man
# pages, the udev rule, the systemd unit), built by `cpack` in a build
# configured with -DCMAKE_INSTALL_PREFIX=/usr: for distributions other than
# Debian. On Debian the packages are built from debian/ (docs/packaging.md),
# and scripts/ci/package.sh checks those, not this one.
set(CPACK_PACKAGE_NAME apci8001)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "The APCI-8001 driver developers")
# The same placeholder address as debian/control (docs/packaging.md, "Maintainer").
set(CPACK_PACKAGE_CONTACT "APCI-8001 driver developers <apci8001@maintainers.invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "APCI-8001/8008 userspace driver (libapci), RWMOS emulator and tools")
# One string: set() with several would join them with ';', which would start the lines.
string(CONCAT CPACK_PACKAGE_DESCRIPTION
  "libapci drives ADDI-DATA APCI-8001/8008 motion-control boards through the universal object\n"
  "interface, over PCI, USB, or an emulator of the RWMOS.ELF firmware (embedded, or the\n"
  "rwmos-emu daemon). apcictl reads, writes and inspects board objects and runs scripts.")
set(CPACK_RESOURCE_FILE_README ${PROJECT_SOURCE_DIR}/README.md)
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
set(CPACK_STRIP_FILES OFF)

set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # apci8001_0.2.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION devel)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Run-time dependencies from the linked libraries (dpkg-shlibdeps).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
# The maintainer scripts: reload udev rules, ldconfig.
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
  ${PROJECT_SOURCE_DIR}/packaging/debian/postinst
  ${PROJECT_SOURCE_DIR}/packaging/debian/postrm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)

include(CPack)
