// SPDX-License-Identifier: MIT
// The OTC module, bus 1330 (design numbers, [ISG-OTC] behaviour: ISG FCT-C20 online tool
// compensation; docs/design.md section 4). DeviceNumber 0: what #OTC programs, the ramp, the head
// kinematics, the channel control unit otc_radius_offset. DeviceNumber 1: the per-axis control
// units otc_offset (Index = board axis). DeviceNumber 2: the current tool's grinding data and
// its wear (the V.G.WZ_AKT variables). docs/object-map.md section 5 is the spec page; every
// rule lives in its hook (otc_module.cpp).
#pragma once

#include <span>

#include "rwmos/board.h"
#include "rwmos/module_table.h"
#include "rwmos/otc/errors.h"
#include "rwmos/otc_state.h"

namespace rwmos {

class OtcModule : public BoardTableModule<OtcModule> {
  public:
    using BoardTableModule::BoardTableModule;
    std::int32_t bus() const noexcept override;
    std::string_view name() const noexcept override { return "OTC"; }
    // Only with the firmware option (BoardConfig::option_otc; Options bit 0x02).
    bool present() const noexcept override;
    std::span<const objif::Entry<OtcModule>> table() const noexcept;

  private:
    // Records `e` in LastError and answers `s` (the refusal of a rule).
    Status refuse(otc::Error e, Status s) noexcept;
    bool queue_busy() const noexcept;

    // DeviceNumber 0.
    Status read_active(const Info&, const Address&, Value& out);
    Status write_active(const Info&, const Address&, const Value& v);
    Status write_wear_const(const Info&, const Address&, const Value& v);
    Status read_wear_const_source(const Info&, const Address&, Value& out);
    Status write_wear_const_source(const Info&, const Address&, const Value& v);
    Status write_last_error(const Info&, const Address&, const Value& v);
    Status read_effective_wear_const(const Info&, const Address&, Value& out);
    Status write_kinematics(const Info&, const Address&, const Value& v);
    Status read_trafo(const Info&, const Address&, Value& out);
    Status write_trafo(const Info&, const Address&, const Value& v);
    // Control units: DeviceNumber 0 Index 20 (channel) and DeviceNumber 1 Index 0..7 (axes).
    Status read_unit_command(const Info&, const Address& a, Value& out);
    Status write_unit_command(const Info&, const Address& a, const Value& v);
    Status read_unit_enable(const Info&, const Address& a, Value& out);
    Status write_unit_enable(const Info&, const Address& a, const Value& v);
    // ManualMvBackToStart: DeviceNumber 1 Index 0..7, SubIndex 5..8.
    Status read_back_command(const Info&, const Address& a, Value& out);
    Status write_back_command(const Info&, const Address& a, const Value& v);
    Status read_back_enable(const Info&, const Address& a, Value& out);
    Status write_back_enable(const Info&, const Address& a, const Value& v);
    Status read_back_request(const Info&, const Address& a, Value& out);
    Status read_back_state(const Info&, const Address& a, Value& out);
    Status read_unit_request(const Info&, const Address& a, Value& out);
    Status read_unit_state(const Info&, const Address& a, Value& out);
    // DeviceNumber 2.
    Status write_tool_number(const Info&, const Address&, const Value& v);
    Status write_tool_wear_const(const Info&, const Address&, const Value& v);
    Status read_wear(const Info&, const Address& a, Value& out);

    // Settings fixed while OTC is on (type, mode, ACC_WEIGHT, kinematics) answer this then.
    Status refuse_while_active(otc::Error e) noexcept;
    // A setting fixed while OTC is on (ProcessingType, Mode, AccWeight, ToolAxisB, the tool's
    // typ, max infeed and tilt): the field Path leads to, refused with E while OTC is on.
    template <otc::Error E, auto... Path>
    Status write_while_off(const Info&, const Address&, const Value& v);
    OtcControlUnit* unit_at(const Address& a) noexcept;
};

}  // namespace rwmos
