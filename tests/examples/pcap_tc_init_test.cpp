// SPDX-License-Identifier: MIT
// examples/pcap_tc_init.c run as a process: the TC sequence of [APCI-TC]
// section 2.5 and the Clean rule, with the registers printed decoded.
#include <gtest/gtest.h>

#include "process.h"
#include "text.h"

namespace {

using test_support::contains;

TEST(PcapTcInit, ApciTcSection25SequenceRunsAndPrintsTheRegistersDecoded) {
    const auto r = test_support::run_process({PCAP_TC_INIT_PATH});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_EQ(r.err, "");
    const char* expected[] = {
        "group 1: RESET, plane XAxis 0, YAxis 1, ZAxis 2\n",
        "tool 1: RADIUS 2.5\n",
        "tool 2: RADIUS 5\n",
        "tool 7: RADIUS 0.8\n",
        "compensation on: tool 2, left\n  STATUS 0x01 Run=on ProfMarked=off\n  ERROR  0x00 none\n",
        "compensation off:\n  STATUS 0x00 Run=off ProfMarked=off\n",
        "after Clean, the old STATUS handle is refused: read int 1300/1/1/3: StaleHandle",
        "with the handle zeroed, STATUS reads again:\n  STATUS 0x00 Run=off ProfMarked=off\n",
        "done\n",
    };
    std::size_t from = 0;
    for (const char* line : expected) {
        const auto at = r.out.find(line, from);
        ASSERT_NE(at, std::string::npos) << "missing, in order: " << line << "\n---\n" << r.out;
        from = at;
    }
}

TEST(PcapTcInit, FailsWithTheFailedStepWhenTheBoardLacksOptionTc) {
    const auto r = test_support::run_process({PCAP_TC_INIT_PATH, "emu:?no-option-tc"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "pcap_tc_init: RESET failed: write int 1300/1/1/2 = 0: NoSuchDevice"))
        << r.err;
    EXPECT_TRUE(contains(r.out, "FAILED")) << r.out;
}

TEST(PcapTcInit, FailsOnAnUnreachableDevice) {
    const auto r = test_support::run_process({PCAP_TC_INIT_PATH, "unix:/nonexistent/apci8001.sock"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "open failed: open 'unix:/nonexistent/apci8001.sock': TransportError")) << r.err;
}

}  // namespace
