# SPDX-License-Identifier: MIT
# libapci: the userspace driver. The whole public API is include/apci/apci.h
# (C) plus the header-only C++ wrapper include/apci/apci.hpp.
add_library(apci SHARED
  src/apci.cpp
  src/apci_link.cpp
  src/apci_motion.cpp
  src/apci_claim.cpp
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
# The SONAME libapci.so.N, N raised with every change of the C ABI; the Debian package libapciN
# (debian/), the pip build (meson.build) and the CI package stage read N here. The file itself
# is libapci.so.N.VERSION (1.0.2.0: SONAME 1, version 0.2.0), so that its name begins with the
# SONAME as ldconfig and packagers expect. docs/packaging.md, "New SONAME".
set(APCI_SOVERSION 1)
set_target_properties(apci PROPERTIES
  VERSION ${APCI_SOVERSION}.${PROJECT_VERSION}
  SOVERSION ${APCI_SOVERSION}
  C_VISIBILITY_PRESET hidden
  CXX_VISIBILITY_PRESET hidden
  VISIBILITY_INLINES_HIDDEN ON
  LINK_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/apci.map)
target_compile_definitions(apci PRIVATE APCI_BUILDING_LIBRARY)
# apci/apci.hpp needs C++17 (std::string_view, if constexpr): a C++ consumer of apci::apci gets
# at least that standard, found by find_package or from the build tree. (A C consumer is not
# affected: the requirement applies to C++ sources only.)
target_compile_features(apci INTERFACE cxx_std_17)
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
# apci.pc names the prefix it is installed to literally (prefix=/usr), as Debian's own .pc
# files do: pkg-config then recognises its system directories and leaves out -I/usr/include
# and -L/usr/lib/<triplet>, so `pkg-config --cflags --libs apci` is `-lapci` there, and no
# early -L can shadow a user's own. The prefix is the one of `cmake --install [--prefix DIR]`,
# filled in when installing (install(CODE) below), so a tree installed elsewhere names its own.
foreach(dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    set(APCI_PC_${dir} "${CMAKE_INSTALL_${dir}}")
  else()
    set(APCI_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()
set(APCI_PC_PREFIX "@APCI_PC_INSTALLED_PREFIX@")
configure_file(apci.pc.in ${APCI_INSTALL_FILES}/apci.pc.in @ONLY)
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(APCI_PC_DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
else()
  set(APCI_PC_DESTINATION "\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig")
endif()
# Written straight to its destination (under DESTDIR) and listed in install_manifest.txt, as
# install(FILES) does; the build tree is only read (an install may run as another user).
install(CODE "
  set(APCI_PC_INSTALLED_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")
  file(READ \"${APCI_INSTALL_FILES}/apci.pc.in\" apci_pc)
  string(CONFIGURE \"\${apci_pc}\" apci_pc @ONLY)
  set(apci_pc_file \"\$ENV{DESTDIR}${APCI_PC_DESTINATION}/apci.pc\")
  message(STATUS \"Installing: \${apci_pc_file}\")
  file(WRITE \"\${apci_pc_file}\" \"\${apci_pc}\")
  list(APPEND CMAKE_INSTALL_MANIFEST_FILES \"\${apci_pc_file}\")")

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
