// SPDX-License-Identifier: MIT
// The general parser's ISG commands and assignments (block_parser.h): #OTC ([ISG-OTC] section
// 2.1), #KIN, #TRAFO, #HSC, $FOR and $ENDFOR (docs/design.md section 8), "Pn = .." and
// "V.G.WZ_AKT.WEAR_CONST = ..", each in a block of its own; loop_marker; and the names of
// #OTC's settings.
#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

#include "apci/nc/lexer.h"
#include "apci/nc/parser.h"
#include "block_parser.h"
#include "objif/enum_names.h"

namespace apci::nc {
namespace parser_detail {

namespace {

constexpr std::string_view kKnownIsg = "#OTC, #KIN, #TRAFO, #HSC, $FOR, $ENDFOR";

// An ISG command or an assignment, from where the block's parser found it to the end of the
// line.
class IsgParser : public LineParse {
  public:
    explicit IsgParser(const LineParse& at) : LineParse(at), b_(out_.block) {}

    bool assignment() {
        Assignment& a = out_.assignment;
        a = Assignment{};
        a.column = c_.column();
        if (to_upper(c_.peek()) == 'P') {
            c_.advance();
            const std::string_view digits = c_.scan_digits();
            const std::optional<std::uint64_t> v =
                whole_at_most(digits, static_cast<std::uint64_t>(kParameterCount - 1));
            if (!v) {
                return fail_here(ErrorKind::kValue, a.column,
                                 fmt::format("P parameter number P{} out of range 0..{}", digits,
                                             kParameterCount - 1));
            }
            const int n = static_cast<int>(*v);
            a.to_parameter = true;
            a.parameter = n;
        } else {
            ExpressionError e;
            if (!scan_variable(c_, a.variable, e)) return fail_here(e.kind, e.column, e.message);
            if (!variable_writable(a.variable)) {
                return fail_here(ErrorKind::kProgramRule, a.column,
                                 fmt::format("{} is read-only (only V.G.WZ_AKT.WEAR_CONST and "
                                             "$SC_TOOL_TEMP_COMP[i] are written by programs)",
                                             variable_name(a.variable)));
            }
            a.to_parameter = false;
        }
        c_.skip_blanks();
        if (c_.peek() != '=') {
            return fail_here(ErrorKind::kSyntax, c_.column(), "expected '=' in the assignment");
        }
        c_.advance();
        if (!expression(a.value)) return false;
        if (!a.to_parameter && a.variable.variable == NcVariable::kWearConst && a.value < 0.0) {
            return fail_here(ErrorKind::kValue, a.column,
                             "V.G.WZ_AKT.WEAR_CONST must not be negative (0.1 um/m, P-TOOL-00030)");
        }
        if (!a.to_parameter && a.variable.variable == NcVariable::kToolTempComp &&
            !(std::fabs(a.value) <= kToolTempCompLimit)) {
            return fail_here(ErrorKind::kValue, a.column,
                             fmt::format("{} = {} out of range: SD 42960 takes -{:g}..{:g} mm",
                                         variable_name(a.variable), a.value, kToolTempCompLimit,
                                         kToolTempCompLimit));
        }
        if (!end_of_command("the assignment")) return false;
        out_.kind = LineKind::kAssignment;
        return true;
    }

    bool isg_command() {
        IsgLine& isg = out_.isg;
        isg = IsgLine{};
        isg.column = c_.column();
        const char sigil = c_.peek();
        c_.advance();
        const std::string_view name = c_.scan_identifier();
        if (name.empty()) {
            return fail_here(ErrorKind::kSyntax, isg.column,
                             fmt::format("expected a command name after '{}'", sigil));
        }
        bool ok = false;
        if (sigil == '#' && keyword_is(name, "OTC")) {
            isg.kind = IsgKind::kOtc;
            ok = otc(isg.otc);
        } else if (sigil == '#' && keyword_is(name, "KIN")) {
            isg.kind = IsgKind::kKin;
            ok = kin(isg);
        } else if (sigil == '#' && keyword_is(name, "TRAFO")) {
            isg.kind = IsgKind::kTrafo;
            ok = on_off("#TRAFO", isg.on, /*optional=*/false) && end_of_command("#TRAFO ON|OFF");
        } else if (sigil == '#' && keyword_is(name, "HSC")) {
            isg.kind = IsgKind::kHsc;
            ok = hsc(isg);
        } else if (sigil == '$' && keyword_is(name, "FOR")) {
            isg.kind = IsgKind::kFor;
            ok = for_loop(isg.loop);
        } else if (sigil == '$' && keyword_is(name, "ENDFOR")) {
            isg.kind = IsgKind::kEndFor;
            ok = end_of_command("$ENDFOR");
        } else {
            return fail_here(ErrorKind::kUnsupported, isg.column,
                             fmt::format("ISG command '{}{}' is not supported (known: {})", sigil,
                                         name, kKnownIsg));
        }
        if (!ok) return false;
        out_.kind = LineKind::kIsg;
        return true;
    }

  private:
    // The rest of the line must be empty (blanks, comments).
    bool end_of_command(std::string_view what) {
        if (!skip_blanks_and_comments(c_, file_, line_, err_)) {
            err_.block = b_.block_number();
            return false;
        }
        if (!c_.at_end()) {
            return fail_here(ErrorKind::kSyntax, c_.column(),
                             fmt::format("unexpected {} after {}", describe_char(c_.peek()), what));
        }
        return true;
    }

    // ON or OFF at the cursor (after blanks); `optional`: neither is fine (value unchanged).
    bool on_off(std::string_view command, bool& on, bool optional, bool* seen = nullptr) {
        c_.skip_blanks();
        const std::size_t at = c_.offset();
        const std::uint32_t col = c_.column();
        const std::string_view word = c_.scan_identifier();
        if (keyword_is(word, "ON") || keyword_is(word, "OFF")) {
            on = keyword_is(word, "ON");
            if (seen != nullptr) *seen = true;
            return true;
        }
        if (optional) {
            c_ = LineCursor(c_.line());
            c_.advance(at);
            return true;
        }
        return fail_here(ErrorKind::kSyntax, col,
                         word.empty() ? fmt::format("expected ON or OFF after {}", command)
                                      : fmt::format("expected ON or OFF after {}, found '{}'",
                                                    command, word));
    }

    // "#OTC ON", "#OTC OFF", "#OTC ON [LENGTH]", "#OTC ON[RADIUS DISC]", "#OTC[RADIUS, AUTO]",
    // "#OTC ON [TOOL_DIR, DISC]": [ISG-OTC] writes all of these.
    bool otc(OtcCommand& cmd) {
        bool on = false, seen = false;
        if (!on_off("#OTC", on, /*optional=*/true, &seen)) return false;
        if (seen) cmd.on = on;
        c_.skip_blanks();
        if (c_.peek() == '[') {
            const std::uint32_t open = c_.column();
            c_.advance();
            if (!otc_parameters(cmd, open)) return false;
        } else if (!seen) {
            return fail_here(ErrorKind::kSyntax, c_.column(),
                             "expected ON, OFF or '[' after #OTC (#OTC ON | OFF [ RADIUS | LENGTH "
                             "| TOOL_DIR | SURF_NORM_DIR  DISC | CONT | AUTO  WEAR_CONST=.. | "
                             "WEAR_CONST_TOOL  ACC_WEIGHT=.. ])");
        }
        return end_of_command("#OTC");
    }

    bool otc_parameters(OtcCommand& cmd, std::uint32_t open) {
        for (;;) {
            c_.skip_blanks();
            if (c_.peek() == ',') {
                c_.advance();
                continue;
            }
            if (c_.peek() == ']') {
                c_.advance();
                return true;
            }
            if (c_.at_end() || c_.peek() == ';' || c_.peek() == '(') {
                return fail_here(ErrorKind::kSyntax, c_.column(),
                                 fmt::format("expected ']' to close the '[' in column {}", open));
            }
            const std::uint32_t col = c_.column();
            const std::string_view word = c_.scan_identifier();
            if (word.empty()) {
                return fail_here(ErrorKind::kSyntax, col,
                                 fmt::format("unexpected {} in #OTC [...]", describe_char(c_.peek())));
            }
            if (!otc_word(cmd, word, col)) return false;
        }
    }

    bool otc_conflict(std::uint32_t col, std::string_view a, std::string_view b) {
        return fail_here(ErrorKind::kConflict, col,
                         a == b ? fmt::format("{} appears twice in #OTC", a)
                                : fmt::format("{} and {} in one #OTC: both set the {}", a, b,
                                              a == "WEAR_CONST" || a == "WEAR_CONST_TOOL"
                                                  ? "wear constant"
                                                  : "same setting"));
    }

    bool otc_word(OtcCommand& cmd, std::string_view word, std::uint32_t col) {
        static constexpr std::pair<std::string_view, OtcType> kTypes[] = {
            {"RADIUS", OtcType::kRadius},
            {"LENGTH", OtcType::kLength},
            {"TOOL_DIR", OtcType::kToolDir},
            {"SURF_NORM_DIR", OtcType::kSurfNormDir}};
        static constexpr std::pair<std::string_view, OtcMode> kModes[] = {
            {"CONT", OtcMode::kCont}, {"DISC", OtcMode::kDisc}, {"AUTO", OtcMode::kAuto}};
        // A keyword of `names` sets `slot`, once per #OTC (`what` it sets, for the conflict);
        // nothing when `word` is none of them.
        auto set_once = [&](const auto& names, auto& slot, std::string_view what,
                            auto name_of) -> std::optional<bool> {
            for (const auto& [name, value] : names) {
                if (!keyword_is(word, name)) continue;
                if (slot) {
                    return fail_here(ErrorKind::kConflict, col,
                                     fmt::format("{} and {} in one #OTC: both set the {}",
                                                 name_of(*slot), name, what));
                }
                slot = value;
                return true;
            }
            return std::nullopt;
        };
        std::optional<bool> set = set_once(kTypes, cmd.type, "processing type", otc_type_name);
        if (!set) set = set_once(kModes, cmd.mode, "mode", otc_mode_name);
        if (set) return *set;
        // The wear constant chosen already, for a conflict.
        const std::string_view chosen =
            cmd.wear_const == WearConstChoice::kTool ? "WEAR_CONST_TOOL" : "WEAR_CONST";
        if (keyword_is(word, "WEAR_CONST_TOOL")) {
            if (cmd.wear_const != WearConstChoice::kUnchanged)
                return otc_conflict(col, chosen, "WEAR_CONST_TOOL");
            cmd.wear_const = WearConstChoice::kTool;
            return true;
        }
        if (keyword_is(word, "WEAR_CONST")) {
            if (cmd.wear_const != WearConstChoice::kUnchanged)
                return otc_conflict(col, chosen, "WEAR_CONST");
            double v = 0.0;
            if (!equals_value("WEAR_CONST", v)) return false;
            // [ISG-OTC] section 3.2, P-TOOL-00030: 0 <= grinding_wear_const.
            if (v < 0.0) {
                return fail_here(ErrorKind::kValue, col,
                                 fmt::format("WEAR_CONST={} must not be negative (0.1 um/m)", v));
            }
            cmd.wear_const = WearConstChoice::kProgrammed;
            cmd.wear_const_value = v;
            return true;
        }
        if (keyword_is(word, "ACC_WEIGHT")) {
            if (cmd.acc_weight) return otc_conflict(col, "ACC_WEIGHT", "ACC_WEIGHT");
            double v = 0.0;
            if (!equals_value("ACC_WEIGHT", v)) return false;
            // [ISG-OTC] section 2.1: "Beschleunigungsgewichtung in Prozent [1;100]".
            if (v < 1.0 || v > 100.0 || v != std::floor(v)) {
                return fail_here(ErrorKind::kValue, col,
                                 fmt::format("ACC_WEIGHT={} out of range: a whole percentage "
                                             "1..100",
                                             v));
            }
            cmd.acc_weight = static_cast<int>(v);
            return true;
        }
        return fail_here(ErrorKind::kUnknownWord, col,
                         fmt::format("unknown #OTC parameter '{}' (known: RADIUS LENGTH TOOL_DIR "
                                     "SURF_NORM_DIR DISC CONT AUTO WEAR_CONST= WEAR_CONST_TOOL "
                                     "ACC_WEIGHT=)",
                                     word));
    }

    bool equals_value(std::string_view name, double& v) {
        c_.skip_blanks();
        if (c_.peek() != '=') {
            return fail_here(ErrorKind::kSyntax, c_.column(), fmt::format("expected '=' after {}", name));
        }
        c_.advance();
        return expression(v);
    }

    // #KIN ID[n] ([ISG-OTC] sections 2.4 and 2.5: "#KIN ID[4]").
    bool kin(IsgLine& isg) {
        c_.skip_blanks();
        const std::uint32_t col = c_.column();
        if (!keyword_is(c_.scan_identifier(), "ID")) {
            return fail_here(ErrorKind::kSyntax, col, "expected ID[n] after #KIN");
        }
        c_.skip_blanks();
        if (c_.peek() != '[') return fail_here(ErrorKind::kSyntax, c_.column(), "expected '[' after #KIN ID");
        double v = 0.0;
        if (!bracketed(v)) return false;
        if (v != std::floor(v) || v < 0.0 || v > 1e6) {
            return fail_here(ErrorKind::kValue, col, fmt::format("#KIN ID[{}]: expected a whole number", v));
        }
        isg.kinematics = static_cast<int>(v);
        return end_of_command("#KIN ID[..]");
    }

    // #HSC ON [..] / OFF / [..]: accepted (its text is not interpreted; the executor reports it
    // as not emulated). The brackets must close.
    bool hsc(IsgLine& isg) {
        bool seen = false;
        if (!on_off("#HSC", isg.on, /*optional=*/true, &seen)) return false;
        c_.skip_blanks();
        if (c_.peek() == '[') {
            const std::uint32_t open = c_.column();
            int depth = 0;
            do {
                if (c_.peek() == '[') ++depth;
                if (c_.peek() == ']') --depth;
                c_.advance();
            } while (depth > 0 && !c_.at_end());
            if (depth > 0) {
                return fail_here(ErrorKind::kSyntax, open,
                                 "the '[' of #HSC is not closed before the end of the line");
            }
        } else if (!seen) {
            return fail_here(ErrorKind::kSyntax, c_.column(), "expected ON, OFF or '[' after #HSC");
        }
        return end_of_command("#HSC");
    }

    // $FOR Pn = start, end, step
    bool for_loop(ForLoop& loop) {
        c_.skip_blanks();
        const std::uint32_t col = c_.column();
        if (to_upper(c_.peek()) != 'P' || !is_digit(c_.peek_at(1))) {
            return fail_here(ErrorKind::kSyntax, col, "expected a P parameter after $FOR ($FOR P1 = 0, 10, 1)");
        }
        c_.advance();
        const std::string_view digits = c_.scan_digits();
        const std::optional<std::uint64_t> v =
            whole_at_most(digits, static_cast<std::uint64_t>(kParameterCount - 1));
        if (!v) {
            return fail_here(ErrorKind::kValue, col,
                             fmt::format("P parameter number P{} out of range 0..{}", digits,
                                         kParameterCount - 1));
        }
        const int n = static_cast<int>(*v);
        loop.parameter = n;
        c_.skip_blanks();
        if (c_.peek() != '=') return fail_here(ErrorKind::kSyntax, c_.column(), "expected '=' after the $FOR parameter");
        c_.advance();
        if (!expression(loop.start)) return false;
        for (double* bound : {&loop.end, &loop.step}) {
            c_.skip_blanks();
            if (c_.peek() != ',') {
                return fail_here(ErrorKind::kSyntax, c_.column(),
                                 "expected ',' in $FOR Pn = start, end, step");
            }
            c_.advance();
            if (!expression(*bound)) return false;
        }
        if (loop.step == 0.0) {
            return fail_here(ErrorKind::kValue, col, "the $FOR step must not be 0 (the loop would never end)");
        }
        return end_of_command("$FOR Pn = start, end, step");
    }

    Block& b_;
};

}  // namespace

bool is_assignment_start(const LineCursor& c) {
    const char ch = to_upper(c.peek());
    if (ch == 'V' && c.peek_at(1) == '.') return true;
    if (at_setting_data(c)) return true;
    if (ch != 'P' || !is_digit(c.peek_at(1))) return false;
    std::size_t i = 1;
    while (is_digit(c.peek_at(i))) ++i;
    while (c.peek_at(i) == ' ' || c.peek_at(i) == '\t') ++i;
    return c.peek_at(i) == '=';
}

bool parse_isg_command(const LineParse& at) {
    return IsgParser(at).isg_command();
}

bool parse_assignment(const LineParse& at) {
    return IsgParser(at).assignment();
}

}  // namespace parser_detail

using parser_detail::keyword_is;

LoopMarker loop_marker(std::string_view line) noexcept {
    LineCursor c(line);
    c.skip_blanks();
    if (to_upper(c.peek()) == 'N' && is_digit(c.peek_at(1))) {
        c.advance();
        while (is_digit(c.peek())) c.advance();
        c.skip_blanks();
    }
    if (c.peek() != '$') return LoopMarker::kNone;
    c.advance();
    const std::string_view name = c.scan_identifier();
    if (keyword_is(name, "FOR")) return LoopMarker::kFor;
    if (keyword_is(name, "ENDFOR")) return LoopMarker::kEndFor;
    return LoopMarker::kNone;
}

std::string_view otc_type_name(OtcType t) noexcept {
    static constexpr auto kNames = objif::enum_names<OtcType::kRadius, OtcType::kSurfNormDir>(
        {"RADIUS", "LENGTH", "TOOL_DIR", "SURF_NORM_DIR"}, "?");
    return kNames(t);
}

std::string_view otc_mode_name(OtcMode m) noexcept {
    static constexpr auto kNames =
        objif::enum_names<OtcMode::kCont, OtcMode::kAuto>({"CONT", "DISC", "AUTO"}, "?");
    return kNames(m);
}

}  // namespace apci::nc
