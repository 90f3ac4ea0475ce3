// SPDX-License-Identifier: MIT
#include "apci/run/plc_script.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "apci/nc/lexer.h"

namespace apci::run {

namespace {

using nc::Diagnostic;
using nc::ErrorKind;
using nc::LineCursor;

bool word_is(std::string_view id, std::string_view lower) {
    if (id.size() != lower.size()) return false;
    for (std::size_t i = 0; i < id.size(); ++i) {
        const char c = id[i] >= 'A' && id[i] <= 'Z' ? static_cast<char>(id[i] + 32) : id[i];
        if (c != lower[i]) return false;
    }
    return true;
}

class LineParser {
  public:
    LineParser(std::string_view line, std::uint64_t n, std::string_view file, Diagnostic& err)
        : c_(line), n_(n), file_(file), err_(err) {}

    // False with err; `empty` when the line holds nothing.
    bool parse(PlcWrite& w, bool& empty) {
        skip();
        empty = c_.at_end();
        if (empty) return true;
        w.line = n_;
        const std::uint32_t col = c_.column();
        const std::string_view when = c_.scan_identifier();
        if (word_is(when, "cycle"))
            w.when = PlcWrite::When::kCycle;
        else if (word_is(when, "block"))
            w.when = PlcWrite::When::kBlock;
        else
            return fail(col, "expected 'cycle N' or 'block N' at the start of the line");
        skip();
        if (!whole(w.at, w.when == PlcWrite::When::kCycle ? "cycle" : "block")) return false;
        skip();
        if (!unit(w)) return false;
        skip();
        if (!value(w)) return false;
        skip();
        if (!c_.at_end()) return fail(c_.column(), "unexpected text after the value");
        return true;
    }

  private:
    void skip() {
        c_.skip_blanks();
        if (c_.peek() == '#') c_.advance(c_.rest().size());
    }
    bool fail(std::uint32_t col, std::string message) {
        err_.kind = ErrorKind::kSyntax;
        err_.file = std::string(file_);
        err_.line = n_;
        err_.column = col;
        err_.message = std::move(message);
        return false;
    }
    bool whole(std::uint64_t& out, std::string_view what) {
        const std::uint32_t col = c_.column();
        if (!nc::is_digit(c_.peek()))
            return fail(col, fmt::format("expected a whole number after '{}'", what));
        out = 0;
        while (nc::is_digit(c_.peek())) {
            if (out > (std::numeric_limits<std::uint64_t>::max() - 9) / 10)
                return fail(col, fmt::format("the {} number is out of range", what));
            out = out * 10 + static_cast<std::uint64_t>(c_.peek() - '0');
            c_.advance();
        }
        return true;
    }
    bool unit(PlcWrite& w) {
        const std::uint32_t col = c_.column();
        const std::string_view name = c_.scan_identifier();
        if (word_is(name, "otc_radius_offset")) {
            w.channel = true;
        } else if (word_is(name, "otc_offset")) {
            w.channel = false;
            if (c_.peek() != '[') return fail(c_.column(), "expected '[axis]' after otc_offset");
            c_.advance();
            std::uint64_t axis = 0;
            if (!whole(axis, "otc_offset[")) return false;
            if (axis > 7) return fail(col, "otc_offset[i]: axis index 0..7");
            if (c_.peek() != ']') return fail(c_.column(), "expected ']' after the axis index");
            c_.advance();
            w.axis = static_cast<int>(axis);
        } else {
            return fail(col, "unknown unit (known: otc_radius_offset, otc_offset[i])");
        }
        if (c_.peek() != '.')
            return fail(c_.column(), "expected '.command' or '.enable' after the unit");
        c_.advance();
        const std::uint32_t fcol = c_.column();
        const std::string_view field = c_.scan_identifier();
        // The seed's ST names command_w / enable_w are accepted too.
        if (word_is(field, "command") || word_is(field, "command_w"))
            w.field = PlcWrite::Field::kCommand;
        else if (word_is(field, "enable") || word_is(field, "enable_w"))
            w.field = PlcWrite::Field::kEnable;
        else
            return fail(fcol, "unknown field (known: command, enable)");
        return true;
    }
    bool value(PlcWrite& w) {
        const std::uint32_t col = c_.column();
        if (w.field == PlcWrite::Field::kEnable && nc::is_letter(c_.peek())) {
            const std::string_view v = c_.scan_identifier();
            if (word_is(v, "true")) {
                w.value = 1;
                return true;
            }
            if (word_is(v, "false")) {
                w.value = 0;
                return true;
            }
            return fail(col, "enable takes 0, 1, TRUE or FALSE");
        }
        double d = 0.0;
        if (c_.scan_number(d) != nc::NumberScan::kOk) return fail(col, "expected a value");
        if (d != static_cast<double>(static_cast<std::int64_t>(d)) ||
            d < static_cast<double>(std::numeric_limits<std::int32_t>::min()) ||
            d > static_cast<double>(std::numeric_limits<std::int32_t>::max()))
            return fail(col, "the value must be a whole number in the DINT range (0.1 um)");
        if (w.field == PlcWrite::Field::kEnable && d != 0.0 && d != 1.0)
            return fail(col, "enable takes 0, 1, TRUE or FALSE");
        w.value = static_cast<std::int32_t>(d);
        return true;
    }

    LineCursor c_;
    std::uint64_t n_;
    std::string_view file_;
    Diagnostic& err_;
};

}  // namespace

std::string plc_unit_name(const PlcWrite& w) {
    const char* field = w.field == PlcWrite::Field::kCommand ? "command" : "enable";
    if (w.channel) return fmt::format("otc_radius_offset.{}", field);
    return fmt::format("otc_offset[{}].{}", w.axis, field);
}

nc::Result<PlcScript> parse_plc_script(std::string_view text, std::string_view file) {
    PlcScript s;
    s.file_ = std::string(file);
    std::uint64_t n = 0;
    std::size_t pos = 0;
    while (pos <= text.size()) {
        const std::size_t nl = text.find('\n', pos);
        std::string_view line =
            text.substr(pos, nl == std::string_view::npos ? text.size() - pos : nl - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        ++n;
        Diagnostic err;
        PlcWrite w;
        bool empty = false;
        if (!LineParser(line, n, file, err).parse(w, empty)) return err;
        if (!empty) (w.when == PlcWrite::When::kCycle ? s.cycle_ : s.block_).push_back(w);
        if (nl == std::string_view::npos) break;
        pos = nl + 1;
    }
    std::stable_sort(s.cycle_.begin(), s.cycle_.end(),
                     [](const PlcWrite& a, const PlcWrite& b) { return a.at < b.at; });
    return s;
}

nc::Result<PlcScript> load_plc_script(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        Diagnostic d;
        d.kind = ErrorKind::kIo;
        d.file = path;
        d.message = fmt::format("cannot open: {}", std::strerror(errno));
        return d;
    }
    std::ostringstream buf;
    buf << f.rdbuf();
    return parse_plc_script(buf.str(), path);
}

}  // namespace apci::run
