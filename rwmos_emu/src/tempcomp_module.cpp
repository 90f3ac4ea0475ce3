// SPDX-License-Identifier: MIT
// Temperature compensation module, bus 1320 ([SIN-TEMP], SINUMERIK 840D FB1
// W1 section 2.8; design numbers, docs/design.md section 4). Every value takes effect at the next
// interpolation cycle, also in the middle of a profile (the engine reads them each cycle), so
// no hook has a state rule: the dictionary's type and range checks are the whole of it.
#include "rwmos/tempcomp_module.h"

#include <array>

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
constexpr double kMax = tempcomp::kMaxValue;
constexpr double kLastAxis = tempcomp::kAxisCount - 1;
constexpr auto kInt = ValueType::kInt32;
constexpr auto kDouble = ValueType::kDouble;
constexpr std::array<std::string_view, tempcomp::kAxisCount> kTypeNames{
    "TEMP_COMP_TYPE[0]", "TEMP_COMP_TYPE[1]", "TEMP_COMP_TYPE[2]", "TEMP_COMP_TYPE[3]",
    "TEMP_COMP_TYPE[4]", "TEMP_COMP_TYPE[5]", "TEMP_COMP_TYPE[6]", "TEMP_COMP_TYPE[7]"};
constexpr std::array<std::string_view, tempcomp::kAxisCount> kOffsetNames{
    "Offset0", "Offset1", "Offset2", "Offset3", "Offset4", "Offset5", "Offset6", "Offset7"};

constexpr ObjectInfo obj(std::int32_t index, std::int32_t sub, std::string_view name,
                         ValueType type, Access access, double min, double max, Value def,
                         std::string_view rule) {
    return {tempcomp::kDevice, index, index, sub, name, type, access, min, max, def, rule};
}
}  // namespace

std::int32_t TempCompModule::bus() const noexcept {
    return tempcomp::kBus;
}
bool TempCompModule::present() const noexcept {
    return state_.config.option_temp_comp;
}

std::span<const Entry<TempCompModule>> TempCompModule::table() const noexcept {
    using M = TempCompModule;
    constexpr auto kR = Access::kRead;
    constexpr auto kRW = Access::kReadWrite;
    static constexpr std::string_view kSd =
        "[SIN-TEMP]: SD 42960 TOOL_TEMP_COMP, a component of the vector on the geometry axes; "
        "acts at once";
    static constexpr std::string_view kMd32750 =
        "[SIN-TEMP]: MD 32750 TEMP_COMP_TYPE of the axis; bit 2 (4): the axis takes the vector";
    static constexpr std::string_view kOffset =
        "design: the displacement the axis got at the last interpolation cycle";
    static constexpr auto type = [](std::int32_t axis) {
        return Entry<M>{
            obj(tempcomp::kIdxTempCompType, axis, kTypeNames[static_cast<std::size_t>(axis)], kInt,
                kRW, 0, 255, Value::of_int(0), kMd32750),
            &M::read_int, &M::write_int};
    };
    static constexpr auto offset = [](std::int32_t axis) {
        return Entry<M>{
            obj(tempcomp::kIdxOffset, axis, kOffsetNames[static_cast<std::size_t>(axis)], kDouble,
                kR, -kMax, kMax, Value::of_double(0.0), kOffset),
            &M::read_offset, nullptr};
    };
    static constexpr std::array<Entry<M>, 24> kTable{{
        {obj(tempcomp::kIdxToolTempComp, 0, "TOOL_TEMP_COMP[0]", kDouble, kRW, -kMax, kMax,
             Value::of_double(0.0), kSd),
         &M::read_comp, &M::write_comp},
        {obj(tempcomp::kIdxToolTempComp, 1, "TOOL_TEMP_COMP[1]", kDouble, kRW, -kMax, kMax,
             Value::of_double(0.0), kSd),
         &M::read_comp, &M::write_comp},
        {obj(tempcomp::kIdxToolTempComp, 2, "TOOL_TEMP_COMP[2]", kDouble, kRW, -kMax, kMax,
             Value::of_double(0.0), kSd),
         &M::read_comp, &M::write_comp},
        {obj(tempcomp::kIdxToolTempCompOn, 0, "TOOL_TEMP_COMP_ON", kInt, kRW, objif::kInt32Min,
             objif::kInt32Max, Value::of_int(0),
             "[SIN-TEMP]: MD 20390, any value but 0 activates the compensation; kept as written"),
         &M::read_int, &M::write_int},
        type(0),
        type(1),
        type(2),
        type(3),
        type(4),
        type(5),
        type(6),
        type(7),
        {obj(tempcomp::kIdxToolHolder, 0, "ToolHolder", kInt, kRW, 0, 1, Value::of_int(0),
             "[SIN-TEMP]: orientable tool holder active: the vector turns with the head (B, C)"),
         &M::read_int, &M::write_int},
        {obj(tempcomp::kIdxHeadAxisB, 0, "HeadAxisB", kInt, kRW, 0, kLastAxis, Value::of_int(4),
             "design: board axis of the head's B (degrees), kinematics.h"),
         &M::read_int, &M::write_int},
        {obj(tempcomp::kIdxHeadAxisC, 0, "HeadAxisC", kInt, kRW, tempcomp::kNoHeadAxis, kLastAxis,
             Value::of_int(tempcomp::kNoHeadAxis), "design: board axis of the head's C, -1 none"),
         &M::read_int, &M::write_int},
        {obj(tempcomp::kIdxRampVelocity, 0, "RampVelocity", kDouble, kRW,
             tempcomp::kMinRampVelocity, tempcomp::kMaxRampVelocity,
             Value::of_double(tempcomp::kDefaultRampVelocity),
             "design: mm/s at which an axis that left the geometry axes goes to zero"),
         &M::read_ramp, &M::write_ramp},
        offset(0),
        offset(1),
        offset(2),
        offset(3),
        offset(4),
        offset(5),
        offset(6),
        offset(7),
    }};
    return kTable;
}

Status TempCompModule::read_comp(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_double(state_.temp_comp.comp[a.subindex]);
    return Status::kOk;
}

Status TempCompModule::write_comp(const ObjectInfo&, const Address& a, const Value& v) {
    state_.temp_comp.comp[a.subindex] = v.as_double();
    return Status::kOk;
}

std::int32_t& TempCompModule::int_field(const Address& a) noexcept {
    TempCompState& t = state_.temp_comp;
    switch (a.index) {
        case tempcomp::kIdxToolTempCompOn:
            return t.on;
        case tempcomp::kIdxTempCompType:
            return t.type[static_cast<std::size_t>(a.subindex)];
        case tempcomp::kIdxToolHolder:
            return t.tool_holder;
        case tempcomp::kIdxHeadAxisB:
            return t.head_axis_b;
        default:
            return t.head_axis_c;
    }
}

Status TempCompModule::read_int(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_int(int_field(a));
    return Status::kOk;
}

Status TempCompModule::write_int(const ObjectInfo&, const Address& a, const Value& v) {
    int_field(a) = v.as_int();
    return Status::kOk;
}

Status TempCompModule::read_ramp(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_double(state_.temp_comp.ramp_velocity);
    return Status::kOk;
}

Status TempCompModule::write_ramp(const ObjectInfo&, const Address&, const Value& v) {
    state_.temp_comp.ramp_velocity = v.as_double();
    return Status::kOk;
}

Status TempCompModule::read_offset(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_double(state_.temp_comp_engine.applied()[static_cast<std::size_t>(a.subindex)]);
    return Status::kOk;
}

}  // namespace rwmos
