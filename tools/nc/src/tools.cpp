// SPDX-License-Identifier: MIT
#include "apci/nc/tools.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string_view>
#include <tuple>

#include "apci/nc/block.h"
#include "apci/nc/lexer.h"
#include "apci/nc/source.h"
#include "table_line_parser.h"

namespace apci::nc {

const ToolData* ToolTable::find(int index) const noexcept {
    const auto it = std::lower_bound(tools_.begin(), tools_.end(), index,
                                     [](const ToolData& t, int i) { return t.index < i; });
    return it != tools_.end() && it->index == index ? &*it : nullptr;
}

ToolData& ToolTable::define(int index) {
    auto it = std::lower_bound(tools_.begin(), tools_.end(), index,
                               [](const ToolData& t, int i) { return t.index < i; });
    if (it == tools_.end() || it->index != index) {
        ToolData t;
        t.index = index;
        it = tools_.insert(it, t);
    }
    return *it;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One tool field: its name, whether it takes an axis index, its value rule and its slot.
struct FieldSpec {
    std::string_view name;
    bool indexed;  // ax_ersatz[k]
    bool whole;    // whole number (int32 slot)
    double min;
    double max;
    std::string_view range;  // for the error message
    std::int32_t ToolData::*integer;
    double ToolData::*real;
};

// Units and ranges: [ISG-OTC] section 3.2 (P-TOOL-00001/00030/00031/00138) and section 2.6.
constexpr FieldSpec kFields[] = {
    {"gueltig", false, true, 0, 1, "0..1", &ToolData::gueltig, nullptr},
    {"typ", false, true, 0, 3, "0..3", &ToolData::typ, nullptr},
    {"mass_einheit", false, true, 0, 1, "0..1", &ToolData::mass_einheit, nullptr},
    {"laenge", false, false, -kInf, kInf, "", nullptr, &ToolData::laenge},
    {"radius", false, false, 0, kInf, ">= 0", nullptr, &ToolData::radius},
    {"ax_ersatz", true, false, -kInf, kInf, "", nullptr, nullptr},
    {"grinding_wear_const", false, false, 0, kInf, ">= 0", nullptr, &ToolData::grinding_wear_const},
    {"grinding_max_infeed", false, false, -2147483648.0, 2147483647.0,
     "-2147483648..2147483647 (SGN32)", nullptr, &ToolData::grinding_max_infeed},
    {"grinding_disc_tilt_angle", false, false, -450000, 450000,
     "-450000..450000 (-45..45 degrees in 0.0001 degree)", nullptr,
     &ToolData::grinding_disc_tilt_angle},
    {"r2", false, false, 0, kInf, ">= 0", nullptr, &ToolData::r2},
    {"dl", false, false, -kInf, kInf, "", nullptr, &ToolData::dl},
    {"dr", false, false, -kInf, kInf, "", nullptr, &ToolData::dr},
    {"dr2", false, false, -kInf, kInf, "", nullptr, &ToolData::dr2},
    {"wear_radius", false, false, -kInf, kInf, "", nullptr, &ToolData::wear_radius},
    {"wear_radius_cont", false, false, -kInf, kInf, "", nullptr, &ToolData::wear_radius_cont},
    {"cut", false, true, 0, 99, "0..99", &ToolData::cut, nullptr},
    {"srk_lage", false, true, 0, 9, "0..9", &ToolData::srk_lage, nullptr},
};

constexpr std::string_view kFieldList =
    "gueltig, typ, mass_einheit, laenge, radius, ax_ersatz[k], grinding_wear_const, "
    "grinding_max_infeed, grinding_disc_tilt_angle, r2, dl, dr, dr2, wear_radius, "
    "wear_radius_cont, cut, srk_lage";

const FieldSpec* find_field(std::string_view name) {
    for (const FieldSpec& f : kFields) {
        if (f.name == name) return &f;
    }
    return nullptr;
}

class ToolLineParser : TableLineParser {
  public:
    ToolLineParser(std::string_view file, ToolTable& table)
        : TableLineParser(file), table_(table) {}

    bool line(std::string_view text, std::uint64_t line_number, Diagnostic& err) {
        LineCursor c(text);
        start_line(line_number, err);
        c.skip_blanks();
        if (c.at_end() || c.peek() == '#') return true;
        const std::uint32_t start_col = c.column();
        if (c.scan_identifier() != "wz") {
            return fail(ErrorKind::kSyntax, start_col,
                        "expected 'wz[i].field value' or a '#' comment");
        }
        std::string_view digits;
        if (!bracketed(c, "after 'wz'", "a tool number", digits)) return false;
        const std::optional<std::uint64_t> index =
            whole_at_most(digits, static_cast<std::uint64_t>(kMaxToolNumber));
        if (!index || *index < 1) {
            return fail(ErrorKind::kValue, index_col_,
                        fmt::format("tool number {} out of range 1..{}", digits, kMaxToolNumber));
        }
        const int tool = static_cast<int>(*index);
        if (c.peek() != '.') {
            return fail(ErrorKind::kSyntax, c.column(),
                        fmt::format("expected '.' and a field name after 'wz[{}]'", tool));
        }
        c.advance();
        const std::uint32_t field_col = c.column();
        const std::string_view name = c.scan_identifier();
        if (name.empty()) {
            return fail(ErrorKind::kSyntax, field_col,
                        fmt::format("expected a field name after 'wz[{}].'", tool));
        }
        const FieldSpec* field = find_field(name);
        if (field == nullptr) {
            return fail(ErrorKind::kUnknownWord, field_col,
                        fmt::format("unknown tool field '{}' (known: {})", name, kFieldList));
        }
        std::uint64_t axis = 0;
        std::string label = fmt::format("wz[{}].{}", tool, name);
        if (field->indexed) {
            std::string_view axis_digits;
            if (!bracketed(c, fmt::format("after '{}'", label), "an axis index", axis_digits))
                return false;
            const std::optional<std::uint64_t> a =
                whole_at_most(axis_digits, static_cast<std::uint64_t>(kAxisOffsetCount - 1));
            if (!a) {
                return fail(ErrorKind::kValue, index_col_,
                            fmt::format("axis index {} out of range 0..{}", axis_digits,
                                        kAxisOffsetCount - 1));
            }
            axis = *a;
            label = fmt::format("{}[{}]", label, axis);
        } else if (c.peek() == '[') {
            return fail(ErrorKind::kSyntax, c.column(), fmt::format("'{}' takes no index", name));
        }
        double value = 0.0;
        if (!field_value(c, *field, label, value)) return false;
        // A field given twice would silently depend on line order; refuse it.
        const auto key = std::make_tuple(tool, static_cast<int>(field - kFields), axis);
        const auto [it, fresh] = seen_.emplace(key, current_line());
        if (fresh) columns_.emplace(key, field_col);
        if (!fresh) {
            return fail(ErrorKind::kConflict, field_col,
                        fmt::format("{} set twice (first on line {})", label, it->second));
        }
        ToolData& t = table_.define(tool);
        if (field->integer != nullptr) {
            t.*(field->integer) = static_cast<std::int32_t>(value);
        } else if (field->real != nullptr) {
            t.*(field->real) = value;
        } else {
            t.ax_ersatz[axis] = value;
        }
        return true;
    }

    // Where wz[tool].NAME (an unindexed field) was set: its line and the column of its name;
    // {0, 0} when it was not.
    std::pair<std::uint64_t, std::uint32_t> where(int tool, std::string_view name) const {
        const FieldSpec* field = find_field(name);
        if (field == nullptr) return {0, 0};
        const auto key = std::make_tuple(tool, static_cast<int>(field - kFields), std::uint64_t{0});
        const auto line = seen_.find(key);
        const auto column = columns_.find(key);
        if (line == seen_.end() || column == columns_.end()) return {0, 0};
        return {line->second, column->second};
    }

  private:
    // "[digits]" at the cursor.
    // "[digits]": the digits as written (range checks name them so, never clamped).
    bool bracketed(LineCursor& c, std::string_view where, std::string_view what,
                   std::string_view& out) {
        if (c.peek() != '[') {
            return fail(ErrorKind::kSyntax, c.column(), fmt::format("expected '[' {}", where));
        }
        c.advance();
        index_col_ = c.column();
        if (!is_digit(c.peek())) {
            return fail(ErrorKind::kSyntax, index_col_, fmt::format("expected {} after '['", what));
        }
        out = c.scan_digits();
        if (c.peek() != ']') {
            return fail(ErrorKind::kSyntax, c.column(), "expected ']'");
        }
        c.advance();
        return true;
    }

    bool field_value(LineCursor& c, const FieldSpec& f, const std::string& label, double& value) {
        std::uint32_t col = 0;
        if (!field_number(c, label, value, col)) return false;
        if (!c.at_end() && c.peek() != ' ' && c.peek() != '\t') {
            return fail(ErrorKind::kSyntax, c.column(),
                        fmt::format("expected a blank or the end of the line after the value of "
                                    "{}",
                                    label));
        }
        if (f.whole && value != std::floor(value)) {
            return fail(ErrorKind::kValue, col, fmt::format("{} must be a whole number", label));
        }
        if (value < f.min || value > f.max) {
            return fail(ErrorKind::kValue, col,
                        fmt::format("{} {} out of range {}", label, value, f.range));
        }
        return true;
    }

    ToolTable& table_;
    std::uint32_t index_col_ = 0;
    std::map<std::tuple<int, int, std::uint64_t>, std::uint64_t> seen_;
    std::map<std::tuple<int, int, std::uint64_t>, std::uint32_t> columns_;
};

// The board's TC module takes a tool radius and length within its coordinate limit
// (docs/object-map.md): a tool beyond is refused with its name here, once mass_einheit is known,
// rather than by the object write at its D.

bool check_sizes(const ToolTable& table, const ToolLineParser& parser, const std::string& file,
                 Diagnostic& err) {
    for (const ToolData& t : table.tools()) {
        const std::pair<std::string_view, double> sizes[] = {{"radius", t.radius_mm()},
                                                             {"laenge", t.length_mm()}};
        for (const auto& [field, mm] : sizes) {
            if (std::abs(mm) <= kBoardCoordinateLimit) continue;
            // Named where the size was set (a size beyond the limit was set: an unset one is 0).
            err = Diagnostic{};
            err.kind = ErrorKind::kValue;
            err.file = file;
            std::tie(err.line, err.column) = parser.where(t.index, field);
            err.message = fmt::format(
                "wz[{}].{} is {:g} mm: beyond the board's tool sizes of +-{:g} mm (check "
                "mass_einheit: 0 is 0.1 um, 1 is mm)",
                t.index, field, mm, kBoardCoordinateLimit);
            return false;
        }
    }
    return true;
}

Result<ToolTable> parse_lines(LineSource& source) {
    ToolTable table;
    ToolLineParser parser(source.name(), table);
    Diagnostic err;
    std::string_view text;
    for (;;) {
        switch (source.next(text, err)) {
            case LineSource::Read::kEnd:
                if (!check_sizes(table, parser, source.name(), err)) return err;
                return table;
            case LineSource::Read::kError:
                return err;
            case LineSource::Read::kLine:
                if (!parser.line(text, source.line_number(), err)) return err;
                break;
        }
    }
}

}  // namespace

ToolData* ToolTable::find_mutable(int index) noexcept {
    return const_cast<ToolData*>(static_cast<const ToolTable&>(*this).find(index));
}

namespace {
// Up to 6 decimals, trailing zeros and point dropped: "300000", "-12.5", "0.000001".
std::string format_value(double v) {
    std::string s = fmt::format("{:.6f}", v);
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    if (s == "-0") return "0";
    return s;
}
}  // namespace

std::string format_tool_table(const ToolTable& table) {
    std::string out;
    for (const ToolData& t : table.tools()) {
        const auto line = [&](std::string_view field, const std::string& value) {
            out += fmt::format("wz[{}].{:<26}{}\n", t.index, field, value);
        };
        line("gueltig", std::to_string(t.gueltig));
        line("typ", std::to_string(t.typ));
        line("mass_einheit", std::to_string(t.mass_einheit));
        for (const FieldSpec& f : kFields) {
            if (f.real != nullptr && t.*f.real != 0.0) line(f.name, format_value(t.*f.real));
            // The whole fields after the three above, when set.
            if (f.integer != nullptr && f.integer != &ToolData::gueltig &&
                f.integer != &ToolData::typ && f.integer != &ToolData::mass_einheit &&
                t.*f.integer != 0)
                line(f.name, std::to_string(t.*f.integer));
        }
        for (std::size_t k = 0; k < kAxisOffsetCount; ++k)
            if (t.ax_ersatz[k] != 0.0)
                line(fmt::format("ax_ersatz[{}]", k), format_value(t.ax_ersatz[k]));
    }
    return out;
}

Result<ToolTable> parse_tool_table(std::string_view text, std::string_view file) {
    LineSource source = LineSource::from_text(text, std::string(file));
    return parse_lines(source);
}

Result<ToolTable> load_tool_table(const std::string& path) {
    Result<LineSource> source = LineSource::open_file(path);
    if (!source) return source.error();
    return parse_lines(source.value());
}

}  // namespace apci::nc
