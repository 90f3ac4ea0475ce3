// SPDX-License-Identifier: MIT
#include "apci/run/plc_script.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <optional>

#include "apci/nc/block.h"
#include "apci/nc/lexer.h"
#include "apci/nc/source.h"
#include "apci/run/run_files.h"
#include "objif/map/object_map.h"

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
        const bool cycle = w.when == PlcWrite::When::kCycle;
        if (!whole(w.at, cycle ? "cycle" : "block", cycle ? kMaxPlcCycle : nc::kMaxWordNumber,
                   cycle ? fmt::format(" (the clock runs on to it: at most {:.1f} days of board "
                                       "time at 1 ms)",
                                       static_cast<double>(kMaxPlcCycle) * 1e-3 / 86400.0)
                         : " (an N number of the program)"))
            return false;
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
    // A whole number in 0..max after `what`; one beyond is named as written, with its range
    // and `why` (never clamped or wrapped).
    bool whole(std::uint64_t& out, std::string_view what, std::uint64_t max, std::string_view why) {
        const std::uint32_t col = c_.column();
        if (!nc::is_digit(c_.peek()))
            return fail(col, fmt::format("expected a whole number after '{}'", what));
        const std::string_view digits = c_.scan_digits();
        const std::optional<std::uint64_t> v = nc::whole_at_most(digits, max);
        if (!v) return fail(col, fmt::format("{} {} out of range 0..{}{}", what, digits, max, why));
        out = *v;
        return true;
    }
    // "[i]" with i in 0..last; `what` names the unit in the error.
    bool bracket_index(int& out, int last, std::string_view what, std::uint32_t col) {
        if (c_.peek() != '[')
            return fail(c_.column(), fmt::format("expected '[i]' after {}", what));
        c_.advance();
        const std::uint32_t digits_col = c_.column();
        if (!nc::is_digit(c_.peek()))
            return fail(digits_col, fmt::format("expected a whole number after '{}['", what));
        const std::optional<std::uint64_t> i =
            nc::whole_at_most(c_.scan_digits(), static_cast<std::uint64_t>(last));
        if (!i)
            return fail(col, fmt::format("{}[i]: {} index 0..{}", what,
                                         what == "tool_temp_comp" ? "component" : "axis", last));
        if (c_.peek() != ']') return fail(c_.column(), "expected ']' after the index");
        c_.advance();
        out = static_cast<int>(*i);
        return true;
    }
    bool unit(PlcWrite& w) {
        using Unit = PlcWrite::Unit;
        // Each unit's name and the last index it takes in brackets (-1: none).
        struct UnitName {
            std::string_view name;
            Unit unit;
            int last_index;
        };
        static constexpr UnitName kUnits[] = {{"otc_radius_offset", Unit::kOtcRadiusOffset, -1},
                                              {"otc_offset", Unit::kOtcOffset, 7},
                                              {"tool_temp_comp", Unit::kToolTempComp, 2},
                                              {"tool_temp_comp_on", Unit::kToolTempCompOn, -1},
                                              {"temp_comp_type", Unit::kTempCompType, 7},
                                              {"tool_holder", Unit::kToolHolder, -1},
                                              {"tool_holder_axis_b", Unit::kToolHolderAxisB, -1},
                                              {"tool_holder_axis_c", Unit::kToolHolderAxisC, -1},
                                              {"temp_ramp_velocity", Unit::kTempRampVelocity, -1}};
        const std::uint32_t col = c_.column();
        const std::string_view name = c_.scan_identifier();
        const auto* u = std::find_if(std::begin(kUnits), std::end(kUnits),
                                     [&](const UnitName& x) { return word_is(name, x.name); });
        if (u == std::end(kUnits)) {
            return fail(col,
                        "unknown unit (known: otc_radius_offset, otc_offset[i], "
                        "tool_temp_comp[i], tool_temp_comp_on, temp_comp_type[i], tool_holder, "
                        "tool_holder_axis_b, tool_holder_axis_c, temp_ramp_velocity)");
        }
        w.unit = u->unit;
        if (u->last_index >= 0 && !bracket_index(w.index, u->last_index, u->name, col))
            return false;
        if (!w.otc()) return true;  // the temperature units have no field
        if (c_.peek() != '.')
            return fail(c_.column(), "expected '.command' or '.enable' after the unit");
        c_.advance();
        const std::uint32_t fcol = c_.column();
        const std::string_view field = c_.scan_identifier();
        // The ST names of [ISG-OTC], command_w / enable_w are accepted too.
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
        const char* flag_error = w.otc() ? "enable takes 0, 1, TRUE or FALSE"
                                 : w.unit == PlcWrite::Unit::kToolHolder
                                     ? "tool_holder takes 0, 1, TRUE or FALSE"
                                     : "tool_temp_comp_on (MD 20390) takes a whole number "
                                       "(int32; not 0: on), TRUE or FALSE";
        if (w.flag() && nc::is_letter(c_.peek())) {
            const std::string_view v = c_.scan_identifier();
            if (word_is(v, "true")) {
                w.value = 1;
                return true;
            }
            if (word_is(v, "false")) {
                w.value = 0;
                return true;
            }
            return fail(col, flag_error);
        }
        double d = 0.0;
        if (c_.scan_number(d) != nc::NumberScan::kOk || !std::isfinite(d))
            return fail(col, "expected a value (a finite number)");
        switch (w.unit) {
            case PlcWrite::Unit::kToolTempComp:
                // The object's range (bus 1320 Index 1, docs/object-map.md section 7).
                if (!(std::fabs(d) <= objif::map::tempcomp::kMaxValue))
                    return fail(col, fmt::format("tool_temp_comp[{}] (SD 42960, mm) takes "
                                                 "-{:g}..{:g}",
                                                 w.index, objif::map::tempcomp::kMaxValue,
                                                 objif::map::tempcomp::kMaxValue));
                w.value = d;
                return true;
            case PlcWrite::Unit::kToolTempCompOn:
                // [SIN-TEMP]: MD 20390 "ungleich Null" activates; the object takes any int32.
                if (d != std::floor(d) || d < std::numeric_limits<std::int32_t>::min() ||
                    d > std::numeric_limits<std::int32_t>::max())
                    return fail(col, flag_error);
                w.value = d;
                return true;
            case PlcWrite::Unit::kToolHolder:
                if (d != 0.0 && d != 1.0) return fail(col, flag_error);
                w.value = d;
                return true;
            case PlcWrite::Unit::kToolHolderAxisB:
            case PlcWrite::Unit::kToolHolderAxisC: {
                // The objects' ranges (bus 1320 Index 5, 6): B on a board axis, C also none.
                const bool b = w.unit == PlcWrite::Unit::kToolHolderAxisB;
                const double lowest = b ? 0.0 : static_cast<double>(objif::map::tempcomp::kNoHeadAxis);
                if (d != std::floor(d) || d < lowest || d > 7.0)
                    return fail(col, b ? "tool_holder_axis_b takes a board axis 0..7"
                                       : "tool_holder_axis_c takes a board axis 0..7, or -1 "
                                         "(no C axis)");
                w.value = d;
                return true;
            }
            case PlcWrite::Unit::kTempRampVelocity:
                if (!(d >= objif::map::tempcomp::kMinRampVelocity &&
                      d <= objif::map::tempcomp::kMaxRampVelocity))
                    return fail(col, fmt::format("temp_ramp_velocity (mm/s) takes {:g}..{:g}",
                                                 objif::map::tempcomp::kMinRampVelocity,
                                                 objif::map::tempcomp::kMaxRampVelocity));
                w.value = d;
                return true;
            case PlcWrite::Unit::kTempCompType:
                if (d != std::floor(d) || d < 0.0 || d > 255.0)
                    return fail(col, "temp_comp_type[i] (MD 32750) takes a whole number 0..255 "
                                     "(bit 2, 4: the axis takes the vector)");
                w.value = d;
                return true;
            case PlcWrite::Unit::kOtcRadiusOffset:
            case PlcWrite::Unit::kOtcOffset:
                break;
        }
        if (d != static_cast<double>(static_cast<std::int64_t>(d)) ||
            d < static_cast<double>(std::numeric_limits<std::int32_t>::min()) ||
            d > static_cast<double>(std::numeric_limits<std::int32_t>::max()))
            return fail(col, "the value must be a whole number in the DINT range (0.1 um)");
        if (w.field == PlcWrite::Field::kEnable && d != 0.0 && d != 1.0) return fail(col, flag_error);
        w.value = d;
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
    switch (w.unit) {
        case PlcWrite::Unit::kOtcRadiusOffset:
            return fmt::format("otc_radius_offset.{}", field);
        case PlcWrite::Unit::kOtcOffset:
            return fmt::format("otc_offset[{}].{}", w.index, field);
        case PlcWrite::Unit::kToolTempComp:
            return fmt::format("tool_temp_comp[{}]", w.index);
        case PlcWrite::Unit::kToolTempCompOn:
            return "tool_temp_comp_on";
        case PlcWrite::Unit::kTempCompType:
            return fmt::format("temp_comp_type[{}]", w.index);
        case PlcWrite::Unit::kToolHolder:
            return "tool_holder";
        case PlcWrite::Unit::kToolHolderAxisB:
            return "tool_holder_axis_b";
        case PlcWrite::Unit::kToolHolderAxisC:
            return "tool_holder_axis_c";
        case PlcWrite::Unit::kTempRampVelocity:
            return "temp_ramp_velocity";
    }
    return "?";
}

nc::Result<PlcScript> parse_plc_script(std::string_view text, std::string_view file) {
    PlcScript s;
    s.file_ = std::string(file);
    // Lines as the NC front end reads them (apci::nc::LineSource: the line ends, the length
    // bound kMaxPlcLineLength, a byte-order mark at the start).
    nc::LineSource source = nc::LineSource::from_text(text, std::string(file));
    std::string_view line;
    Diagnostic err;
    for (;;) {
        const nc::LineSource::Read r = source.next(line, err);
        if (r == nc::LineSource::Read::kError) return err;
        if (r == nc::LineSource::Read::kEnd) break;
        Diagnostic bad;
        PlcWrite w;
        bool empty = false;
        if (!LineParser(line, source.line_number(), file, bad).parse(w, empty)) return bad;
        if (!empty) (w.when == PlcWrite::When::kCycle ? s.cycle_ : s.block_).push_back(w);
    }
    std::stable_sort(s.cycle_.begin(), s.cycle_.end(),
                     [](const PlcWrite& a, const PlcWrite& b) { return a.at < b.at; });
    return s;
}

nc::Result<PlcScript> load_plc_script(const std::string& path) {
    const auto io_error = [&](std::string message) {
        Diagnostic d;
        d.kind = ErrorKind::kIo;
        d.file = path;
        d.message = std::move(message);
        return d;
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return io_error(fmt::format("cannot open: {}", std::strerror(errno)));
    std::string text;
    int error = 0;
    const BoundedRead read = read_bounded(fd, kMaxPlcScriptBytes, text, error);
    ::close(fd);
    if (read == BoundedRead::kTooLarge)
        return io_error(
            fmt::format("larger than {} MiB: a PLC script is read whole before the "
                        "run (one write a line)",
                        kMaxPlcScriptBytes >> 20));
    if (read == BoundedRead::kError)
        return io_error(fmt::format("read error: {}", std::strerror(error)));
    return parse_plc_script(text, path);
}

}  // namespace apci::run
