// SPDX-License-Identifier: MIT
// Board module, bus 1000 (design: docs/design.md section 4 "Board"). Object
// numbers in rwmos/object_map.h; docs/object-map.md is the spec page.
#include "rwmos/board_module.h"

#include <array>

#include "objif/map/objects.h"
#include <limits>

#include "rwmos/board_state.h"
#include "rwmos/module_table.h"

namespace rwmos {

std::int32_t BoardModule::bus() const noexcept { return board::kBus; }

std::span<const Entry<BoardModule>> BoardModule::table() const noexcept {
    using M = BoardModule;
    static constexpr std::array<Hooks<M>, 16> kHooks{{
        {"FirmwareVersion", &M::read_firmware_version, nullptr},
        {"Options", &M::read_options, nullptr},
        {"AxisCount", &M::read_axis_count, nullptr},
        {"InterpolationCycle", &M::read_field<&State::interpolation_cycle_us>,
         &M::write_field<&State::interpolation_cycle_us>},
        {"PU", &M::read_field<&State::pu>, &M::write_pu},
        {"SpoolerCapacity", &M::read_field<&State::spooler, &SpoolerState::capacity>, nullptr},
        {"SpoolerFill", &M::read_field<&State::spooler, &SpoolerState::fill>, nullptr},
        {"Position0", &M::read_axis_position, nullptr},
        {"Position1", &M::read_axis_position, nullptr},
        {"Position2", &M::read_axis_position, nullptr},
        {"Position3", &M::read_axis_position, nullptr},
        {"Position4", &M::read_axis_position, nullptr},
        {"Position5", &M::read_axis_position, nullptr},
        {"Position6", &M::read_axis_position, nullptr},
        {"Position7", &M::read_axis_position, nullptr},
        {"rs", nullptr, &M::write_rs},
    }};
    static constexpr auto kTable = objif::attach(objif::map::board::kObjects, kHooks);
    return kTable;
}

Status BoardModule::read_firmware_version(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(kFirmwareVersion);
    return Status::kOk;
}

Status BoardModule::read_options(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int((state_.config.option_tc ? board::kOptionTc : 0) |
                        (state_.config.option_otc ? board::kOptionOtc : 0) |
                        (state_.config.option_temp_comp ? board::kOptionTempComp : 0));
    return Status::kOk;
}

Status BoardModule::read_axis_count(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(static_cast<std::int32_t>(state_.axes.size()));
    return Status::kOk;
}

Status BoardModule::write_pu(const ObjectInfo&, const Address&, const Value& v) {
    state_.pu = v.as_int();
    state_.motion.settings_changed();  // the unit of the TC tool values
    return Status::kOk;
}

Status BoardModule::read_axis_position(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_double(state_.axes[static_cast<std::size_t>(a.subindex)].position);
    return Status::kOk;
}

// [APCI-TC] Table 2 (RotAngle, RotCenterX, RotCenterY): "Dieser Wert wird mit
// dem Kommando rs() abgenullt". The parameter is meaningless.
Status BoardModule::write_rs(const ObjectInfo&, const Address&, const Value&) {
    state_.tc.rot_angle = 0.0;
    state_.tc.rot_center_x = 0.0;
    state_.tc.rot_center_y = 0.0;
    state_.motion.settings_changed();
    return Status::kOk;
}

}  // namespace rwmos
