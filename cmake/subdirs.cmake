# SPDX-License-Identifier: MIT
# apci_add_subdirectories(a b c): add_subdirectory() for each; a directory that is missing is a
# configure error, so no component leaves the build without a word.
function(apci_add_subdirectories)
  foreach(dir IN LISTS ARGN)
    add_subdirectory(${dir})
  endforeach()
endfunction()
