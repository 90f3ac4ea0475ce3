// SPDX-License-Identifier: MIT
#include "apci/nc/correction_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <string_view>
#include <utility>

#include "apci/nc/lexer.h"
#include "apci/nc/source.h"
#include "table_line_parser.h"

namespace apci::nc {

namespace {

struct Field {
    std::string_view name;
    double CorrectionRow::*value;
};
constexpr std::array<Field, 3> kFields{
    {{"dl", &CorrectionRow::dl}, {"dr", &CorrectionRow::dr}, {"dr2", &CorrectionRow::dr2}}};

class RowParser : TableLineParser {
  public:
    explicit RowParser(std::string_view file) : TableLineParser(file) {}

    // One line: `row` 0 for a blank or comment line, else the row, field and value to set.
    bool line(std::string_view text, std::uint64_t n, int& row, std::size_t& field, double& value,
              Diagnostic& err) {
        LineCursor c(text);
        start_line(n, err);
        row = 0;
        c.skip_blanks();
        if (c.at_end() || c.peek() == '#') return true;
        const std::uint32_t start = c.column();
        if (c.scan_identifier() != "corr" || c.peek() != '[')
            return fail(ErrorKind::kSyntax, start,
                        "expected 'corr[n].dl|dr|dr2 value' or a '#' comment");
        c.advance();
        const std::uint32_t index_col = c.column();
        if (!is_digit(c.peek()))
            return fail(ErrorKind::kSyntax, index_col, "expected a row number after '['");
        const std::string_view digits = c.scan_digits();
        if (c.peek() != ']') return fail(ErrorKind::kSyntax, c.column(), "expected ']'");
        c.advance();
        const std::optional<std::uint64_t> index =
            whole_at_most(digits, static_cast<std::uint64_t>(kMaxCorrectionRow));
        if (!index || *index < 1)
            return fail(ErrorKind::kValue, index_col,
                        fmt::format("correction row {} out of range 1..{} (row 0 is no "
                                    "correction: FUNCTION CORRDATA RESET TCS)",
                                    digits, kMaxCorrectionRow));
        const int r = static_cast<int>(*index);
        if (c.peek() != '.')
            return fail(ErrorKind::kSyntax, c.column(),
                        fmt::format("expected '.' and a field name after 'corr[{}]'", r));
        c.advance();
        const std::uint32_t field_col = c.column();
        const std::string_view name = c.scan_identifier();
        const auto* f = std::find_if(kFields.begin(), kFields.end(),
                                     [&](const Field& x) { return x.name == name; });
        if (f == kFields.end())
            return fail(ErrorKind::kUnknownWord, field_col,
                        fmt::format("unknown correction field '{}' (known: dl, dr, dr2)", name));
        const std::string label = fmt::format("corr[{}].{}", r, name);
        std::uint32_t col = 0;
        if (!field_number(c, label, value, col)) return false;
        c.skip_blanks();
        if (!c.at_end() && c.peek() != '#')
            return fail(ErrorKind::kSyntax, c.column(),
                        fmt::format("unexpected text after the value of {}", label));
        if (!(std::fabs(value) <= kCorrectionLimit))
            return fail(ErrorKind::kValue, col,
                        fmt::format("{} {} out of range -{:g}..{:g} mm", label, value,
                                    kCorrectionLimit, kCorrectionLimit));
        field = static_cast<std::size_t>(f - kFields.begin());
        const auto [it, fresh] = seen_.emplace(std::pair{r, field}, current_line());
        if (!fresh)
            return fail(ErrorKind::kConflict, field_col,
                        fmt::format("{} set twice (first on line {})", label, it->second));
        row = r;
        return true;
    }

  private:
    std::map<std::pair<int, std::size_t>, std::uint64_t> seen_;
};

}  // namespace

const CorrectionRow* CorrectionTable::find(int row) const noexcept {
    const auto it = std::lower_bound(rows_.begin(), rows_.end(), row,
                                     [](const CorrectionRow& r, int n) { return r.row < n; });
    return it != rows_.end() && it->row == row ? &*it : nullptr;
}

CorrectionRow& CorrectionTable::define(int row) {
    const auto it = std::lower_bound(rows_.begin(), rows_.end(), row,
                                     [](const CorrectionRow& r, int n) { return r.row < n; });
    if (it != rows_.end() && it->row == row) return *it;
    CorrectionRow r;
    r.row = row;
    return *rows_.insert(it, r);
}

Result<CorrectionTable> parse_correction_table(std::string_view text, std::string_view file) {
    LineSource source = LineSource::from_text(text, std::string(file));
    CorrectionTable table;
    RowParser parser(source.name());
    Diagnostic err;
    std::string_view line;
    for (;;) {
        switch (source.next(line, err)) {
            case LineSource::Read::kEnd:
                return table;
            case LineSource::Read::kError:
                return err;
            case LineSource::Read::kLine: {
                int row = 0;
                std::size_t field = 0;
                double value = 0.0;
                if (!parser.line(line, source.line_number(), row, field, value, err)) return err;
                if (row != 0) table.define(row).*(kFields[field].value) = value;
                break;
            }
        }
    }
}

Result<CorrectionTable> load_correction_table(const std::string& path) {
    Result<LineSource> source = LineSource::open_file(path);
    if (!source) return source.error();
    std::string text;
    std::string_view line;
    Diagnostic err;
    for (;;) {
        const auto r = source.value().next(line, err);
        if (r == LineSource::Read::kError) return err;
        if (r == LineSource::Read::kEnd) break;
        text.append(line);
        text.push_back('\n');
    }
    return parse_correction_table(text, path);
}

}  // namespace apci::nc
