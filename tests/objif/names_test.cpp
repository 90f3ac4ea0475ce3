// SPDX-License-Identifier: MIT
// Dotted names of the object map (objif/names.h): every address named once, names and
// addresses map to each other both ways, the examples of docs/object-map.md hold, suggestions
// find what was meant, and the name list of docs/object-map.md is the one the tables make.
#include "objif/names.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

using objif::Address;
using objif::find_object;
using objif::named_objects;

namespace {

TEST(ObjectNames, EveryAddressOfTheMapHasOneNameAndBack) {
    std::size_t expected = 0;
    for (const auto& m : objif::map::kModules)
        for (const auto& o : m.objects)
            expected += static_cast<std::size_t>(o.index_last - o.index_first + 1);
    const auto all = named_objects();
    ASSERT_EQ(all.size(), expected);
    std::set<std::string> names;
    for (const auto& o : all) {
        EXPECT_TRUE(names.insert(o.name).second) << "twice: " << o.name;
        const auto* by_name = find_object(o.name);
        ASSERT_NE(by_name, nullptr) << o.name;
        EXPECT_EQ(by_name->address, o.address) << o.name;
        const auto* by_address = find_object(o.address);
        ASSERT_NE(by_address, nullptr) << o.address.to_string();
        EXPECT_EQ(by_address->name, o.name);
        EXPECT_TRUE(o.info->covers(o.address)) << o.name;
        EXPECT_EQ(o.address.bus, o.module->bus) << o.name;
    }
}

TEST(ObjectNames, NamesAreLowerCaseDottedAndStartWithTheModule) {
    for (const auto& o : named_objects()) {
        EXPECT_TRUE(o.name.starts_with(std::string(o.module->key) + ".")) << o.name;
        for (char c : o.name)
            EXPECT_TRUE((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.' ||
                        c == '[' || c == ']')
                << o.name;
    }
}

TEST(ObjectNames, TheDocumentedExamplesNameTheirAddresses) {
    const std::map<std::string, Address> examples{
        {"tc.group[1].radius", {1300, 1, 1, 7}},
        {"tc.group[0].status", {1300, 1, 0, 3}},
        {"tc.init.tc_plane", {1300, 0, 12, 0}},
        {"tc.init.y_axis_nr", {1300, 0, 11, 1}},
        {"board.axis_count", {1000, 0, 3, 0}},
        {"board.position[7]", {1000, 0, 10, 7}},
        {"otc.tool.wear_const", {1330, 2, 3, 0}},
        {"otc.axis[2].command", {1330, 1, 2, 1}},
        {"otc.channel.radius_offset.state", {1330, 0, 20, 4}},
        {"comp3d.tool[1023].dr2", {1310, 1, 1023, 5}},
        {"comp3d.correction[5].dl", {1310, 2, 5, 1}},
        {"comp3d.settings.nz", {1310, 0, 11, 2}},
        {"tempcomp.tool_temp_comp[2]", {1320, 0, 1, 2}},
        {"tempcomp.offset[0]", {1320, 0, 10, 0}},
    };
    for (const auto& [name, address] : examples) {
        const auto* o = find_object(name);
        ASSERT_NE(o, nullptr) << name;
        EXPECT_EQ(o->address, address) << name;
    }
}

TEST(ObjectNames, UnknownNamesAndAddressesAreNotFound) {
    EXPECT_EQ(find_object("tc.group[4].radius"), nullptr);  // groups 0..3
    EXPECT_EQ(find_object("TC.GROUP[1].RADIUS"), nullptr);  // names are lower case
    EXPECT_EQ(find_object("tc.group[1].radius "), nullptr);
    EXPECT_EQ(find_object(""), nullptr);
    EXPECT_EQ(find_object(Address{1300, 1, 4, 7}), nullptr);
    EXPECT_EQ(find_object(Address{999, 0, 0, 0}), nullptr);
}

TEST(ObjectNames, SuggestionsFindWhatWasMeant) {
    const auto near = objif::nearest_names("tc.group[1].radus");
    ASSERT_FALSE(near.empty());
    EXPECT_EQ(near.front(), "tc.group[1].radius");
    EXPECT_EQ(objif::nearest_names("TC.GROUP[1].RADIUS").front(), "tc.group[1].radius");
    EXPECT_EQ(objif::nearest_names("otc.tool.wearconst").front(), "otc.tool.wear_const");
    EXPECT_LE(objif::nearest_names("board.axis_cnt", 2).size(), 2u);
    EXPECT_TRUE(objif::nearest_names("something entirely different").empty());
    // A row over a range of indices is offered at the typed index, brought into its range.
    EXPECT_EQ(objif::nearest_names("comp3d.tool[17].dr3").front(), "comp3d.tool[17].dr");
    EXPECT_EQ(objif::nearest_names("tc.group[4].radius").front(), "tc.group[3].radius");
    EXPECT_EQ(objif::nearest_names("tc.groupxx.radius").front(), "tc.group[0].radius");
}

TEST(ObjectNames, AnErrorSuggestsOnlyTheClosestNames) {
    // One step from group 1's radius; the nearest list goes on to names further away.
    const auto nearest = objif::nearest_names("tc.group[1].radus", 3);
    ASSERT_GT(nearest.size(), 1u);
    EXPECT_EQ(objif::closest_names("tc.group[1].radus"),
              std::vector<std::string_view>{"tc.group[1].radius"});
    // Ties stay, in map order, up to max.
    const auto tied = objif::closest_names("tc.group[1].x", 10);
    ASSERT_FALSE(tied.empty());
    const std::size_t d = objif::edit_distance("tc.group[1].x", tied.front());
    for (std::string_view n : tied) EXPECT_EQ(objif::edit_distance("tc.group[1].x", n), d) << n;
    EXPECT_LE(objif::closest_names("tc.group[1].x", 1).size(), 1u);
    EXPECT_TRUE(objif::closest_names("something entirely different").empty());
}

// The name list of docs/object-map.md, made from the tables: a row of objects over an index
// range is one line with the range in brackets.
std::string names_section() {
    std::ostringstream out;
    out << "| name | bus | device | index | sub | type | access | unit |\n"
        << "|---|---|---|---|---|---|---|---|\n";
    for (const auto& m : objif::map::kModules) {
        for (const auto& o : m.objects) {
            std::string device;
            for (const auto& d : m.devices)
                if (d.device == o.device) device = std::string(d.key);
            std::string name(m.key);
            std::string index = std::to_string(o.index_first);
            if (!device.empty()) name += "." + device;
            if (o.index_first != o.index_last) {
                index += ".." + std::to_string(o.index_last);
                name += "[" + index + "]";
            }
            name += "." + std::string(o.key);
            out << "| `" << name << "` | " << m.bus << " | " << o.device << " | " << index << " | "
                << o.subindex << " | " << (o.type == objif::ValueType::kDouble ? "double" : "int")
                << " | " << objif::access_name(o.access) << " | " << o.unit << " |\n";
        }
    }
    return out.str();
}

TEST(ObjectNames, TheDocumentedNameListIsTheTables) {
    const std::string path = std::string(APCI_SOURCE_DIR) + "/docs/object-map.md";
    std::ifstream in(path);
    ASSERT_TRUE(in) << path;
    std::stringstream text;
    text << in.rdbuf();
    std::string doc = text.str();
    const std::string begin = "<!-- names:begin -->\n";
    const std::string end = "<!-- names:end -->";
    const auto b = doc.find(begin);
    const auto e = doc.find(end);
    ASSERT_NE(b, std::string::npos) << "docs/object-map.md lacks " << begin;
    ASSERT_NE(e, std::string::npos) << "docs/object-map.md lacks " << end;
    const std::string want = names_section();
    if (const char* update = std::getenv("APCI_UPDATE_DOCS");
        update && std::string(update) == "1") {
        doc.replace(b + begin.size(), e - b - begin.size(), want);
        std::ofstream(path) << doc;
        return;
    }
    EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), want)
        << "docs/object-map.md's name list differs from objif/map/objects.h: run "
           "scripts/update_object_names.sh";
}

}  // namespace
