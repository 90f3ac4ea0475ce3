// SPDX-License-Identifier: MIT
// Board module, bus 1000 (design: docs/design.md section 4 "Board"). Object
// numbers in rwmos/object_map.h; docs/object-map.md is the spec page.
#include "rwmos/board_module.h"

#include <array>
#include <limits>

#include "rwmos/board_state.h"

namespace rwmos {

using objif::Access;
using objif::Address;
using objif::Entry;
using objif::ObjectInfo;
using objif::Status;
using objif::Value;
using objif::ValueType;

namespace {
constexpr double kIntMin = objif::kInt32Min;
constexpr double kIntMax = objif::kInt32Max;
constexpr double kDoubleMin = std::numeric_limits<double>::lowest();
constexpr double kDoubleMax = std::numeric_limits<double>::max();
constexpr std::string_view kDesign = "design: docs/design.md section 4 Board";

constexpr std::array<std::string_view, kAxisCount> kPositionNames{
    "Position0", "Position1", "Position2", "Position3",
    "Position4", "Position5", "Position6", "Position7"};

constexpr ObjectInfo ro_int(std::int32_t index, std::string_view name, std::int32_t def) {
    return {board::kDevice, index, index, 0, name, ValueType::kInt32, Access::kRead,
            kIntMin, kIntMax, Value::of_int(def), kDesign};
}
}  // namespace

std::int32_t BoardModule::bus() const noexcept { return board::kBus; }

std::span<const Entry<BoardModule>> BoardModule::table() const noexcept {
    using M = BoardModule;
    static constexpr auto position = [](std::int32_t axis) {
        return Entry<M>{{board::kDevice, board::kIdxAxisPosition, board::kIdxAxisPosition, axis,
                         kPositionNames[static_cast<std::size_t>(axis)], ValueType::kDouble,
                         Access::kRead, kDoubleMin, kDoubleMax, Value::of_double(0.0),
                         "design: axis position, written by the motion layer"},
                        &M::read_axis_position, nullptr};
    };
    static constexpr std::array<Entry<M>, 16> kTable{{
        {ro_int(board::kIdxFirmwareVersion, "FirmwareVersion", kFirmwareVersion),
         &M::read_firmware_version, nullptr},
        {ro_int(board::kIdxOptions, "Options", board::kOptionTc | board::kOptionOtc | board::kOptionTempComp),
         &M::read_options, nullptr},
        {ro_int(board::kIdxAxisCount, "AxisCount", kAxisCount), &M::read_axis_count, nullptr},
        {{board::kDevice, board::kIdxInterpolationCycle, board::kIdxInterpolationCycle, 0,
          "InterpolationCycle", ValueType::kInt32, Access::kReadWrite, kMinInterpolationCycleUs,
          kMaxInterpolationCycleUs, Value::of_int(kDefaultInterpolationCycleUs),
          "design: docs/design.md section 4, default 1 ms, in microseconds"},
         &M::read_interpolation_cycle, &M::write_interpolation_cycle},
        {{board::kDevice, board::kIdxPu, board::kIdxPu, 0, "PU", ValueType::kInt32,
          Access::kReadWrite, board::kPuMillimetre, board::kPuInch, Value::of_int(board::kPuMillimetre),
          "design: unit of RADIUS/WkzLen ([APCI-TC] Table 3 'mit PU angewaehlte Einheit')"},
         &M::read_pu, &M::write_pu},
        {ro_int(board::kIdxSpoolerCapacity, "SpoolerCapacity", kSpoolerCapacity),
         &M::read_spooler_capacity, nullptr},
        {ro_int(board::kIdxSpoolerFill, "SpoolerFill", 0), &M::read_spooler_fill, nullptr},
        position(0), position(1), position(2), position(3),
        position(4), position(5), position(6), position(7),
        {{board::kDevice, board::kIdxRs, board::kIdxRs, 0, "rs", ValueType::kInt32, Access::kWrite,
          kIntMin, kIntMax, Value::of_int(0),
          "[APCI-TC] Table 2: rs() zeroes RotAngle, RotCenterX, RotCenterY"},
         nullptr, &M::write_rs},
    }};
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

Status BoardModule::read_interpolation_cycle(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(state_.interpolation_cycle_us);
    return Status::kOk;
}

Status BoardModule::write_interpolation_cycle(const ObjectInfo&, const Address&, const Value& v) {
    state_.interpolation_cycle_us = v.as_int();
    return Status::kOk;
}

Status BoardModule::read_pu(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(state_.pu);
    return Status::kOk;
}

Status BoardModule::write_pu(const ObjectInfo&, const Address&, const Value& v) {
    state_.pu = v.as_int();
    return Status::kOk;
}

Status BoardModule::read_spooler_capacity(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(state_.spooler.capacity);
    return Status::kOk;
}

Status BoardModule::read_spooler_fill(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(state_.spooler.fill);
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
    return Status::kOk;
}

}  // namespace rwmos
