// SPDX-License-Identifier: MIT
// `status`: the TC registers ERROR (Table 4) and STATUS (Table 5) of each
// compensation group and of the active group, decoded by the bit names of [APCI-TC] (Tables 4 and 5)
// ([APCI-TC] section 2.3 "Fehlerabfrage von TC").
#include <cstdint>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.h"
#include "objif/map/object_map.h"

namespace apcictl {
namespace {

constexpr std::int32_t kGroupCount = 3;  // Index 1..3; Index 0 = the active group

std::string_view plane_name(std::int32_t plane) {
    switch (plane) {
        case 17: return "X-Y";
        case 18: return "Z-X";
        case 19: return "Y-Z";
    }
    return "unknown plane";
}

// "0x01 InitError", "0x00 none", "0x41 InitError, bit6".
std::string decode_error(std::int32_t value) {
    const auto bits = static_cast<std::uint32_t>(value);
    std::string names;
    for (int bit = 0; bit < 32; ++bit) {
        if ((bits & (1u << bit)) == 0) continue;
        if (!names.empty()) names += ", ";
        const char* name = apci_tc_error_bit_name(bit);
        names += name != nullptr ? std::string(name) : fmt::format("bit{}", bit);
    }
    return fmt::format("0x{:02X} {}", bits, names.empty() ? "none" : names);
}

// "0x01 (Run on, ProfMarked off)"; bits [APCI-TC] does not name are listed too.
std::string decode_status(std::int32_t value) {
    const auto bits = static_cast<std::uint32_t>(value);
    std::string flags;
    for (int bit = 0; bit < 32; ++bit) {
        const char* name = apci_tc_status_bit_name(bit);
        const bool set = (bits & (1u << bit)) != 0;
        if (name == nullptr && !set) continue;
        if (!flags.empty()) flags += ", ";
        flags += name != nullptr ? fmt::format("{} {}", name, set ? "on" : "off")
                                 : fmt::format("bit{} on", bit);
    }
    return fmt::format("0x{:02X} ({})", bits, flags);
}

// The bits of a register as names: [APCI-TC]'s where it has one, "bitN" else; set bits only.
nlohmann::json bit_names(std::int32_t value, const char* (*name_of)(int)) {
    nlohmann::json names = nlohmann::json::array();
    for (int bit = 0; bit < 32; ++bit) {
        if ((static_cast<std::uint32_t>(value) & (1u << bit)) == 0) continue;
        const char* name = name_of(bit);
        names.push_back(name != nullptr ? std::string(name) : fmt::format("bit{}", bit));
    }
    return names;
}

// Who holds the board's motion (docs/motion-claim.md), from the board's record
// (apci_motion_claim_get): the holder as libapci names it (apci_motion_claim_holder). `served`
// false where the transport does not serve claims (nothing then keeps two programs apart).
struct MotionHolder {
    apci::Status status = APCI_OK;  // of the query: APCI_OK, APCI_NOT_SUPPORTED or an error
    apci_motion_claim claim{};
    bool served() const { return status != APCI_NOT_SUPPORTED; }
    bool held() const { return claim.held != 0; }
    std::string name() const { return apci::motion_claim_name(claim); }
    std::string holder() const { return apci::motion_claim_holder(claim); }
};
MotionHolder motion_holder(apci::Board& board) {
    const auto r = board.motion_claim();
    return MotionHolder{r.status, r.ok() ? r.value : apci_motion_claim{}};
}

// A register read for --json: {"value": 1, "set": ["Run"]}, or {"unreadable": "StatusName"}.
nlohmann::json register_json(const apci::Result<std::int32_t>& r, const char* (*name_of)(int)) {
    if (!r) return {{"unreadable", std::string(apci::status_name(r.status))}};
    return {{"value", r.value}, {"set", bit_names(r.value, name_of)}};
}

class StatusCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        app.add_flag("--json", json_,
                     "Print one JSON object instead (docs/apcictl.md, \"status --json\")");
        app.footer(
            "Reads the spooler fill level (bus 1000), who holds the board's motion (docs/motion-claim.md), TcPlane, then ERROR (SubIndex 1) and STATUS (SubIndex 3) of compensation "
            "groups 1..3 and of the active group (Index 0) on bus 1300, DeviceNumber 1, and "
            "names the set bits. Says so when the firmware has no optionTC. Exit 1 if a "
            "register could not be read. --json prints the same as one JSON object: spooler "
            "{fill, capacity}, motion {served, held, pid, name, since_ms, holder}, tc {bus, plane, plane_name, groups [{group, active, error "
            "{value, set}, status {value, set}}]} (tc null without optionTC; an unreadable "
            "register {unreadable: STATUS}).");
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;

        if (json_) return run_json(*board);
        Outcome outcome = show_spooler(*board);
        show_motion(*board, session.uri(), outcome);

        auto plane_object = apci::object(APCI_TC_BUS, APCI_TC_DEVICE_INIT, APCI_TC_PLANE, 0);
        const auto plane = board->read_int(plane_object);
        if (plane.status == APCI_NO_SUCH_DEVICE) {
            fmt::print("TC module (bus {}): absent, the firmware has no optionTC\n", APCI_TC_BUS);
            return outcome;
        }
        if (!plane) return failed(*board, "TcPlane", plane.status);
        fmt::print("TC module (bus {}): TcPlane {} ({})\n", APCI_TC_BUS, plane.value,
                   plane_name(plane.value));

        for (std::int32_t group = 1; group <= kGroupCount; ++group)
            show_group(*board, group, fmt::format("group {}", group), outcome);
        show_group(*board, 0, "active group", outcome);
        return outcome;
    }

private:
    bool json_ = false;

    // The same registers as one JSON object on one line; the same exit status.
    static Outcome run_json(apci::Board& board) {
        namespace b = objif::map::board;
        Outcome outcome;
        nlohmann::json out;
        auto fill_object = apci::object(b::kBus, b::kDevice, b::kIdxSpoolerFill, 0);
        auto capacity_object = apci::object(b::kBus, b::kDevice, b::kIdxSpoolerCapacity, 0);
        const auto fill = board.read_int(fill_object);
        const auto capacity = board.read_int(capacity_object);
        if (fill && capacity) {
            out["spooler"] = {{"fill", fill.value}, {"capacity", capacity.value}};
        } else {
            const apci::Status s = fill ? capacity.status : fill.status;
            out["spooler"] = {{"unreadable", std::string(apci::status_name(s))}};
            outcome = failed(board, "spooler", s);
        }
        const MotionHolder motion = motion_holder(board);
        if (!motion.served()) {
            out["motion"] = {{"served", false}};
        } else if (motion.status != APCI_OK) {
            out["motion"] = {{"unreadable", std::string(apci::status_name(motion.status))}};
            if (outcome.ok()) outcome = failed(board, "motion claim", motion.status);
        } else if (!motion.held()) {
            out["motion"] = {{"served", true}, {"held", false}};
        } else {
            out["motion"] = {{"served", true},         {"held", true},
                             {"pid", motion.claim.pid}, {"name", motion.name()},
                             {"since_ms", motion.claim.since_ms}, {"holder", motion.holder()}};
        }
        auto plane_object = apci::object(APCI_TC_BUS, APCI_TC_DEVICE_INIT, APCI_TC_PLANE, 0);
        const auto plane = board.read_int(plane_object);
        if (plane.status == APCI_NO_SUCH_DEVICE) {
            out["tc"] = nullptr;  // no optionTC
        } else if (!plane) {
            out["tc"] = {{"unreadable", std::string(apci::status_name(plane.status))}};
            if (outcome.ok()) outcome = failed(board, "TcPlane", plane.status);
        } else {
            nlohmann::json groups = nlohmann::json::array();
            // Groups 1..3, then the active group (Index 0).
            for (std::int32_t group : {1, 2, 3, 0}) {
                auto error_object =
                    apci::object(APCI_TC_BUS, APCI_TC_DEVICE_GROUP, group, APCI_TC_ERROR);
                auto status_object =
                    apci::object(APCI_TC_BUS, APCI_TC_DEVICE_GROUP, group, APCI_TC_STATUS);
                const auto error = board.read_int(error_object);
                const auto status = board.read_int(status_object);
                groups.push_back({{"group", group},
                                  {"active", group == 0},
                                  {"error", register_json(error, apci_tc_error_bit_name)},
                                  {"status", register_json(status, apci_tc_status_bit_name)}});
                const std::string label = group == 0 ? "active group" : fmt::format("group {}", group);
                if (outcome.ok() && !error) outcome = failed(board, label + " ERROR", error.status);
                if (outcome.ok() && !status) outcome = failed(board, label + " STATUS", status.status);
            }
            out["tc"] = {{"bus", APCI_TC_BUS},
                         {"plane", plane.value},
                         {"plane_name", std::string(plane_name(plane.value))},
                         {"groups", groups}};
        }
        fmt::print("{}\n", out.dump());
        return outcome;
    }

    // "board (bus 1000): spooler 0 of 256 profiles" (board module, design numbers).
    static Outcome show_spooler(apci::Board& board) {
        namespace b = objif::map::board;
        auto fill_object = apci::object(b::kBus, b::kDevice, b::kIdxSpoolerFill, 0);
        auto capacity_object = apci::object(b::kBus, b::kDevice, b::kIdxSpoolerCapacity, 0);
        const auto fill = board.read_int(fill_object);
        const auto capacity = board.read_int(capacity_object);
        if (fill && capacity) {
            fmt::print("board (bus {}): spooler {} of {} profiles\n", b::kBus, fill.value,
                       capacity.value);
            return Outcome::success();
        }
        const apci::Status s = fill ? capacity.status : fill.status;
        fmt::print("board (bus {}): spooler unreadable, {}\n", b::kBus, describe_status(s));
        return failed(board, "spooler", s);
    }

    // "motion: free", "motion: held by pid 4242 (apcictl) since ...", or that the transport
    // does not serve claims; an error of the query becomes the outcome, if it is the first.
    static void show_motion(apci::Board& board, const std::string& uri, Outcome& outcome) {
        const MotionHolder motion = motion_holder(board);
        if (!motion.served()) {
            fmt::print("motion: {} does not serve motion claims\n", uri);
        } else if (motion.status != APCI_OK) {
            fmt::print("motion: unreadable, {}\n", describe_status(motion.status));
            if (outcome.ok()) outcome = failed(board, "motion claim", motion.status);
        } else if (!motion.held()) {
            fmt::print("motion: free\n");
        } else {
            fmt::print("motion: held by {}\n", motion.holder());
        }
    }

    // Prints one line; the first unreadable register becomes the outcome.
    static void show_group(apci::Board& board, std::int32_t index, const std::string& label,
                           Outcome& outcome) {
        auto error_object = apci::object(APCI_TC_BUS, APCI_TC_DEVICE_GROUP, index, APCI_TC_ERROR);
        auto status_object = apci::object(APCI_TC_BUS, APCI_TC_DEVICE_GROUP, index, APCI_TC_STATUS);
        const auto error = board.read_int(error_object);
        const auto status = board.read_int(status_object);
        const std::string error_text =
            error ? decode_error(error.value) : fmt::format("unreadable, {}", describe_status(error.status));
        const std::string status_text =
            status ? decode_status(status.value) : fmt::format("unreadable, {}", describe_status(status.status));
        fmt::print("{}: ERROR {}; STATUS {}\n", label, error_text, status_text);
        if (!outcome.ok()) return;
        if (!error)
            outcome = failed(board, label + " ERROR", error.status);
        else if (!status)
            outcome = failed(board, label + " STATUS", status.status);
    }

    static Outcome failed(const apci::Board& board, const std::string& what, apci::Status s) {
        return Outcome::board_error(
            fmt::format("status: {}: {}", what, describe_failure(board, s)));
    }
};

}  // namespace

std::unique_ptr<Command> make_status_command() { return std::make_unique<StatusCommand>(); }

}  // namespace apcictl
