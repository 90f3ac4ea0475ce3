# SPDX-License-Identifier: MIT
# add_optional_subdirectories(a b c): adds each child that has a CMakeLists.txt,
# so areas can land one at a time without editing a shared list.
function(add_optional_subdirectories)
  foreach(dir IN LISTS ARGN)
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/CMakeLists.txt)
      add_subdirectory(${dir})
    endif()
  endforeach()
endfunction()
