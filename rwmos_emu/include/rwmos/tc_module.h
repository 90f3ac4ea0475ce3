// SPDX-License-Identifier: MIT
// The TC module, bus 1300 ([APCI-TC]; docs/design.md section 3): DeviceNumber 0
// initialisation objects (Table 2) and DeviceNumber 1 compensation groups
// (Table 3). Each object's rule lives in its hook (tc_module.cpp), next to the
// table row; docs/object-map.md is the spec page.
#pragma once

#include <span>

#include "rwmos/board.h"
#include "rwmos/module_table.h"
#include "rwmos/tc_state.h"

namespace rwmos {

class TcModule : public BoardTableModule<TcModule> {
public:
    using BoardTableModule::BoardTableModule;
    std::int32_t bus() const noexcept override;
    std::string_view name() const noexcept override { return "TC"; }
    // [APCI-TC] section 1: only with the firmware option optionTC.
    bool present() const noexcept override;
    std::span<const objif::Entry<TcModule>> table() const noexcept;

    // ReInit and Reset ignore their SubIndex ([APCI-TC] Table 2: "Subindex und
    // Parameter sind unbedeutend"): every SubIndex finds the SubIndex 0 row.
    const objif::ObjectInfo* find(const objif::Address& a, objif::Status& why) const noexcept override;
    // Every successful access marks the TC objects as accessed (TcState::objects_accessed).
    objif::Status read(const objif::ObjectInfo& info, const objif::Address& a, objif::Value& out) override;
    objif::Status write(const objif::ObjectInfo& info, const objif::Address& a, const objif::Value& v) override;

private:
    TcState& tc() noexcept;
    // Index 0 -> the active group, 1..3 -> that group; kWrongDeviceState when
    // Index 0 names no group.
    Status group_at(const Address& a, TcGroup*& g, std::int32_t& number) noexcept;
    Status with_group(const Address& a, TcGroup*& g) noexcept;
    void discard_held_profile(std::int32_t number);
    // The stored shift of the correction axes cleared (motion layer and offsets).
    void clear_shift();

    // DeviceNumber 0.
    Status write_clean(const Info&, const Address&, const Value&);
    Status read_axis_nr(const Info&, const Address& a, Value& out);
    Status write_axis_nr(const Info&, const Address& a, const Value& v);
    Status write_reinit(const Info&, const Address&, const Value&);
    Status write_reset(const Info&, const Address&, const Value&);

    // DeviceNumber 1.
    Status write_error(const Info&, const Address& a, const Value& v);
    Status write_group_reset(const Info&, const Address& a, const Value& v);
    Status write_status(const Info&, const Address& a, const Value& v);
    Status write_left(const Info&, const Address& a, const Value& v);
    Status write_right(const Info&, const Address& a, const Value& v);
    // A group's int field as it is (ERROR, STATUS, the axes, WKZINDEX, Side, the modes).
    template <std::int32_t TcGroup::*Field>
    Status read_group_field(const Info&, const Address& a, Value& out);
    // The int modes of a group (CornerMode, SelectionMode, LengthMode).
    template <std::int32_t TcGroup::*Field>
    Status write_group_mode(const Info&, const Address& a, const Value& v);
    // The current tool's values (RADIUS, WkzLen, CuttingEdge): Field a member pointer of TcTool.
    template <auto Field>
    Status read_tool_field(const Info&, const Address& a, Value& out);
    template <auto Field>
    Status write_tool_field(const Info&, const Address& a, const Value& v);

    // Shared by the "only while inactive" objects (XAxis, YAxis, ZAxis,
    // WKZINDEX, Left, Right): refuse and flag InitError while Run is set.
    Status write_while_inactive(const Address& a, std::int32_t TcGroup::*field, std::int32_t value);
    template <std::int32_t TcGroup::*Field>
    Status write_group_while_inactive(const Info&, const Address& a, const Value& v);
};

}  // namespace rwmos
