// SPDX-License-Identifier: MIT
// `read OBJECT` and `write OBJECT VALUE`, OBJECT a name (tc.group[1].radius) or BUS DEV IDX
// SUB: the type follows the object. Objects hold int32 or double; by name the map says which;
// by numbers the board answers TypeMismatch to the wrong accessor without touching state, so
// asking is safe.
#include <fmt/format.h>

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "arguments.h"
#include "command.h"
#include "object_name.h"
#include "objif/map/comp3d_refusal.h"
#include "objif/map/object_map.h"
#include "objif/map/otc_errors.h"
#include "value_text.h"

namespace apcictl {
namespace {

// The object of `read` and `write`: a dotted name (objif/names.h), or BUS DEV IDX SUB.
struct ObjectArgs {
    // The positionals as typed: NAME|BUS, DEV, IDX, SUB and, for `write`, VALUE. By name the
    // value lands in DEV: the words are taken apart in parse().
    std::array<std::string, 5> slots;
    std::vector<std::string> words;  // the object's words as typed
    objif::Address address;
    const objif::NamedObject* named = nullptr;  // given by name: its type is known

    void declare(CLI::App& app, bool with_value) {
        app.add_option("NAME|BUS", slots[0],
                       "The object's dotted name (tc.group[1].radius, docs/object-map.md "
                       "section 8), or its BusNumber (1300: TC module) followed by DEV IDX SUB")
            ->type_name("TEXT|INT")
            ->required();
        app.add_option("DEV", slots[1], "DeviceNumber")->type_name("INT");
        app.add_option("IDX", slots[2], "Index")->type_name("INT");
        app.add_option("SUB", slots[3], "SubIndex")->type_name("INT");
        if (with_value)
            app.add_option("VALUE", slots[4],
                           "Value: int32 (5, -3, 0x1F) or double (2.5, 1e-3); after a NAME it "
                           "follows the name");
    }
    // The positional words typed, in order.
    std::vector<std::string> typed() const {
        std::vector<std::string> out;
        for (const std::string& w : slots)
            if (!w.empty()) out.push_back(w);
        return out;
    }
    // Takes the object (and, for `write`, VALUE: the word after it) from `typed`. Empty, else
    // why not; an unknown name sets `unknown` (its error names no command: "unknown object").
    std::string parse(std::vector<std::string> typed, std::string* value, bool& unknown) {
        static constexpr std::array<const char*, 5> kWords{"BUS", "DEV", "IDX", "SUB", "VALUE"};
        unknown = false;
        if (typed.empty()) return "NAME|BUS is required";
        const std::size_t object_words = is_object_name(typed.front()) ? 1 : 4;
        const std::size_t needed = object_words + (value != nullptr ? 1 : 0);
        if (typed.size() < needed)
            return fmt::format("{} is required",
                               object_words == 1 ? "VALUE" : kWords[typed.size()]);
        if (typed.size() > needed) {
            const std::vector<std::string> extra(
                typed.begin() + static_cast<std::ptrdiff_t>(needed), typed.end());
            return fmt::format("The following argument{} not expected: {}",
                               extra.size() == 1 ? " was" : "s were", fmt::join(extra, " "));
        }
        if (value != nullptr) *value = typed.back();
        words.assign(typed.begin(), typed.begin() + static_cast<std::ptrdiff_t>(object_words));
        if (object_words == 1) {
            std::string error;
            named = resolve_object_name(words.front(), error);
            if (named == nullptr) {
                unknown = true;
                return error;
            }
            address = named->address;
            return {};
        }
        for (auto [i, target] : {std::pair{0, &address.bus}, std::pair{1, &address.device},
                                 std::pair{2, &address.index}, std::pair{3, &address.subindex}}) {
            const auto at = static_cast<std::size_t>(i);
            if (std::string why = parse_int32_argument(kWords[at], words[at], *target);
                !why.empty())
                return why;
        }
        return {};
    }
    apci::ObjectDescriptor descriptor() const {
        return apci::object(address.bus, address.device, address.index, address.subindex);
    }
    std::string label() const { return named != nullptr ? named->name : address_text(address); }
};

struct TypeFlags {
    bool force_int = false;
    bool force_double = false;

    void declare(CLI::App& app, std::string_view verb) {
        auto* i = app.add_flag("--int", force_int, fmt::format("{} as int32, whatever the object", verb));
        auto* d = app.add_flag("--double", force_double, fmt::format("{} as double, whatever the object", verb));
        i->excludes(d);
    }
    std::string text() const { return force_int ? " --int" : (force_double ? " --double" : ""); }
    // A forced type against a named object's own: why they contradict, else empty.
    std::string contradiction(const objif::NamedObject* named) const {
        if (named == nullptr || (!force_int && !force_double)) return {};
        const bool is_int = named->info->type == objif::ValueType::kInt32;
        if (is_int == force_int) return {};
        return fmt::format("{} contradicts the object: {} holds {}", text().substr(1), named->name,
                           is_int ? "an int32" : "a double");
    }
};

class ReadCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        object_.declare(app, false);
        type_.declare(app, "Read");
        app.footer(
            "Prints the value. By name the type is the object's (a contradicting --int or "
            "--double is an error); by numbers, without --int/--double, int32 is tried "
            "first, then double.");
    }

    Outcome prepare() override {
        typed_ = object_.typed();
        bool unknown = false;
        std::string why = object_.parse(typed_, nullptr, unknown);
        if (unknown) return Outcome::usage_error(why);
        if (why.empty()) why = type_.contradiction(object_.named);
        if (!why.empty()) return Outcome::usage_error(fmt::format("{}: {}", command_text(), why));
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        auto o = object_.descriptor();
        const bool named_double =
            object_.named != nullptr && object_.named->info->type == objif::ValueType::kDouble;
        if (!type_.force_double && !named_double) {
            const auto r = board->read_int(o);
            if (r) {
                fmt::print("{}\n", r.value);
                return Outcome::success();
            }
            if (type_.force_int || object_.named != nullptr || r.status != APCI_TYPE_MISMATCH)
                return failed(*board, r.status);
        }
        const auto r = board->read_double(o);
        if (!r) return failed(*board, r.status);
        fmt::print("{}\n", r.value);
        return Outcome::success();
    }

    std::optional<objif::Address> object() const override { return object_.address; }

  private:
    std::string command_text() const {
        return fmt::format("read{} {}", type_.text(), fmt::join(typed_, " "));
    }
    Outcome failed(const apci::Board& board, apci::Status s) const {
        return Outcome::board_error(
            fmt::format("{}: {}", command_text(), describe_failure(board, s)));
    }

    ObjectArgs object_;
    TypeFlags type_;
    std::vector<std::string> typed_;  // the words as typed
};

class WriteCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        object_.declare(app, true);
        type_.declare(app, "Write");
        app.footer(
            "The value's type follows the object: an integer written to a double object "
            "is written as that double; a value with a fraction (2.5) written to an int "
            "object is an error (by name found before anything is written). A "
            "contradicting --int or --double with a name is an error. Prints nothing on "
            "success.");
    }

    Outcome prepare() override {
        typed_ = object_.typed();
        bool unknown = false;
        std::string why = object_.parse(typed_, &value_text_, unknown);
        if (unknown) return Outcome::usage_error(why);
        if (why.empty()) why = type_.contradiction(object_.named);
        if (!why.empty()) return usage(why);
        is_int_ = parse_int32(value_text_, int_value_);
        const bool is_number = parse_double(value_text_, double_value_);
        if (type_.force_int && !is_int_)
            return usage(fmt::format("VALUE '{}' is not an int32 (--int)", value_text_));
        if (!is_number && !is_int_)
            return usage(fmt::format("VALUE '{}' is not a number", value_text_));
        if (object_.named != nullptr && object_.named->info->type == objif::ValueType::kInt32 &&
            !is_int_)
            return usage(fmt::format("VALUE '{}' is not an int32 ({} holds an int32)", value_text_,
                                     object_.named->name));
        if ((type_.force_double || named_double()) && is_int_) double_value_ = int_value_;
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        board_ = board;
        auto o = object_.descriptor();
        if (type_.force_int) return result(board->write_int(o, int_value_).status);
        if (type_.force_double || named_double())
            return result(board->write_double(o, double_value_).status);
        if (object_.named != nullptr) return result(board->write_int(o, int_value_).status);
        if (is_int_) {
            const auto r = board->write_int(o, int_value_);
            if (r.status != APCI_TYPE_MISMATCH) return result(r.status);
            // A double object: every int32 is exactly a double.
            return result(board->write_double(o, static_cast<double>(int_value_)).status);
        }
        const auto r = board->write_double(o, double_value_);
        if (r.status == APCI_TYPE_MISMATCH) {
            return Outcome::board_error(fmt::format(
                "{}: {}: object {} holds an int32, and {} is not an int32 value", command_text(),
                describe_failure(*board, r.status), object_.label(), value_text_));
        }
        return result(r.status);
    }

    std::optional<objif::Address> object() const override { return object_.address; }

  private:
    std::string command_text() const {
        return fmt::format("write{} {}", type_.text(), fmt::join(typed_, " "));
    }
    Outcome usage(std::string why) const {
        return Outcome::usage_error(fmt::format("{}: {}", command_text(), why));
    }
    Outcome result(apci::Status s) const {
        if (s == APCI_OK) return Outcome::success();
        // Described before tc_consequence reads the group's ERROR (a call of its own).
        const std::string failure = describe_failure(*board_, s);
        return Outcome::board_error(fmt::format("{}: {}{}{}", command_text(), failure,
                                                tc_consequence(s), last_error(s)));
    }

    // A module that records why it refused a write in its LastError (the OTC module, bus 1330,
    // objif/map/otc_errors.h; the 3D compensation, bus 1310, objif/map/comp3d_refusal.h): the
    // refusal names it, as the executor does (the status alone says only how).
    std::string last_error(apci::Status s) const {
        namespace otc = objif::map::otc;
        namespace c3 = objif::map::comp3d;
        if (board_ == nullptr || s == APCI_NO_SUCH_DEVICE || s == APCI_OBJECT_MISSING ||
            s == APCI_TYPE_MISMATCH)
            return {};
        // The module, where its LastError is, and the name and message of a value.
        const auto named = [&](std::string_view module, std::int32_t bus, std::int32_t device,
                               std::int32_t index, auto describe) -> std::string {
            auto o = apci::object(bus, device, index, 0);
            const auto e = board_->read_int(o);
            if (!e || e.value == 0) return {};
            const auto [name, message] = describe(e.value);
            return fmt::format("; the {} module's LastError ({} {} {} 0) reads {}: {} ({})", module,
                               bus, device, index, e.value, name, message);
        };
        if (object_.address.bus == otc::kBus)
            return named("OTC", otc::kBus, otc::kDevChannel, otc::kIdxLastError, [](int v) {
                const auto e = static_cast<otc::Error>(v);
                return std::pair{otc::error_name(e), otc::error_message(e)};
            });
        if (object_.address.bus == c3::kBus)
            return named("3D", c3::kBus, c3::kDevSettings, c3::kIdxLastError, [](int v) {
                const auto r = static_cast<c3::Refusal>(v);
                return std::pair{c3::refusal_name(r), c3::refusal_message(r)};
            });
        return {};
    }

    // A refused write to a TC group may have set the group's ERROR ([APCI-TC] Table 3: InitError
    // for STATUS = 1 on a group not initialised, and for the axes, WKZINDEX, Left or Right
    // while it runs): the refusal says so, and what to change.
    std::string tc_consequence(apci::Status s) const {
        namespace tc = objif::map::tc;
        if (object_.address.bus == tc::kBus && object_.address.device == tc::kDevInit &&
            object_.address.index == tc::kIdxReInit && s == APCI_WRONG_DEVICE_STATE)
            return "; ReInit while a contour is under way (a profile held, STATUS bit "
                   "ProfMarked) is not emulated: [APCI-TC] gives it for before a re-reference "
                   "and does not say what it does to a contour; end the contour first (STATUS = "
                   "0, or SSF 2001 to its axes), or write Reset (1300 0 14) to drop it";
        if (object_.address.bus != tc::kBus || object_.address.device != tc::kDevGroups ||
            board_ == nullptr)
            return {};
        auto error = apci::object(tc::kBus, tc::kDevGroups, object_.address.index, tc::kSubError);
        const auto bits = board_->read_int(error);
        if (!bits || bits.value == 0) return {};
        std::string names;
        for (int bit = 0; bit < 32; ++bit) {
            if ((static_cast<std::uint32_t>(bits.value) & (1u << bit)) == 0) continue;
            const char* name = apci_tc_error_bit_name(bit);
            names += names.empty() ? "" : ", ";
            names += name != nullptr ? name : fmt::format("bit {}", bit);
        }
        const std::string group = object_.address.index == tc::kActiveGroupIndex
                                      ? "the active group"
                                      : fmt::format("group {}", object_.address.index);
        std::string hint;
        if ((bits.value & 1) != 0) {
            if (object_.address.subindex == tc::kSubStatus)
                hint = "; STATUS = 1 needs the group initialised: XAxis, YAxis and ZAxis "
                       "distinct and on no axis of a running group, and Left or Right written "
                       "([APCI-TC] Table 3)";
            else if (object_.address.subindex == tc::kSubXAxis ||
                     object_.address.subindex == tc::kSubYAxis ||
                     object_.address.subindex == tc::kSubZAxis ||
                     object_.address.subindex == tc::kSubWkzIndex ||
                     object_.address.subindex == tc::kSubLeft ||
                     object_.address.subindex == tc::kSubRight)
                hint = "; this object changes only while the group is inactive: write STATUS = 0 "
                       "first ([APCI-TC] Table 3)";
        }
        return fmt::format("; {}'s ERROR now reads 0x{:02x} ({}){} (clear it: write {} {} {} {} 0)",
                           group, bits.value, names, hint, tc::kBus, tc::kDevGroups,
                           object_.address.index, tc::kSubError);
    }

    bool named_double() const {
        return object_.named != nullptr && object_.named->info->type == objif::ValueType::kDouble;
    }

    ObjectArgs object_;
    TypeFlags type_;
    std::vector<std::string> typed_;  // the words as typed: the object's, then VALUE
    apci::Board* board_ = nullptr;  // the board written to (its TC ERROR explains a refusal)
    std::string value_text_;
    bool is_int_ = false;
    std::int32_t int_value_ = 0;
    double double_value_ = 0.0;
};

}  // namespace

std::unique_ptr<Command> make_read_command() { return std::make_unique<ReadCommand>(); }
std::unique_ptr<Command> make_write_command() { return std::make_unique<WriteCommand>(); }

}  // namespace apcictl
