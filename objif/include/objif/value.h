// SPDX-License-Identifier: MIT
// A typed object value: int32 or IEEE-754 double, tagged. Reading or writing
// with the wrong tag is a type error (checked by the dictionary, not here).
#pragma once

#include <cstdint>
#include <string>

namespace objif {

// Wire tags (one byte on the wire); 0 is never a valid tag.
enum class ValueType : std::uint8_t { kInt32 = 1, kDouble = 2 };

std::string_view value_type_name(ValueType t) noexcept;  // "int" / "double"

class Value {
public:
    constexpr Value() noexcept : type_(ValueType::kInt32), i_(0) {}
    static constexpr Value of_int(std::int32_t v) noexcept { Value x; x.type_ = ValueType::kInt32; x.i_ = v; return x; }
    static constexpr Value of_double(double v) noexcept { Value x; x.type_ = ValueType::kDouble; x.d_ = v; return x; }

    constexpr ValueType type() const noexcept { return type_; }
    constexpr bool is_int() const noexcept { return type_ == ValueType::kInt32; }
    constexpr bool is_double() const noexcept { return type_ == ValueType::kDouble; }
    // Callers check type() first; these do not convert.
    constexpr std::int32_t as_int() const noexcept { return is_int() ? i_ : 0; }
    constexpr double as_double() const noexcept { return is_double() ? d_ : 0.0; }
    // Numeric view for range checks and printing.
    constexpr double numeric() const noexcept { return is_int() ? static_cast<double>(i_) : d_; }

    std::string to_string() const;  // "5" or "2.5" (shortest round-trip form)

    friend constexpr bool operator==(const Value& a, const Value& b) noexcept {
        if (a.type_ != b.type_) return false;
        return a.is_int() ? a.i_ == b.i_ : a.d_ == b.d_;
    }

private:
    ValueType type_;
    union {
        std::int32_t i_;
        double d_;
    };
};

}  // namespace objif
