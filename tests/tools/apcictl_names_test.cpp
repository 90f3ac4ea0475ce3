// SPDX-License-Identifier: MIT
// Objects by name in apcictl: read and write by name (in process, through the commands
// library, and as a process), every name of the map through apcictl's resolution and through
// read and write-then-read in one board session, the "did you mean" of an unknown name, and
// `dump` as a table and as JSON.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "object_name.h"
#include "objif/names.h"
#include "apcictl.h"
#include "script_reader.h"
#include "text.h"

namespace {

using test_support::contains;
using test_support::apcictl;
using test_support::lines_of;
using test_support::ProcessResult;

// A script run in this process through apcictl's commands library, against `session`.
struct InProcess {
    std::vector<std::string> errors;  // "line N: ..." for lines that did not parse or failed
    std::string out;                  // what the lines printed
};

InProcess run_script(apcictl::Session& session, const std::string& text) {
    std::istringstream in(text);
    apcictl::ParsedScript parsed = apcictl::parse_script(in);
    InProcess r;
    for (const auto& e : parsed.errors)
        r.errors.push_back(fmt::format("line {}: {}", e.number, e.outcome.error));
    if (!r.errors.empty()) return r;
    testing::internal::CaptureStdout();
    for (auto& line : parsed.lines) {
        const apcictl::Outcome o = line.command->run(session);
        if (!o.ok()) r.errors.push_back(fmt::format("line {}: {}", line.number, o.error));
    }
    r.out = testing::internal::GetCapturedStdout();
    return r;
}

// The error one script line gives when it is parsed (empty: it parsed).
std::string parse_error(const std::string& line) {
    std::istringstream in(line + "\n");
    const apcictl::ParsedScript parsed = apcictl::parse_script(in);
    return parsed.errors.empty() ? std::string() : parsed.errors.front().outcome.error;
}

// A value the object takes: its default, else (outside its range) its minimum; as
// `read` prints it.
std::string valid_value(const objif::ObjectInfo& info) {
    const double d = info.default_value.numeric();
    const double v = d >= info.min && d <= info.max ? d : info.min;
    if (info.type == objif::ValueType::kInt32) return fmt::format("{}", static_cast<int>(v));
    return fmt::format("{}", v);
}

// ---- resolution

TEST(ApcictlNames, EveryNameResolvesToItsAddressAndBack) {
    const auto all = objif::named_objects();
    ASSERT_GT(all.size(), 8000u);
    for (const objif::NamedObject& o : all) {
        ASSERT_TRUE(apcictl::is_object_name(o.name)) << o.name;
        std::string error;
        ASSERT_EQ(apcictl::resolve_object_name(o.name, error), &o) << o.name << ": " << error;
        EXPECT_EQ(apcictl::object_label(o.address),
                  fmt::format("{} ({})", o.name, apcictl::address_text(o.address)));
    }
    EXPECT_EQ(apcictl::object_label({1300, 1, 9, 3}), "1300/1/9/3");  // no such object
    for (const char* number : {"1300", "-1", "0x514", "+7"})
        EXPECT_FALSE(apcictl::is_object_name(number)) << number;
}

// Every name of the map through `read NAME` (and `read BUS DEV IDX SUB`, which must print the
// same) and, for an object that may be written and read, `write NAME VALUE` then `read NAME`,
// with a value it takes: all lines of one script in one board session, in this process.
TEST(ApcictlNames, EveryNameReadsAndWritesThroughTheCommandsInOneSession) {
    std::string script;
    std::vector<std::string> expected;  // what each printing line prints, or "" (any value)
    std::size_t reads = 0, writes = 0;
    for (const objif::NamedObject& o : objif::named_objects()) {
        const objif::Address& a = o.address;
        const bool readable = objif::can_read(o.info->access);
        const bool writable = objif::can_write(o.info->access);
        if (readable) {
            script += fmt::format("read {}\nread {} {} {} {}\n", o.name, a.bus, a.device, a.index,
                                  a.subindex);
            expected.emplace_back();
            expected.emplace_back();
            ++reads;
        }
        if (readable && writable) {
            const std::string v = valid_value(*o.info);
            script += fmt::format("write {} {}\nread {}\n", o.name, v, o.name);
            expected.push_back(v);
            ++writes;
        }
    }
    ASSERT_GT(reads, 8000u);
    ASSERT_GT(writes, 8000u);
    apcictl::Session session("emu:");
    const InProcess r = run_script(session, script);
    ASSERT_TRUE(r.errors.empty()) << r.errors.size() << " failures, the first: "
                                  << (r.errors.empty() ? std::string() : r.errors.front());
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), expected.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (!expected[i].empty()) {
            EXPECT_EQ(lines[i], expected[i]) << "line " << i;
            continue;
        }
        // A read by name, then the same read by numbers: they print the same.
        ASSERT_LT(i + 1, lines.size());
        EXPECT_EQ(lines[i], lines[i + 1]) << "line " << i;
        ++i;
    }
}

// ---- read and write by name

TEST(ApcictlNames, ReadAndWriteByNameInProcess) {
    apcictl::Session session("emu:");
    const InProcess r = run_script(session,
                                   "write tc.group[1].wkz_index 5\n"
                                   "write tc.group[1].radius 2.5\n"
                                   "write tc.group[1].wkz_len 3\n"  // an integer to a double
                                   "read tc.group[1].radius\n"
                                   "read 1300 1 1 7\n"
                                   "read tc.group[1].wkz_len\n"
                                   "read tc.group[1].wkz_index\n"
                                   "read --double tc.group[1].radius\n"
                                   "write --int tc.init.tc_plane 18\n"
                                   "read tc.init.tc_plane\n");
    EXPECT_TRUE(r.errors.empty()) << r.errors.front();
    EXPECT_EQ(r.out, "2.5\n2.5\n3\n5\n2.5\n18\n");
}

TEST(ApcictlNames, UnknownNameSaysWhichWasMeant) {
    EXPECT_EQ(parse_error("read tc.group[1].radus"),
              "unknown object 'tc.group[1].radus'; did you mean 'tc.group[1].radius'?");
    EXPECT_EQ(parse_error("write tc.group[1].radus 2.5"),
              "unknown object 'tc.group[1].radus'; did you mean 'tc.group[1].radius'?");
    // Equally close names: up to three.
    EXPECT_EQ(parse_error("read tc.init.y_axis_n"),
              "unknown object 'tc.init.y_axis_n'; did you mean 'tc.init.y_axis_nr'?");
    EXPECT_EQ(parse_error("read tc.init.axis_nr"),
              "unknown object 'tc.init.axis_nr'; did you mean 'tc.init.x_axis_nr', "
              "'tc.init.y_axis_nr' or 'tc.init.z_axis_nr'?");
    // Nothing close: where the names are.
    EXPECT_EQ(parse_error("read frobnicate"),
              "unknown object 'frobnicate' (names: docs/object-map.md section 8, or 'apcictl "
              "dump')");
}

TEST(ApcictlNames, MalformedObjectWordsAreUsageErrorsNamingWhatIsMissing) {
    EXPECT_EQ(parse_error("write tc.group[1].radius"),
              "write tc.group[1].radius: VALUE is required");
    EXPECT_EQ(parse_error("write 1300 1 1 8"), "write 1300 1 1 8: VALUE is required");
    EXPECT_EQ(parse_error("read 1300 1 1"), "read 1300 1 1: SUB is required");
    EXPECT_EQ(parse_error("read tc.group[1].radius 7"),
              "read tc.group[1].radius 7: The following argument was not expected: 7");
    EXPECT_EQ(parse_error("write tc.group[1].radius 1 2"),
              "write tc.group[1].radius 1 2: The following argument was not expected: 2");
}

TEST(ApcictlNames, TypeOptionThatContradictsTheNamedObjectIsAUsageError) {
    EXPECT_EQ(parse_error("read --int tc.group[1].radius"),
              "read --int tc.group[1].radius: --int contradicts the object: tc.group[1].radius "
              "holds a double");
    EXPECT_EQ(parse_error("write --double tc.init.tc_plane 17"),
              "write --double tc.init.tc_plane 17: --double contradicts the object: "
              "tc.init.tc_plane holds an int32");
    // A fraction for an int object is found before anything runs.
    EXPECT_EQ(parse_error("write tc.group[1].wkz_index 2.5"),
              "write tc.group[1].wkz_index 2.5: VALUE '2.5' is not an int32 "
              "(tc.group[1].wkz_index holds an int32)");
    EXPECT_EQ(parse_error("read --double tc.group[1].radius"), "");
}

TEST(ApcictlNames, ReadAndWriteByNameAsAProcess) {
    auto r = apcictl({"read", "tc.init.tc_plane"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "17\n");
    r = apcictl({"write", "tc.group[1].radius", "2.5"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "");
    r = apcictl({"read", "tc.group[1].radus"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err,
              "apcictl: unknown object 'tc.group[1].radus'; did you mean 'tc.group[1].radius'?\n");
    // The board's refusal names the command as typed.
    r = apcictl({"write", "tc.group[1].radius", "--", "-.5"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "apcictl: write tc.group[1].radius -.5: ValueTooLow")) << r.err;
    r = apcictl({"--device", "emu:?no-option-tc", "read", "tc.group[1].radius"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "apcictl: read tc.group[1].radius: NoSuchDevice")) << r.err;
    // In a script, one session: the write is read back.
    r = apcictl({"script", "-"}, "write tc.group[1].radius 2.5\nread tc.group[1].radius\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "2.5\n");
    r = apcictl({"script", "-"}, "read tc.init.tc_plane\nread tc.init.tc_plan\n");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err,
              "apcictl: line 2: unknown object 'tc.init.tc_plan'; did you mean "
              "'tc.init.tc_plane'?\n");
}

// ---- dump

std::set<std::string> readable_names(std::string_view prefix) {
    std::set<std::string> names;
    for (const objif::NamedObject& o : objif::named_objects())
        if (apcictl::name_has_prefix(o.name, prefix) && objif::can_read(o.info->access))
            names.insert(o.name);
    return names;
}

TEST(ApcictlDump, PrefixesAreWholeComponents) {
    using apcictl::name_has_prefix;
    EXPECT_TRUE(name_has_prefix("tc.group[1].radius", "tc"));
    EXPECT_TRUE(name_has_prefix("tc.group[1].radius", "tc."));
    EXPECT_TRUE(name_has_prefix("tc.group[1].radius", "tc.group"));
    EXPECT_TRUE(name_has_prefix("tc.group[1].radius", "tc.group[1]"));
    EXPECT_TRUE(name_has_prefix("tc.group[1].radius", "tc.group[1].radius"));
    EXPECT_TRUE(name_has_prefix("tc.group[1].radius", ""));
    EXPECT_FALSE(name_has_prefix("tc.group[1].radius", "tc.gr"));
    EXPECT_FALSE(name_has_prefix("tc.group[1].radius", "tc.group[1"));
    EXPECT_FALSE(name_has_prefix("tc.group[12].radius", "tc.group[1]"));
    EXPECT_FALSE(name_has_prefix("tc.group[1].radius", "t"));
    EXPECT_FALSE(name_has_prefix("tc.group[1].radius_x", "tc.group[1].radius"));
}

TEST(ApcictlDump, JsonListsExactlyTheReadableObjectsUnderThePrefix) {
    const auto r = apcictl({"dump", "tc", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j.is_array());
    std::set<std::string> names;
    for (const auto& o : j) {
        ASSERT_TRUE(o.contains("name") && o.contains("bus") && o.contains("device") &&
                    o.contains("index") && o.contains("subindex") && o.contains("type") &&
                    o.contains("access") && o.contains("value") && o.contains("unit"))
            << o.dump();
        EXPECT_FALSE(o.contains("status")) << o.dump();
        const std::string name = o["name"];
        EXPECT_TRUE(names.insert(name).second) << name << " twice";
        const objif::NamedObject* named = objif::find_object(name);
        ASSERT_NE(named, nullptr) << name;
        EXPECT_EQ(o["bus"], named->address.bus);
        EXPECT_EQ(o["device"], named->address.device);
        EXPECT_EQ(o["index"], named->address.index);
        EXPECT_EQ(o["subindex"], named->address.subindex);
        EXPECT_EQ(o["type"], objif::value_type_name(named->info->type));
        EXPECT_EQ(o["access"], objif::access_name(named->info->access));
        EXPECT_EQ(o["unit"], named->info->unit);
        EXPECT_TRUE(o["value"].is_number()) << o.dump();
    }
    EXPECT_EQ(names, readable_names("tc"));
    const auto plane = std::find_if(j.begin(), j.end(),
                                    [](const auto& o) { return o["name"] == "tc.init.tc_plane"; });
    ASSERT_NE(plane, j.end());
    EXPECT_EQ(*plane, nlohmann::json::parse(R"({"name":"tc.init.tc_plane","bus":1300,"device":0,
        "index":12,"subindex":0,"type":"int","access":"r/w","value":17,"unit":""})"));
}

TEST(ApcictlDump, TableHasOneRowPerReadableObjectWithItsAddressTypeAccessValueAndUnit) {
    const auto r = apcictl({"dump", "tc.group[1]"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 1 + readable_names("tc.group[1]").size()) << r.out;
    EXPECT_TRUE(std::regex_match(lines[0], std::regex("name +address +type +access +value +unit")))
        << lines[0];
    EXPECT_TRUE(std::regex_search(
        r.out, std::regex("\ntc\\.group\\[1\\]\\.radius +1300/1/1/7 +double +r/w +0 +PU\n")))
        << r.out;
    EXPECT_TRUE(std::regex_search(
        r.out, std::regex("\ntc\\.group\\[1\\]\\.error +1300/1/1/1 +int +r/w +0\n")))
        << r.out;
    EXPECT_FALSE(contains(r.out, "tc.group[1].reset")) << "write-only objects are not read";
    // The columns line up: every row's address starts where the header's does.
    const std::size_t column = lines[0].find("address");
    for (std::size_t i = 1; i < lines.size(); ++i)
        EXPECT_EQ(lines[i].find("1300/1/1/"), column) << lines[i];
}

TEST(ApcictlDump, AbsentModuleShowsItsStatusAndTheDumpGoesOn) {
    auto r = apcictl({"--device", "emu:?no-option-tc", "dump", "tc.init", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j.size(), readable_names("tc.init").size());
    for (const auto& o : j) {
        EXPECT_TRUE(o["value"].is_null()) << o.dump();
        EXPECT_EQ(o["status"], "NoSuchDevice") << o.dump();
    }
    r = apcictl({"--device", "emu:?no-option-tc", "dump"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("\ntc\\.init\\.tc_plane +1300/0/12/0 +int +r/w "
                                                    "+NoSuchDevice\n")))
        << r.out.substr(0, 2000);
    EXPECT_TRUE(
        std::regex_search(r.out, std::regex("\nboard\\.axis_count +1000/0/3/0 +int +r +8\n")))
        << r.out.substr(0, 2000);
}

TEST(ApcictlDump, PrefixThatMatchesNothingSaysWhatWasMeant) {
    auto r = apcictl({"dump", "tc.grup"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err,
              "apcictl: dump: no object is named 'tc.grup' or under it (whole components: tc, "
              "tc.group, tc.group[1]); did you mean 'tc.group'?\n");
    r = apcictl({"dump", "tc.gr"});  // a plain string prefix is not a component
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "no object is named 'tc.gr' or under it")) << r.err;
    r = apcictl({"dump", "tc.init.reset"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err,
              "apcictl: dump: nothing to read under 'tc.init.reset': its one object is "
              "write-only\n");
}

// The whole map, about 8,400 readable addresses, in one session.
TEST(ApcictlDump, TheWholeMapOnTheEmbeddedBoardListsEveryReadableObject) {
    const auto r = apcictl({"dump", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.size(), readable_names("").size());
    EXPECT_GT(j.size(), 8000u);
    const auto table = apcictl({"dump"});
    ASSERT_EQ(table.exit_code, 0) << table.err;
    EXPECT_EQ(lines_of(table.out).size(), 1 + j.size());
}

}  // namespace
