// SPDX-License-Identifier: MIT
// The emulated APCI-8001/8008 running RWMOS.ELF: one struct of state behind
// the universal object interface. Every request is checked before it touches
// state; a bad one gets a status code and changes nothing.
// Not thread-safe: one thread at a time (the daemon serialises its clients).
#pragma once

#include <cstdint>
#include <memory>

#include "objif/descriptor.h"
#include "objif/dictionary.h"
#include "objif/status.h"
#include "objif/value.h"

namespace rwmos {

struct BoardConfig {
    // Firmware option "optionTC" (seed 003, section 1): without it the TC
    // module (bus 1300) does not exist and every access answers NoSuchDevice.
    bool option_tc = true;
};

class Board {
public:
    explicit Board(const BoardConfig& config = {});
    ~Board();
    Board(const Board&) = delete;
    Board& operator=(const Board&) = delete;

    objif::Status read(objif::Descriptor& d, objif::ValueType want, objif::Value& out);
    objif::Status write(objif::Descriptor& d, const objif::Value& v);

    const BoardConfig& config() const noexcept;
    objif::Dictionary& dictionary() noexcept;

    struct State;  // all device state, defined in board_state.h
    // The state behind the objects, for the emulator's own layers (motion,
    // spooler, clock) and for tests; PCAP-style code goes through read/write.
    State& state() noexcept;
    const State& state() const noexcept;

private:
    std::unique_ptr<State> state_;
};

}  // namespace rwmos
