// SPDX-License-Identifier: MIT
// The board module, bus 1000 (design; docs/object-map.md): firmware version,
// options, axis count, interpolation cycle, PU, spooler capacity and fill
// level, axis positions and the rs() command.
#pragma once

#include <span>

#include "objif/dictionary.h"
#include "rwmos/board.h"

namespace rwmos {

class BoardModule : public objif::TableModule<BoardModule> {
public:
    explicit BoardModule(Board::State& state) noexcept : state_(state) {}
    std::int32_t bus() const noexcept override;
    std::string_view name() const noexcept override { return "Board"; }
    std::span<const objif::Entry<BoardModule>> table() const noexcept;

private:
    using Status = objif::Status;
    using Info = objif::ObjectInfo;
    using Address = objif::Address;
    using Value = objif::Value;

    Status read_firmware_version(const Info&, const Address&, Value& out);
    Status read_options(const Info&, const Address&, Value& out);
    Status read_axis_count(const Info&, const Address&, Value& out);
    Status read_interpolation_cycle(const Info&, const Address&, Value& out);
    Status write_interpolation_cycle(const Info&, const Address&, const Value& v);
    Status read_pu(const Info&, const Address&, Value& out);
    Status write_pu(const Info&, const Address&, const Value& v);
    Status read_spooler_capacity(const Info&, const Address&, Value& out);
    Status read_spooler_fill(const Info&, const Address&, Value& out);
    Status read_axis_position(const Info&, const Address& a, Value& out);
    Status write_rs(const Info&, const Address&, const Value&);

    Board::State& state_;
};

}  // namespace rwmos
