# SPDX-License-Identifier: MIT
# apci_library(NAME ALIAS SOURCE...): one of the project's static libraries, its public headers
# in include/ beside the calling CMakeLists.txt, C++20, also known as ALIAS (apci::nc,
# rwmos::otc, ...). What it links is the caller's to say (target_link_libraries).
function(apci_library name alias)
  add_library(${name} STATIC ${ARGN})
  add_library(${alias} ALIAS ${name})
  target_include_directories(${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${name} PUBLIC cxx_std_20)
endfunction()
