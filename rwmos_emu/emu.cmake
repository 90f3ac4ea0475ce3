# SPDX-License-Identifier: MIT
# rwmos_emu: the emulated board (state, modules, object dictionary) and the
# frame server every transport's emulator side uses.
add_library(rwmos_emu STATIC
  ${CMAKE_CURRENT_LIST_DIR}/src/board.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/board_module.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/tc_state.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/tc_module.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/comp3d_state.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/comp3d_module.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/frame_server.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/motion_claim.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/motion_layer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/board_motion.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/motion_wire.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/otc_engine.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/otc_module.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/tempcomp_engine.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/tempcomp_module.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/frame_stream.cpp)
add_library(apci::rwmos_emu ALIAS rwmos_emu)
target_include_directories(rwmos_emu PUBLIC
  $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_link_libraries(rwmos_emu PUBLIC objif rwmos_motion rwmos_comp3d rwmos_otc rwmos_tempcomp)
