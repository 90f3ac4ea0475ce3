// SPDX-License-Identifier: MIT
// The words of the object interface each module's table (board, TC, 3D, OTC, temperature) is
// written in: its entries, their access, type, hooks and the statuses they answer; and the
// module's base: its table's hooks work on the board's state, which the board hands each module
// it builds.
#pragma once

#include "objif/dictionary.h"
#include "rwmos/board.h"

namespace rwmos {

using objif::Access;
using objif::Address;
using objif::Entry;
using objif::Hooks;
using objif::ObjectInfo;
using objif::Status;
using objif::Value;
using objif::ValueType;

template <class Derived>
class BoardTableModule : public objif::TableModule<Derived> {
  public:
    explicit BoardTableModule(EmulatedBoard::State& state) noexcept : state_(state) {}

  protected:
    using Status = objif::Status;
    using Info = objif::ObjectInfo;
    using Address = objif::Address;
    using Value = objif::Value;

    EmulatedBoard::State& state_;
};

}  // namespace rwmos
