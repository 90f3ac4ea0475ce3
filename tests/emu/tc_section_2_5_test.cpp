// SPDX-License-Identifier: MIT
// [APCI-TC] section 2.5 "Verwendung von TC", end to end: initialisation
// (RESET, compensation plane, tool table) and use (WKZINDEX, side, STATUS=1,
// STATUS=0), on a Board and over wire frames through the FrameServer.
#include <functional>

#include "emu_test_util.h"
#include "objif/frame.h"
#include "rwmos/frame_server.h"
#include "objif/map/tc_bits.h"

using namespace emu_test;
namespace tc = rwmos::tc;

namespace {

// One object access, however it travels.
using WriteFn = std::function<Status(Descriptor&, const Value&)>;
using ReadFn = std::function<Status(Descriptor&, ValueType, Value&)>;

// The PCAP program of section 2.5, written against read/write only. Group 2
// is used so Index (group) and WKZINDEX (tool) cannot be confused ([APCI-TC]:
// "Achtung: Nicht verwechseln mit dem Werkzeugindex!").
void run_section_2_5(const WriteFn& write, const ReadFn& read) {
    auto g = [](std::int32_t sub) { return tc_group(2, sub); };
    auto w_int = [&](Descriptor d, std::int32_t v) { return write(d, Value::of_int(v)); };
    auto w_dbl = [&](Descriptor d, double v) { return write(d, Value::of_double(v)); };
    auto r_int = [&](Descriptor d) {
        Value v;
        EXPECT_EQ(read(d, ValueType::kInt32, v), Status::kOk) << d.address.to_string();
        return v.as_int();
    };
    auto r_dbl = [&](Descriptor d) {
        Value v;
        EXPECT_EQ(read(d, ValueType::kDouble, v), Status::kOk) << d.address.to_string();
        return v.as_double();
    };

    // Initialisation: reset the tool compensation.
    ASSERT_EQ(w_int(g(tc::kSubReset), 0), Status::kOk);
    // Define the compensation plane (XAxis, YAxis, ZAxis): here the X-Y plane of board axes 0, 1.
    ASSERT_EQ(w_int(g(tc::kSubXAxis), 0), Status::kOk);
    ASSERT_EQ(w_int(g(tc::kSubYAxis), 1), Status::kOk);
    ASSERT_EQ(w_int(g(tc::kSubZAxis), 2), Status::kOk);
    // Define the tool table: for each tool, select the index, then program the radius.
    const std::array<std::pair<std::int32_t, double>, 3> tools{{{1, 2.5}, {2, 4.0}, {1023, 0.75}}};
    for (const auto& [index, radius] : tools) {
        ASSERT_EQ(w_int(g(tc::kSubWkzIndex), index), Status::kOk);
        ASSERT_EQ(w_dbl(g(tc::kSubRadius), radius), Status::kOk);
    }
    for (const auto& [index, radius] : tools) {
        ASSERT_EQ(w_int(g(tc::kSubWkzIndex), index), Status::kOk);
        EXPECT_EQ(r_dbl(g(tc::kSubRadius)), radius) << "tool " << index;
    }

    // Use: select the tool, then the side (only while no compensation is active), then activate.
    ASSERT_EQ(w_int(g(tc::kSubWkzIndex), 2), Status::kOk);
    ASSERT_EQ(w_int(g(tc::kSubRight), 0), Status::kOk);
    ASSERT_EQ(w_int(g(tc::kSubStatus), 1), Status::kOk);
    EXPECT_EQ(r_int(g(tc::kSubStatus)) & tc::kRun, tc::kRun);
    EXPECT_EQ(r_int(g(tc::kSubError)), 0);
    EXPECT_EQ(r_dbl(g(tc::kSubRadius)), 4.0);

    // The status can be read back at any time to catch programming errors:
    // a side change while active is refused and flagged.
    EXPECT_EQ(w_int(g(tc::kSubLeft), 0), Status::kWrongDeviceState);
    EXPECT_EQ(r_int(g(tc::kSubError)), tc::kInitError);
    EXPECT_EQ(r_int(g(tc::kSubSide)), tc::kSideRight);
    ASSERT_EQ(w_int(g(tc::kSubError), 0), Status::kOk);

    // (Profiles are spooled and executed here; that is the motion layer's part.)

    // Deactivate.
    ASSERT_EQ(w_int(g(tc::kSubStatus), 0), Status::kOk);
    EXPECT_EQ(r_int(g(tc::kSubStatus)), 0);
    EXPECT_EQ(r_int(g(tc::kSubError)), 0);
    // Inactive again: the side may change.
    EXPECT_EQ(w_int(g(tc::kSubLeft), 0), Status::kOk);
}

TEST(ApciTcSection2_5, SequenceRunsOnABoard) {
    rwmos::EmulatedBoard board;
    run_section_2_5([&](Descriptor& d, const Value& v) { return board.write(d, v); },
                    [&](Descriptor& d, ValueType t, Value& v) { return board.read(d, t, v); });
    EXPECT_EQ(board.state().tc.group(2).tools[2].radius, 4.0);
    EXPECT_EQ(board.state().tc.group(1).tools[2].radius, 0.0) << "group 1 untouched";
}

// The same program over the wire: every access is a request frame served by
// the FrameServer, as the daemon, mailbox and USB transports do.
class WireBoard {
public:
    Status write(Descriptor& d, const Value& v) {
        std::vector<std::uint8_t> payload;
        objif::encode(objif::WriteRequest{d, v}, payload);
        const auto reply = round_trip(objif::Opcode::kObjectWrite, payload);
        objif::WriteReply rep;
        if (objif::decode(reply, rep) != objif::FrameError::kNone) return Status::kBadFrame;
        d.handle = rep.handle;
        return rep.status;
    }
    Status read(Descriptor& d, ValueType t, Value& out) {
        std::vector<std::uint8_t> payload;
        objif::encode(objif::ReadRequest{d, t}, payload);
        const auto reply = round_trip(objif::Opcode::kObjectRead, payload);
        objif::ReadReply rep;
        if (objif::decode(reply, rep) != objif::FrameError::kNone) return Status::kBadFrame;
        d.handle = rep.handle;
        if (objif::ok(rep.status)) out = rep.value;
        return rep.status;
    }
    rwmos::EmulatedBoard board;

private:
    std::vector<std::uint8_t> round_trip(objif::Opcode op, const std::vector<std::uint8_t>& payload) {
        std::vector<std::uint8_t> request, reply;
        objif::encode_frame(static_cast<std::uint16_t>(op), ++sequence_, payload, request);
        EXPECT_EQ(server_.serve(request, reply), objif::FrameError::kNone);
        objif::Frame frame;
        std::size_t used = 0;
        bool need_more = false;
        EXPECT_EQ(objif::decode_frame(reply, frame, used, need_more), objif::FrameError::kNone);
        EXPECT_EQ(frame.sequence, sequence_);
        EXPECT_EQ(frame.opcode, static_cast<std::uint16_t>(op) | objif::kReplyFlag);
        return frame.payload;
    }
    rwmos::FrameServer server_{board};
    std::uint32_t sequence_ = 0;
};

TEST(ApciTcSection2_5, SequenceRunsOverWireFrames) {
    WireBoard wire;
    run_section_2_5([&](Descriptor& d, const Value& v) { return wire.write(d, v); },
                    [&](Descriptor& d, ValueType t, Value& v) { return wire.read(d, t, v); });
    EXPECT_EQ(wire.board.state().tc.group(2).tools[1023].radius, 0.75);
}

TEST(ApciTcSection2_5, StaleHandleAfterCleanTravelsOverTheWire) {
    WireBoard wire;
    auto radius = tc_group(1, tc::kSubRadius);
    ASSERT_EQ(wire.write(radius, Value::of_double(1.0)), Status::kOk);
    auto clean = tc_init(tc::kIdxClean);
    ASSERT_EQ(wire.write(clean, Value::of_int(1)), Status::kOk);
    Value v;
    EXPECT_EQ(wire.read(radius, ValueType::kDouble, v), Status::kStaleHandle);
}

}  // namespace
