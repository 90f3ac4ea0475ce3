# SPDX-License-Identifier: MIT
# C examples: plain C11 PCAP programs using only apci.h.
add_executable(pcap_tc_init pcap_tc_init.c)
set_target_properties(pcap_tc_init PROPERTIES C_STANDARD 11 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
target_compile_options(pcap_tc_init PRIVATE -pedantic)
target_link_libraries(pcap_tc_init PRIVATE apci::apci)
