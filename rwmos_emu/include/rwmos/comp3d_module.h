// SPDX-License-Identifier: MIT
// The 3D tool compensation module, bus 1310 ([TNC-3D]; design numbers): DeviceNumber 0 the
// tool in force, the modes and the vectors of the next LN profile; DeviceNumber 1 the tool
// table (R, R2, DL, DR, DR2); DeviceNumber 2 the correction table (DL, DR, DR2). Each rule
// lives in its hook (comp3d_module.cpp); docs/object-map.md section 6 is the spec page.
#pragma once

#include <span>

#include "rwmos/board.h"
#include "rwmos/module_table.h"
#include "rwmos/comp3d_state.h"

namespace rwmos {

class Comp3dModule : public BoardTableModule<Comp3dModule> {
  public:
    using BoardTableModule::BoardTableModule;
    std::int32_t bus() const noexcept override;
    std::string_view name() const noexcept override { return "3D compensation"; }
    std::span<const objif::Entry<Comp3dModule>> table() const noexcept;

  private:
    Comp3dState& s() noexcept;
    // A refusal: LastError records it, the request answers WrongDeviceState (or InvalidValue
    // for vectors), nothing else changes.
    Status refuse(comp3d::Refusal r) noexcept;

    Status write_tool(const Info&, const Address&, const Value& v);
    Status read_call(const Info&, const Address& a, Value& out);
    Status write_call(const Info&, const Address& a, const Value& v);
    Status write_correction_row(const Info&, const Address&, const Value& v);
    Status write_allow_oversize(const Info&, const Address& a, const Value& v);
    Status read_vector(const Info&, const Address& a, Value& out);
    Status write_vector(const Info&, const Address& a, const Value& v);
    Status write_arm(const Info&, const Address&, const Value& v);
    Status write_last_error(const Info&, const Address&, const Value& v);
    Status read_deltas(const Info&, const Address& a, Value& out);
    Status read_last_tip(const Info&, const Address& a, Value& out);
    Status read_tool_row(const Info&, const Address& a, Value& out);
    Status write_tool_row(const Info&, const Address& a, const Value& v);
    Status read_correction(const Info&, const Address& a, Value& out);
    Status write_correction(const Info&, const Address& a, const Value& v);
};

}  // namespace rwmos
