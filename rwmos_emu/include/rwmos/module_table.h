// SPDX-License-Identifier: MIT
// The words of the object interface each module's table (board, TC, 3D, OTC, temperature) is
// written in: its entries, their access, type, hooks and the statuses they answer; and the
// module's base: its table's hooks work on the board's state, which the board hands each module
// it builds.
#pragma once

#include <cstdint>
#include <type_traits>

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

// A value of the board's state as an object's value, and back: an std::int32_t or an enum is an
// int object, a double a double object (a field of any other type has hooks of its own).
inline Value value_of(std::int32_t v) noexcept {
    return Value::of_int(v);
}
inline Value value_of(double v) noexcept {
    return Value::of_double(v);
}
inline void assign(std::int32_t& field, const Value& v) noexcept {
    field = v.as_int();
}
inline void assign(double& field, const Value& v) noexcept {
    field = v.as_double();
}
template <class E>
requires std::is_enum_v<E> Value value_of(E v)
noexcept {
    return Value::of_int(static_cast<std::int32_t>(v));
}
template <class E>
requires std::is_enum_v<E>
void assign(E& field, const Value& v) noexcept {
    field = static_cast<E>(v.as_int());
}

template <class Derived>
class BoardTableModule : public objif::TableModule<Derived> {
  public:
    explicit BoardTableModule(EmulatedBoard::State& state) noexcept : state_(state) {}

  protected:
    using Status = objif::Status;
    using Info = objif::ObjectInfo;
    using Address = objif::Address;
    using Value = objif::Value;
    using State = EmulatedBoard::State;

    // The hooks of an object that is one field of the board's state and follows no rule of its
    // own: the field reached from the state through the member pointers Path (&State::pu;
    // &State::tc, &TcState::rot_angle), read as it is and written as given (the table's type and
    // range checks come first).
    template <auto... Path>
    Status read_field(const Info&, const Address&, Value& out) {
        out = value_of(field_of<Path...>(state_));
        return Status::kOk;
    }
    template <auto... Path>
    Status write_field(const Info&, const Address&, const Value& v) {
        assign(field_of<Path...>(state_), v);
        return Status::kOk;
    }

    // The field the member pointers First, Rest... reach from `object`, one after the other.
    // (Written as a recursion, not as a fold over .*, which cppcheck cannot parse.)
    template <auto First, auto... Rest, class T>
    static auto& field_of(T& object) noexcept {
        if constexpr (sizeof...(Rest) == 0) {
            return object.*First;
        } else {
            return field_of<Rest...>(object.*First);
        }
    }

    EmulatedBoard::State& state_;
};

}  // namespace rwmos
