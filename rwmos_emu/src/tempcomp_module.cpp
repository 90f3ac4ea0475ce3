// SPDX-License-Identifier: MIT
// Temperature compensation module, bus 1320 ([SIN-TEMP], SINUMERIK 840D FB1
// W1 section 2.8; design numbers, docs/design.md section 4). Every value takes effect at the next
// interpolation cycle, also in the middle of a profile (the engine reads them each cycle), so
// no hook has a state rule: the dictionary's type and range checks are the whole of it.
#include "rwmos/tempcomp_module.h"

#include <array>

#include "objif/map/objects.h"

#include "rwmos/board_state.h"
#include "rwmos/module_table.h"

namespace rwmos {

std::int32_t TempCompModule::bus() const noexcept {
    return tempcomp::kBus;
}
bool TempCompModule::present() const noexcept {
    return state_.config.option_temp_comp;
}

std::span<const Entry<TempCompModule>> TempCompModule::table() const noexcept {
    using M = TempCompModule;
    static constexpr std::array<Hooks<M>, 24> kHooks{{
        {"TOOL_TEMP_COMP[0]", &M::read_comp, &M::write_comp},
        {"TOOL_TEMP_COMP[1]", &M::read_comp, &M::write_comp},
        {"TOOL_TEMP_COMP[2]", &M::read_comp, &M::write_comp},
        {"TOOL_TEMP_COMP_ON", &M::read_int, &M::write_int},
        {"TEMP_COMP_TYPE[0]", &M::read_int, &M::write_int},
        {"TEMP_COMP_TYPE[1]", &M::read_int, &M::write_int},
        {"TEMP_COMP_TYPE[2]", &M::read_int, &M::write_int},
        {"TEMP_COMP_TYPE[3]", &M::read_int, &M::write_int},
        {"TEMP_COMP_TYPE[4]", &M::read_int, &M::write_int},
        {"TEMP_COMP_TYPE[5]", &M::read_int, &M::write_int},
        {"TEMP_COMP_TYPE[6]", &M::read_int, &M::write_int},
        {"TEMP_COMP_TYPE[7]", &M::read_int, &M::write_int},
        {"ToolHolder", &M::read_int, &M::write_int},
        {"HeadAxisB", &M::read_int, &M::write_int},
        {"HeadAxisC", &M::read_int, &M::write_int},
        {"RampVelocity", &M::read_field<&State::temp_comp, &TempCompState::ramp_velocity>,
         &M::write_field<&State::temp_comp, &TempCompState::ramp_velocity>},
        {"Offset0", &M::read_offset, nullptr},
        {"Offset1", &M::read_offset, nullptr},
        {"Offset2", &M::read_offset, nullptr},
        {"Offset3", &M::read_offset, nullptr},
        {"Offset4", &M::read_offset, nullptr},
        {"Offset5", &M::read_offset, nullptr},
        {"Offset6", &M::read_offset, nullptr},
        {"Offset7", &M::read_offset, nullptr},
    }};
    static constexpr auto kTable = objif::attach(objif::map::tempcomp::kObjects, kHooks);
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

Status TempCompModule::read_offset(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_double(state_.temp_comp_engine.applied()[static_cast<std::size_t>(a.subindex)]);
    return Status::kOk;
}

}  // namespace rwmos
