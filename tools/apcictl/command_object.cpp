// SPDX-License-Identifier: MIT
// `read BUS DEV IDX SUB` and `write BUS DEV IDX SUB VALUE`: the type follows
// the object. Objects hold int32 or double; the board answers TypeMismatch
// to the wrong accessor without touching state, so asking is safe.
#include <fmt/format.h>

#include <string>
#include <tuple>

#include "arguments.h"
#include "command.h"
#include "objif/map/object_map.h"
#include "value_text.h"

namespace apcictl {
namespace {

struct ObjectArgs {
    std::int32_t bus = 0, device = 0, index = 0, subindex = 0;
    std::string bus_text, device_text, index_text, subindex_text;  // as typed

    void declare(CLI::App& app) {
        app.add_option("BUS", bus_text, "BusNumber (1300: TC module)")
            ->type_name("INT")
            ->required();
        app.add_option("DEV", device_text, "DeviceNumber")->type_name("INT")->required();
        app.add_option("IDX", index_text, "Index")->type_name("INT")->required();
        app.add_option("SUB", subindex_text, "SubIndex")->type_name("INT")->required();
    }
    // Each number an int32 (decimal, or hexadecimal after 0x): empty, else why not.
    std::string parse() {
        for (auto [name, text, value] :
             {std::tuple{"BUS", &bus_text, &bus}, std::tuple{"DEV", &device_text, &device},
              std::tuple{"IDX", &index_text, &index},
              std::tuple{"SUB", &subindex_text, &subindex}}) {
            if (std::string why = parse_int32_argument(name, *text, *value); !why.empty())
                return why;
        }
        return {};
    }
    apci::ObjectDescriptor descriptor() const { return apci::object(bus, device, index, subindex); }
    std::string text() const {
        return fmt::format("{} {} {} {}", bus_text, device_text, index_text, subindex_text);
    }
    std::string address() const { return fmt::format("{}/{}/{}/{}", bus, device, index, subindex); }
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
};

class ReadCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        object_.declare(app);
        type_.declare(app, "Read");
        app.footer("Prints the value. Without --int/--double the type follows the object: "
                   "int32 is tried first, then double.");
    }

    Outcome prepare() override {
        if (std::string why = object_.parse(); !why.empty())
            return Outcome::usage_error(
                fmt::format("read{} {}: {}", type_.text(), object_.text(), why));
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        auto o = object_.descriptor();
        if (!type_.force_double) {
            const auto r = board->read_int(o);
            if (r) {
                fmt::print("{}\n", r.value);
                return Outcome::success();
            }
            if (type_.force_int || r.status != APCI_TYPE_MISMATCH) return failed(r.status);
        }
        const auto r = board->read_double(o);
        if (!r) return failed(r.status);
        fmt::print("{}\n", r.value);
        return Outcome::success();
    }

private:
    Outcome failed(apci::Status s) const {
        return Outcome::board_error(
            fmt::format("read{} {}: {}", type_.text(), object_.text(), describe_status(s)));
    }

    ObjectArgs object_;
    TypeFlags type_;
};

class WriteCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        object_.declare(app);
        app.add_option("VALUE", value_text_, "Value: int32 (5, -3, 0x1F) or double (2.5, 1e-3)")
            ->required();
        type_.declare(app, "Write");
        app.footer("Without --int/--double the value's type follows the object: an integer "
                   "written to a double object is written as that double; a value with a "
                   "fraction (2.5) written to an int object is an error. Prints nothing on "
                   "success.");
    }

    Outcome prepare() override {
        if (std::string why = object_.parse(); !why.empty()) return usage(why);
        is_int_ = parse_int32(value_text_, int_value_);
        const bool is_number = parse_double(value_text_, double_value_);
        if (type_.force_int && !is_int_)
            return usage(fmt::format("VALUE '{}' is not an int32 (--int)", value_text_));
        if (!is_number && !is_int_)
            return usage(fmt::format("VALUE '{}' is not a number", value_text_));
        if (type_.force_double && is_int_) double_value_ = int_value_;
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        board_ = board;
        auto o = object_.descriptor();
        if (type_.force_int) return result(board->write_int(o, int_value_).status);
        if (type_.force_double) return result(board->write_double(o, double_value_).status);
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
                describe_status(r.status), object_.address(), value_text_));
        }
        return result(r.status);
    }

private:
    std::string command_text() const {
        return fmt::format("write{} {} {}", type_.text(), object_.text(), value_text_);
    }
    Outcome usage(std::string why) const {
        return Outcome::usage_error(fmt::format("{}: {}", command_text(), why));
    }
    Outcome result(apci::Status s) const {
        if (s == APCI_OK) return Outcome::success();
        return Outcome::board_error(
            fmt::format("{}: {}{}", command_text(), describe_status(s), tc_consequence(s)));
    }

    // A refused write to a TC group may have set the group's ERROR ([APCI-TC] Table 3: InitError
    // for STATUS = 1 on a group not initialised, and for the axes, WKZINDEX, Left or Right
    // while it runs): the refusal says so, and what to change.
    std::string tc_consequence(apci::Status s) const {
        namespace tc = objif::map::tc;
        if (object_.bus == tc::kBus && object_.device == tc::kDevInit &&
            object_.index == tc::kIdxReInit && s == APCI_WRONG_DEVICE_STATE)
            return "; ReInit while a contour is under way (a profile held, STATUS bit "
                   "ProfMarked) is not emulated: [APCI-TC] gives it for before a re-reference "
                   "and does not say what it does to a contour; end the contour first (STATUS = "
                   "0, or SSF 2001 to its axes), or write Reset (1300 0 14) to drop it";
        if (object_.bus != tc::kBus || object_.device != tc::kDevGroups || board_ == nullptr)
            return {};
        auto error = apci::object(tc::kBus, tc::kDevGroups, object_.index, tc::kSubError);
        const auto bits = board_->read_int(error);
        if (!bits || bits.value == 0) return {};
        std::string names;
        for (int bit = 0; bit < 32; ++bit) {
            if ((static_cast<std::uint32_t>(bits.value) & (1u << bit)) == 0) continue;
            const char* name = apci_tc_error_bit_name(bit);
            names += names.empty() ? "" : ", ";
            names += name != nullptr ? name : fmt::format("bit {}", bit);
        }
        const std::string group =
            object_.index == tc::kActiveGroupIndex ? "the active group"
                                                   : fmt::format("group {}", object_.index);
        std::string hint;
        if ((bits.value & 1) != 0) {
            if (object_.subindex == tc::kSubStatus)
                hint = "; STATUS = 1 needs the group initialised: XAxis, YAxis and ZAxis "
                       "distinct and on no axis of a running group, and Left or Right written "
                       "([APCI-TC] Table 3)";
            else if (object_.subindex == tc::kSubXAxis || object_.subindex == tc::kSubYAxis ||
                     object_.subindex == tc::kSubZAxis || object_.subindex == tc::kSubWkzIndex ||
                     object_.subindex == tc::kSubLeft || object_.subindex == tc::kSubRight)
                hint = "; this object changes only while the group is inactive: write STATUS = 0 "
                       "first ([APCI-TC] Table 3)";
        }
        return fmt::format("; {}'s ERROR now reads 0x{:02x} ({}){} (clear it: write {} {} {} {} 0)",
                           group, bits.value, names, hint, tc::kBus, tc::kDevGroups, object_.index,
                           tc::kSubError);
    }

    ObjectArgs object_;
    TypeFlags type_;
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
