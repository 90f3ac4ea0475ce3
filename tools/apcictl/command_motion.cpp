// SPDX-License-Identifier: MIT
// The motion commands (docs/apcictl.md, docs/motion.md), mostly for scripts,
// where one board session carries the spooler and the clock from line to line:
//   spool G01 N10 X10 Y0 F600          a profile: G00..G03, words as in DIN 66025
//   spool G03 N11 X0 Y10 I0 J0 F600    arcs: I, J = centre on the arc's axes (absolute)
//   direct JA X5 Y5 [F1000]            jog absolute; `direct JS` stops every axis
//   ssf XY 2001                        SSF command to axes X and Y
//   step 1000 | step --idle            advance the interpolation clock
// Axis letters name board axes: X Y Z A B C U V = 0..7.
#include <fmt/format.h>

#include <array>
#include <cctype>
#include <cstdint>
#include <string>
#include <vector>

#include "apci/run/csv_writer.h"
#include "arguments.h"
#include "command.h"
#include "value_text.h"

namespace apcictl {
namespace {

// The board's axis letters, the same as the columns of `run --csv`.
constexpr std::array<char, APCI_AXIS_COUNT> kAxisLetters = apci::run::kBoardAxisLetters;

int axis_of(char letter) {
    const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(letter)));
    for (std::size_t i = 0; i < kAxisLetters.size(); ++i)
        if (kAxisLetters[i] == up) return static_cast<int>(i);
    return -1;
}

std::string joined(const std::vector<std::string>& words) {
    return fmt::format("{}", fmt::join(words, " "));
}

// The board's last error without the C function's own prefix ("spool G01 N1: ").
std::string board_says(apci::Board& board) {
    std::string text = apci::run::board_words(board);
    const auto colon = text.find(": ");
    return colon == std::string::npos ? text : text.substr(colon + 2);
}

// Address words: one letter and a number ("X10", "F600", "N5"), each letter once.
struct Words {
    std::array<bool, APCI_AXIS_COUNT> named{};
    std::array<double, APCI_AXIS_COUNT> target{};
    bool has_tag = false, has_feed = false, has_i = false, has_j = false;
    std::uint32_t tag = 0;
    double feed = 0.0, i = 0.0, j = 0.0;

    // `allowed`: the letters besides the axes this command takes.
    std::string parse(const std::vector<std::string>& words, std::string_view allowed) {
        std::string seen;
        for (const auto& w : words) {
            if (w.size() < 2) return fmt::format("'{}' is not a letter followed by a number", w);
            const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(w[0])));
            const std::string_view number(w.data() + 1, w.size() - 1);
            if (seen.find(letter) != std::string::npos)
                return fmt::format("'{}' is given twice", letter);
            seen += letter;
            const int axis = axis_of(letter);
            if (axis < 0 && allowed.find(letter) == std::string_view::npos)
                return fmt::format("'{}': unknown word (axes {}; also {})", w,
                                   std::string(kAxisLetters.begin(), kAxisLetters.end()), allowed);
            if (letter == 'N') {
                std::int32_t n = 0;
                if (!parse_int32(number, n) || n < 0)
                    return fmt::format("'{}': N needs a block number in 0..2147483647", w);
                has_tag = true;
                tag = static_cast<std::uint32_t>(n);
                continue;
            }
            double v = 0.0;
            if (!parse_double(number, v))
                return fmt::format("'{}': '{}' is not a number", w, number);
            if (axis >= 0) {
                named[static_cast<std::size_t>(axis)] = true;
                target[static_cast<std::size_t>(axis)] = v;
            } else if (letter == 'F') {
                has_feed = true;
                feed = v;
            } else if (letter == 'I') {
                has_i = true;
                i = v;
            } else if (letter == 'J') {
                has_j = true;
                j = v;
            }
        }
        return {};
    }
    std::uint8_t mask() const {
        std::uint8_t m = 0;
        for (std::size_t a = 0; a < named.size(); ++a)
            if (named[a]) m = static_cast<std::uint8_t>(m | (1u << a));
        return m;
    }
};

// "XY" -> axes 0 and 1.
bool axes_of(std::string_view letters, std::uint8_t& mask) {
    mask = 0;
    if (letters.empty()) return false;
    for (char c : letters) {
        const int a = axis_of(c);
        if (a < 0 || (mask & (1u << a)) != 0) return false;
        mask = static_cast<std::uint8_t>(mask | (1u << a));
    }
    return true;
}

// ---- spool

class SpoolCommand final : public Command {
  public:
    void declare(CLI::App& app) override {
        app.add_option("KIND", kind_text_,
                       "G00, G01, G02 or G03 (G0..G3), or TRAVERSE (a G00 the TC module "
                       "compensates)")
            ->required();
        app.add_option("WORDS", words_text_,
                       "N<block> F<feed, units/min> axis targets X Y Z A B C U V (axes 0..7); "
                       "arcs: I J = centre on the arc's first and second axis (absolute)");
        app.add_option("--arc-axes", arc_axes_text_,
                       "The two axes an arc is named in, first then second (default XY)");
        app.footer(
            "Spools one profile. Prints nothing on success. A TC error names the group, "
            "its ERROR bits and the block; Busy means the spooler is full: step, then "
            "spool again.");
    }

    Outcome prepare() override {
        std::string k = kind_text_;
        for (char& c : k) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        if (k == "G0" || k == "G00") {
            profile_.kind = APCI_PROFILE_RAPID;
        } else if (k == "G1" || k == "G01") {
            profile_.kind = APCI_PROFILE_LINE;
        } else if (k == "G2" || k == "G02") {
            profile_.kind = APCI_PROFILE_ARC_CW;
        } else if (k == "G3" || k == "G03") {
            profile_.kind = APCI_PROFILE_ARC_CCW;
        } else if (k == "TRAVERSE") {
            profile_.kind = APCI_PROFILE_TRAVERSE;
        } else {
            return usage(
                fmt::format("KIND '{}' is not G00, G01, G02, G03 or TRAVERSE", kind_text_));
        }
        const bool arc =
            profile_.kind == APCI_PROFILE_ARC_CW || profile_.kind == APCI_PROFILE_ARC_CCW;
        Words w;
        if (std::string why = w.parse(words_text_, arc ? "NFIJ" : "NF"); !why.empty())
            return usage(why);
        if (arc && !(w.has_i && w.has_j)) return usage("an arc needs its centre: I and J");
        std::uint8_t plane = 0;
        if (!axes_of(arc_axes_text_, plane) || arc_axes_text_.size() != 2)
            return usage(
                fmt::format("--arc-axes '{}' is not two different axis letters", arc_axes_text_));
        profile_.axes = w.mask();
        profile_.tag = w.tag;
        profile_.feed = w.feed;
        for (std::size_t a = 0; a < w.target.size(); ++a) profile_.target[a] = w.target[a];
        profile_.arc_axes[0] = static_cast<std::uint8_t>(axis_of(arc_axes_text_[0]));
        profile_.arc_axes[1] = static_cast<std::uint8_t>(axis_of(arc_axes_text_[1]));
        profile_.center[0] = w.i;
        profile_.center[1] = w.j;
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        if (board->spool(profile_)) return Outcome::success();
        return Outcome::board_error(fmt::format("{}: {}", text(), board_says(*board)));
    }

  private:
    std::string text() const {
        std::string t = fmt::format("spool {}", kind_text_);
        if (!words_text_.empty()) t += " " + joined(words_text_);
        if (arc_axes_text_ != "XY") t += " --arc-axes " + arc_axes_text_;
        return t;
    }
    Outcome usage(std::string why) const {
        return Outcome::usage_error(fmt::format("{}: {}", text(), why));
    }

    std::string kind_text_;
    std::vector<std::string> words_text_;
    std::string arc_axes_text_ = "XY";
    apci_profile profile_{};
};

// ---- direct

class DirectCommand final : public Command {
  public:
    void declare(CLI::App& app) override {
        app.add_option("CODE", code_text_, "JA (jog absolute) or JS (jog stop)")->required();
        app.add_option("WORDS", words_text_,
                       "JA: axis targets X Y Z A B C U V, F<feed> (0: rapid)");
        app.footer(
            "Discards the spooler and the held profile first ([APCI-TC] section 1), "
            "then JA moves the named axes, JS stops every axis. Prints nothing "
            "on success.");
    }

    Outcome prepare() override {
        std::string c = code_text_;
        for (char& ch : c) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
        if (c == "JA") {
            command_.code = APCI_DIRECT_JA;
        } else if (c == "JS") {
            command_.code = APCI_DIRECT_JS;
            if (!words_text_.empty()) return usage("JS takes no words: it stops every axis");
        } else {
            return usage(fmt::format("CODE '{}' is not JA or JS", code_text_));
        }
        Words w;
        if (std::string why = w.parse(words_text_, "F"); !why.empty()) return usage(why);
        if (command_.code == APCI_DIRECT_JA && w.mask() == 0)
            return usage("JA needs an axis target");
        command_.axes = w.mask();
        command_.feed = w.feed;
        for (std::size_t a = 0; a < w.target.size(); ++a) command_.target[a] = w.target[a];
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        if (board->direct(command_)) return Outcome::success();
        return Outcome::board_error(fmt::format("{}: {}", text(), board_says(*board)));
    }

  private:
    std::string text() const {
        return words_text_.empty() ? fmt::format("direct {}", code_text_)
                                   : fmt::format("direct {} {}", code_text_, joined(words_text_));
    }
    Outcome usage(std::string why) const {
        return Outcome::usage_error(fmt::format("{}: {}", text(), why));
    }

    std::string code_text_;
    std::vector<std::string> words_text_;
    apci_direct_command command_{};
};

// ---- ssf

class SsfCommand final : public Command {
  public:
    void declare(CLI::App& app) override {
        app.add_option("AXES", axes_text_, "Axis letters, e.g. XY (X Y Z A B C U V = axes 0..7)")
            ->required();
        app.add_option("COMMAND", command_text_,
                       "SSF command number (2001: release the held profile)")
            ->required();
        app.footer("Prints nothing on success.");
    }

    Outcome prepare() override {
        if (!axes_of(axes_text_, axes_))
            return usage(fmt::format("AXES '{}' is not a set of axis letters", axes_text_));
        if (std::string why = parse_int32_argument("COMMAND", command_text_, command_);
            !why.empty())
            return usage(why);
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        if (board->ssf(axes_, command_)) return Outcome::success();
        return Outcome::board_error(fmt::format("{}: {}", text(), board_says(*board)));
    }

  private:
    std::string text() const { return fmt::format("ssf {} {}", axes_text_, command_text_); }
    Outcome usage(std::string why) const {
        return Outcome::usage_error(fmt::format("{}: {}", text(), why));
    }

    std::string axes_text_, command_text_;
    std::uint8_t axes_ = 0;
    std::int32_t command_ = 0;
};

// ---- step

class StepCommand final : public Command {
  public:
    // The most cycles one step may ask for (at the default 1 ms cycle, 11.6 days of board time):
    // a mistyped count must not hold a shared daemon's clock for hours.
    static constexpr std::int64_t kMaxCycles = 1'000'000'000;

    void declare(CLI::App& app) override {
        auto* cycles =
            app.add_option("CYCLES", cycles_text_,
                           fmt::format("Interpolation cycles to advance (1..{})", kMaxCycles))
                ->type_name("UINT");
        auto* idle =
            app.add_flag("--idle", idle_, "Advance until nothing moves (at most --max cycles)");
        app.add_option(
               "--max", max_text_,
               fmt::format("With --idle: the most cycles to run (1..{0}, default {0})", kMaxCycles))
            ->type_name("UINT");
        cycles->excludes(idle);
        app.footer(
            "Prints one line: 'cycle NOW (+RAN) fill F/C idle|moving|held X.. Y.. ...' "
            "with the axis positions after the step.");
    }

    Outcome prepare() override {
        if (!idle_ && cycles_text_.empty())
            return Outcome::usage_error("step: give CYCLES > 0 or --idle");
        std::int64_t value = 0;
        if (!idle_) {
            if (std::string why = parse_integer("CYCLES", cycles_text_, 1, kMaxCycles, value);
                !why.empty())
                return Outcome::usage_error(fmt::format("step {}: {}", cycles_text_, why));
            cycles_ = static_cast<std::uint64_t>(value);
        }
        if (!max_text_.empty()) {
            if (std::string why = parse_integer("--max", max_text_, 1, kMaxCycles, value);
                !why.empty())
                return Outcome::usage_error(fmt::format("step --max {}: {}", max_text_, why));
            max_ = static_cast<std::uint64_t>(value);
        }
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        const auto r = idle_ ? board->run_until_idle(max_) : board->step(cycles_);
        if (!r) return Outcome::board_error(fmt::format("{}: {}", text(), board_says(*board)));
        const apci_motion_status& s = r.value;
        const char* state = (s.flags & APCI_MOTION_HELD) != 0   ? "held"
                            : (s.flags & APCI_MOTION_IDLE) != 0 ? "idle"
                                                                : "moving";
        std::string line =
            fmt::format("cycle {} (+{}) fill {}/{} {}", s.now, s.ran, s.fill, s.capacity, state);
        for (std::size_t a = 0; a < kAxisLetters.size(); ++a)
            line += fmt::format(" {}{}", kAxisLetters[a], s.position[a]);
        fmt::print("{}\n", line);
        return Outcome::success();
    }

  private:
    std::string text() const {
        return idle_ ? fmt::format("step --idle --max {}", max_) : fmt::format("step {}", cycles_);
    }

    std::string cycles_text_, max_text_;
    std::uint64_t cycles_ = 0;
    bool idle_ = false;
    std::uint64_t max_ = kMaxCycles;
};

}  // namespace

std::unique_ptr<Command> make_spool_command() {
    return std::make_unique<SpoolCommand>();
}
std::unique_ptr<Command> make_direct_command() {
    return std::make_unique<DirectCommand>();
}
std::unique_ptr<Command> make_ssf_command() {
    return std::make_unique<SsfCommand>();
}
std::unique_ptr<Command> make_step_command() {
    return std::make_unique<StepCommand>();
}

}  // namespace apcictl
