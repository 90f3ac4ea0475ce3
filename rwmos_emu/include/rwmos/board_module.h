// SPDX-License-Identifier: MIT
// The board module, bus 1000 (design; docs/object-map.md): firmware version,
// options, axis count, interpolation cycle, PU, spooler capacity and fill
// level, axis positions and the rs() command.
#pragma once

#include <span>

#include "rwmos/board.h"
#include "rwmos/module_table.h"

namespace rwmos {

class BoardModule : public BoardTableModule<BoardModule> {
public:
    using BoardTableModule::BoardTableModule;
    std::int32_t bus() const noexcept override;
    std::string_view name() const noexcept override { return "Board"; }
    std::span<const objif::Entry<BoardModule>> table() const noexcept;

private:
    Status read_firmware_version(const Info&, const Address&, Value& out);
    Status read_options(const Info&, const Address&, Value& out);
    Status read_axis_count(const Info&, const Address&, Value& out);
    Status write_pu(const Info&, const Address&, const Value& v);
    Status read_axis_position(const Info&, const Address& a, Value& out);
    Status write_rs(const Info&, const Address&, const Value&);
};

}  // namespace rwmos
