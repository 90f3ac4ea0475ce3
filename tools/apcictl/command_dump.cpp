// SPDX-License-Identifier: MIT
// `dump [PREFIX] [--json]`: every readable object of the map whose name is PREFIX or under it
// by whole components (tc, tc.group, tc.group[1]), read from the board in one session, as a
// table (name, address, type, access, value, unit) or as a JSON list. An object the board does
// not serve (its module absent: NoSuchDevice) or that refuses its read shows the status name
// instead of a value; the dump goes on. A link that fails (TransportError, Timeout) ends it:
// every read after would wait for the same link.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "command.h"
#include "object_name.h"

namespace apcictl {
namespace {

// One object as read.
struct Row {
    const objif::NamedObject* object = nullptr;
    apci::Status status = APCI_OK;
    objif::Value value;
};

bool is_int(const objif::NamedObject& o) {
    return o.info->type == objif::ValueType::kInt32;
}

// The value as `read` prints it ("17", "2.5"), or the status name.
std::string value_text(const Row& r) {
    if (r.status != APCI_OK) return std::string(apci::status_name(r.status));
    return r.value.is_int() ? fmt::format("{}", r.value.as_int())
                            : fmt::format("{}", r.value.as_double());
}

bool link_failed(apci::Status s) {
    return s == APCI_TRANSPORT_ERROR || s == APCI_TIMEOUT;
}

Row read_row(apci::Board& board, const objif::NamedObject& o) {
    Row row{&o, APCI_OK, {}};
    auto d = apci::object(o.address.bus, o.address.device, o.address.index, o.address.subindex);
    if (is_int(o)) {
        const auto r = board.read_int(d);
        row.status = r.status;
        if (r) row.value = objif::Value::of_int(r.value);
    } else {
        const auto r = board.read_double(d);
        row.status = r.status;
        if (r) row.value = objif::Value::of_double(r.value);
    }
    return row;
}

void print_table(const std::vector<Row>& rows) {
    const std::array<std::string_view, 6> header{"name",   "address", "type",
                                                 "access", "value",   "unit"};
    std::vector<std::array<std::string, 6>> cells;
    cells.reserve(rows.size());
    for (const Row& r : rows) {
        const objif::ObjectInfo& info = *r.object->info;
        cells.push_back({r.object->name, address_text(r.object->address),
                         std::string(objif::value_type_name(info.type)),
                         std::string(objif::access_name(info.access)), value_text(r),
                         std::string(info.unit)});
    }
    std::array<std::size_t, 6> width{};
    for (std::size_t c = 0; c < width.size(); ++c) {
        width[c] = header[c].size();
        for (const auto& line : cells) width[c] = std::max(width[c], line[c].size());
    }
    const auto print_line = [&](const auto& line) {
        std::string text;
        for (std::size_t c = 0; c < line.size(); ++c) {
            if (c > 0) text += "  ";
            text += fmt::format("{:<{}}", line[c], c + 1 < line.size() ? width[c] : 0);
        }
        while (!text.empty() && text.back() == ' ') text.pop_back();
        fmt::print("{}\n", text);
    };
    print_line(header);
    for (const auto& line : cells) print_line(line);
}

void print_json(const std::vector<Row>& rows) {
    fmt::print("[");
    bool first = true;
    for (const Row& r : rows) {
        const objif::NamedObject& o = *r.object;
        nlohmann::ordered_json j;
        j["name"] = o.name;
        j["bus"] = o.address.bus;
        j["device"] = o.address.device;
        j["index"] = o.address.index;
        j["subindex"] = o.address.subindex;
        j["type"] = objif::value_type_name(o.info->type);
        j["access"] = objif::access_name(o.info->access);
        if (r.status != APCI_OK)
            j["value"] = nullptr;
        else if (r.value.is_int())
            j["value"] = r.value.as_int();
        else
            j["value"] = r.value.as_double();
        j["unit"] = o.info->unit;
        if (r.status != APCI_OK) j["status"] = apci::status_name(r.status);
        fmt::print("{}\n{}", first ? "" : ",", j.dump());
        first = false;
    }
    fmt::print("{}]\n", first ? "" : "\n");
}

class DumpCommand final : public Command {
  public:
    void declare(CLI::App& app) override {
        app.add_option("PREFIX", prefix_,
                       "Only the objects named PREFIX or under it, by whole components (tc, "
                       "tc.group, tc.group[1], tc.group[1].radius); default: every object");
        app.add_flag("--json", json_, "A JSON list of objects instead of the table");
        app.footer(
            "Reads every readable object of the map (docs/object-map.md section 8) "
            "named by PREFIX in one board session and prints a table: name, address "
            "(bus/device/index/subindex), type, access, value, unit. An object that "
            "cannot be read shows its status name (NoSuchDevice: the module is absent). "
            "Exit 0; 1 if an object of a present module refused its read, or the link "
            "failed.");
    }

    Outcome prepare() override {
        std::size_t named = 0;
        for (const objif::NamedObject& o : objif::named_objects()) {
            if (!name_has_prefix(o.name, prefix_)) continue;
            ++named;
            if (objif::can_read(o.info->access)) objects_.push_back(&o);
        }
        if (named == 0) {
            const auto meant = nearest_prefixes(prefix_);
            std::string error = fmt::format(
                "dump: no object is named '{}' or under it (whole components: tc, "
                "tc.group, tc.group[1])",
                prefix_);
            if (!meant.empty()) error += fmt::format("; did you mean {}?", quoted_choices(meant));
            return Outcome::usage_error(std::move(error));
        }
        if (objects_.empty())
            return Outcome::usage_error(fmt::format(
                "dump: nothing to read under '{}': {} write-only", prefix_,
                named == 1 ? "its one object is" : fmt::format("its {} objects are", named)));
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        std::vector<Row> rows;
        rows.reserve(objects_.size());
        std::map<std::string_view, std::size_t> refused;  // status name -> count
        for (const objif::NamedObject* o : objects_) {
            Row row = read_row(*board, *o);
            if (link_failed(row.status))
                return Outcome::board_error(fmt::format("dump: read {} ({}): {}", o->name,
                                                        address_text(o->address),
                                                        describe_failure(*board, row.status)));
            if (row.status != APCI_OK && row.status != APCI_NO_SUCH_DEVICE)
                ++refused[apci::status_name(row.status)];
            rows.push_back(row);
        }
        if (json_)
            print_json(rows);
        else
            print_table(rows);
        if (refused.empty()) return Outcome::success();
        std::size_t count = 0;
        std::vector<std::string> names;
        for (const auto& [name, n] : refused) {
            count += n;
            names.push_back(fmt::format("{} {}", name, n));
        }
        return Outcome::board_error(fmt::format("dump: {} of {} objects refused their read ({})",
                                                count, rows.size(), fmt::join(names, ", ")));
    }

  private:
    std::string prefix_;
    bool json_ = false;
    std::vector<const objif::NamedObject*> objects_;
};

}  // namespace

std::unique_ptr<Command> make_dump_command() {
    return std::make_unique<DumpCommand>();
}

}  // namespace apcictl
