// SPDX-License-Identifier: MIT
// The in-process transport ("emu:"): owns an rwmos::EmulatedBoard and calls
// it directly, without frames. Blocking: never (virtual time; every call
// returns as soon as the board has served it). Threading: as the Board, one
// thread at a time, which the C API's contract already guarantees.
#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>  // program_invocation_short_name
#include <new>
#include <span>

#include "guarded.h"
#include "rwmos/board.h"
#include "rwmos/motion_claim.h"
#include "rwmos/motion_wire.h"
#include "transport.h"

namespace apci {
namespace {

class InprocTransport final : public Transport {
public:
    explicit InprocTransport(const rwmos::BoardConfig& config) : board_(config) {}

    objif::Status read(objif::Descriptor& d, objif::ValueType want,
                       objif::Value& out) noexcept override {
        try {
            return board_.read(d, want, out);
        } catch (const std::bad_alloc&) {
            return objif::Status::kNoMemory;
        } catch (...) {
            return objif::Status::kGeneralError;
        }
    }

    objif::Status write(objif::Descriptor& d, const objif::Value& v) noexcept override {
        try {
            return board_.write(d, v);
        } catch (const std::bad_alloc&) {
            return objif::Status::kNoMemory;
        } catch (...) {
            return objif::Status::kGeneralError;
        }
    }

    objif::Status spool(const objif::SpoolRequest& req, objif::MotionReply& rep) noexcept override {
        return guarded([&] {
            rwmos::serve_spool(board_, req, rep);
            return rep.status;
        });
    }
    objif::Status direct(const objif::DirectRequest& req, objif::MotionReply& rep) noexcept override {
        return guarded([&] { rep = rwmos::serve_direct(board_, req); return rep.status; });
    }
    objif::Status ssf(const objif::SsfRequest& req, objif::MotionReply& rep) noexcept override {
        return guarded([&] { rep = rwmos::serve_ssf(board_, req); return rep.status; });
    }
    objif::Status clock(const objif::ClockRequest& req, objif::ClockReply& rep) noexcept override {
        return guarded([&] { rep = rwmos::serve_clock(board_, req); return rep.status; });
    }
    objif::Status read_trace(const objif::TraceRequest& req, objif::TraceReply& rep) noexcept override {
        return guarded([&] { rep = rwmos::serve_trace(board_, req); return rep.status; });
    }
    // The board is this handle's alone (every "emu:" opens a board of its own), so its claim
    // has one host; it is kept by the same code as the daemon's (rwmos::MotionClaim).
    objif::Status claim(const objif::ClaimRequest& req, objif::ClaimReply& rep) noexcept override {
        return guarded([&] {
            rwmos::Host self;
            self.pid = static_cast<std::int32_t>(::getpid());
            self.name = program_invocation_short_name;
            rep = claim_.serve(self, req);
            return rep.status;
        });
    }
    // From the emulator's segment log straight into the caller's records: no reply to build
    // and copy (read_trace makes two vectors a call), each segment converted where the log
    // holds it.
    objif::Status read_segments(apci_segment* out, std::size_t max,
                                std::size_t& got) noexcept override {
        got = 0;
        return guarded([&] {
            apci_segment* next = out;
            got = board_.take_segments(
                max,
                [](std::span<const rwmos::motion::Segment> run, void* context) {
                    apci_segment*& at = *static_cast<apci_segment**>(context);
                    for (const rwmos::motion::Segment& s : run) segment_to_c(s, *at++);
                },
                &next);
            return objif::Status::kOk;
        });
    }

private:
    rwmos::EmulatedBoard board_;
    rwmos::MotionClaim claim_;
};

// "emu:?no-option-tc&option-tc": the last word on an option wins.
objif::Status board_config_from(const DeviceUri& uri, rwmos::BoardConfig& config,
                                std::string& why) {
    if (!uri.target.empty()) {
        why = fmt::format("device URI 'emu:{}': the embedded emulator takes no target "
                          "(use 'emu:' or 'emu:?no-option-tc')",
                          uri.target);
        return objif::Status::kInvalidArgument;
    }
    for (const auto& option : uri.options) {
        if (option == "no-option-tc") {
            config.option_tc = false;
        } else if (option == "option-tc") {
            config.option_tc = true;
        } else {
            why = fmt::format("unknown emu: option '{}' (known: option-tc, no-option-tc)", option);
            return objif::Status::kInvalidArgument;
        }
    }
    return objif::Status::kOk;
}

}  // namespace

objif::Status open_inproc(const DeviceUri& uri, std::unique_ptr<Transport>& out,
                          std::string& why) noexcept {
    try {
        rwmos::BoardConfig config;
        const objif::Status st = board_config_from(uri, config, why);
        if (!objif::ok(st)) return st;
        out = std::make_unique<InprocTransport>(config);
        return objif::Status::kOk;
    } catch (const std::bad_alloc&) {
        return objif::Status::kNoMemory;
    } catch (...) {
        why = "the embedded emulator failed to start";
        return objif::Status::kGeneralError;
    }
}

}  // namespace apci
