// SPDX-License-Identifier: MIT
#include "rwmos/board.h"

#include "rwmos/board_state.h"

namespace rwmos {

Board::State::State(const BoardConfig& cfg)
    : config(cfg),
      motion(*this),
      otc_engine(*this),
      temp_comp_engine(*this),
      board_module(*this),
      tc_module(*this),
      comp3d_module(*this),
      otc_module(*this),
      temp_comp_module(*this) {
    tc_motion = &motion;
    cycle_offsets.add(&otc_engine);
    cycle_offsets.add(&temp_comp_engine);
    motion.executor().set_offsets(&cycle_offsets);
    // Modules on distinct buses: add() cannot fail here.
    dictionary.add(&board_module);
    dictionary.add(&tc_module);
    dictionary.add(&comp3d_module);
    dictionary.add(&otc_module);
    dictionary.add(&temp_comp_module);
}

Board::Board(const BoardConfig& config) : state_(std::make_unique<State>(config)) {}
Board::~Board() = default;

objif::Status Board::read(objif::Descriptor& d, objif::ValueType want, objif::Value& out) {
    return state_->dictionary.read(d, want, out);
}

objif::Status Board::write(objif::Descriptor& d, const objif::Value& v) {
    return state_->dictionary.write(d, v);
}

const BoardConfig& Board::config() const noexcept {
    return state_->config;
}
objif::Dictionary& Board::dictionary() noexcept {
    return state_->dictionary;
}
Board::State& Board::state() noexcept {
    return *state_;
}
const Board::State& Board::state() const noexcept {
    return *state_;
}

}  // namespace rwmos
