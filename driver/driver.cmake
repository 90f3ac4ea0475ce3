# SPDX-License-Identifier: MIT
# libapci: the userspace driver. The whole public API is include/apci/apci.h
# (C) plus the header-only C++ wrapper include/apci/apci.hpp.
add_library(apci SHARED
  src/apci.cpp
  src/apci_link.cpp
  src/apci_motion.cpp
  src/tc_names.cpp
  src/transport.cpp
  src/frame_transport.cpp
  src/mailbox_link.cpp
  src/mapped_file.cpp
  src/transport_inproc.cpp
  src/transport_unix.cpp
  src/transport_shm.cpp
  src/transport_pci.cpp)
add_library(apci::apci ALIAS apci)
set_target_properties(apci PROPERTIES
  VERSION ${PROJECT_VERSION}
  SOVERSION 0
  C_VISIBILITY_PRESET hidden
  CXX_VISIBILITY_PRESET hidden
  VISIBILITY_INLINES_HIDDEN ON
  LINK_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/apci.map)
target_compile_definitions(apci PRIVATE APCI_BUILDING_LIBRARY)
target_include_directories(apci
  PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
  PRIVATE src)
target_link_libraries(apci PRIVATE rwmos_emu objif fmt::fmt)
if(TARGET PkgConfig::LIBUSB)
  target_sources(apci PRIVATE src/transport_usb.cpp)
  target_compile_definitions(apci PRIVATE APCI_HAVE_LIBUSB)
  target_link_libraries(apci PRIVATE PkgConfig::LIBUSB)
else()
  message(STATUS "libapci: libusb-1.0 not found, the usb: transport is left out")
endif()
target_link_options(apci PRIVATE -Wl,--version-script=${CMAKE_CURRENT_SOURCE_DIR}/apci.map)
# clang's sanitizer runtimes live in the executable, not in shared libraries.
if(NOT APCI_SANITIZER_RUNTIME_IN_EXECUTABLE)
  target_link_options(apci PRIVATE -Wl,--no-undefined)
endif()

# ---- install: library, headers, CMake package, pkg-config file
include(CMakePackageConfigHelpers)
set(APCI_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/apci)
install(TARGETS apci EXPORT apciTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES include/apci/apci.h include/apci/apci.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/apci)
install(EXPORT apciTargets NAMESPACE apci:: DESTINATION ${APCI_CMAKE_DIR})
# The files to install are written to driver/install/, so that no file of the
# build tree's top looks like a package that is not one.
set(APCI_INSTALL_FILES ${CMAKE_CURRENT_BINARY_DIR}/install)
configure_package_config_file(apciConfig.cmake.in
  ${APCI_INSTALL_FILES}/apciConfig.cmake
  INSTALL_DESTINATION ${APCI_CMAKE_DIR})
# 0.x: a minor version may break the API, so only the same minor is compatible.
write_basic_package_version_file(${APCI_INSTALL_FILES}/apciConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES
  ${APCI_INSTALL_FILES}/apciConfig.cmake
  ${APCI_INSTALL_FILES}/apciConfigVersion.cmake
  DESTINATION ${APCI_CMAKE_DIR})
# apci.pc finds its prefix relative to its own directory (pkg-config's
# ${pcfiledir}), so the installed tree can be moved (cmake --install --prefix).
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}" OR IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(APCI_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH APCI_PC_UP "/p/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/p")
  set(APCI_PC_PREFIX "\${pcfiledir}/${APCI_PC_UP}")
endif()
configure_file(apci.pc.in ${APCI_INSTALL_FILES}/apci.pc @ONLY)
install(FILES ${APCI_INSTALL_FILES}/apci.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# ---- the build tree as a package, for consumers that build against it uninstalled:
#   cmake -Dapci_DIR=BUILD ...            (find_package(apci): BUILD/apciConfig.cmake)
#   PKG_CONFIG_PATH=BUILD pkg-config apci (BUILD/apci-uninstalled.pc, which pkg-config
#                                          prefers to apci.pc, its convention)
# Headers from the source tree, the library from the build tree.
export(EXPORT apciTargets NAMESPACE apci:: FILE ${CMAKE_BINARY_DIR}/apciTargets.cmake)
configure_package_config_file(apciConfig.cmake.in ${CMAKE_BINARY_DIR}/apciConfig.cmake
  INSTALL_DESTINATION ${CMAKE_BINARY_DIR} INSTALL_PREFIX ${CMAKE_BINARY_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/apciConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
configure_file(apci-uninstalled.pc.in ${CMAKE_CURRENT_BINARY_DIR}/apci-uninstalled.pc.genex @ONLY)
file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/apci-uninstalled.pc
  INPUT ${CMAKE_CURRENT_BINARY_DIR}/apci-uninstalled.pc.genex)
