// SPDX-License-Identifier: MIT
#include "rwmos/board.h"

#include "rwmos/board_state.h"

namespace rwmos {

EmulatedBoard::State::State(const BoardConfig& cfg)
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

EmulatedBoard::EmulatedBoard(const BoardConfig& config) : state_(std::make_unique<State>(config)) {}
EmulatedBoard::~EmulatedBoard() = default;

namespace {
// An object access may change what the motion layer's TC settings are read from (a TC write,
// PU, rs, OTC's OFF folding wear into the tool table, a TC read marking the objects accessed):
// they are read again at the next motion call, also when the access ends in an exception.
class SettingsMayChange {
  public:
    explicit SettingsMayChange(MotionLayer& motion) noexcept : motion_(motion) {
        motion_.settings_changed();
    }
    ~SettingsMayChange() { motion_.settings_changed(); }
    SettingsMayChange(const SettingsMayChange&) = delete;
    SettingsMayChange& operator=(const SettingsMayChange&) = delete;

  private:
    MotionLayer& motion_;
};
}  // namespace

objif::Status EmulatedBoard::read(objif::Descriptor& d, objif::ValueType want, objif::Value& out) {
    const SettingsMayChange access(state_->motion);
    return state_->dictionary.read(d, want, out);
}

objif::Status EmulatedBoard::write(objif::Descriptor& d, const objif::Value& v) {
    const SettingsMayChange access(state_->motion);
    return state_->dictionary.write(d, v);
}

const BoardConfig& EmulatedBoard::config() const noexcept {
    return state_->config;
}
objif::Dictionary& EmulatedBoard::dictionary() noexcept {
    return state_->dictionary;
}
EmulatedBoard::State& EmulatedBoard::state() noexcept {
    return *state_;
}
const EmulatedBoard::State& EmulatedBoard::state() const noexcept {
    return *state_;
}

}  // namespace rwmos
