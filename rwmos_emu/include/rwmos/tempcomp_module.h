// SPDX-License-Identifier: MIT
// The temperature compensation module, bus 1320 ([SIN-TEMP]; design numbers): SD 42960,
// MD 20390, MD 32750, the orientable tool holder and the ramp; the displacement it applies.
// docs/object-map.md section 7 is the spec page.
#pragma once

#include <span>

#include "rwmos/board.h"
#include "rwmos/module_table.h"
#include "rwmos/tempcomp_state.h"

namespace rwmos {

class TempCompModule : public BoardTableModule<TempCompModule> {
  public:
    using BoardTableModule::BoardTableModule;
    std::int32_t bus() const noexcept override;
    std::string_view name() const noexcept override { return "Temperature compensation"; }
    // [SIN-TEMP]: "eine Option, die vorher freigeschaltet werden muß"
    // (BoardConfig::option_temp_comp).
    bool present() const noexcept override;
    std::span<const objif::Entry<TempCompModule>> table() const noexcept;

  private:
    Status read_comp(const Info&, const Address& a, Value& out);
    Status write_comp(const Info&, const Address& a, const Value& v);
    Status read_int(const Info&, const Address& a, Value& out);
    Status write_int(const Info&, const Address& a, const Value& v);
    Status read_offset(const Info&, const Address& a, Value& out);

    std::int32_t& int_field(const Address& a) noexcept;
};

}  // namespace rwmos
