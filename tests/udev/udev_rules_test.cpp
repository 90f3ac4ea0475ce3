// SPDX-License-Identifier: MIT
// udev/60-apci8001.rules (docs/transports.md, "Permissions for real boards"): every rule
// guarded by ACTION and SUBSYSTEM; USB and UIO nodes for the seat user
// (uaccess) and group plugdev, mode 0660; the PCI BAR resource files made
// group-accessible; ADDI-DATA's vendor ID 0x15b8 matched by vendor, AMCC's
// 0x10e8 (other makers' cards carry it too) only in commented-out rules
// narrowed by product ID. udevadm cannot check rules without a device here, so
// the rules are read the way udev reads them: one rule a line,
// comma-separated KEY op "value" pairs.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

struct Rule {
    int line = 0;
    std::string text;
    bool has(const std::string& part) const { return text.find(part) != std::string::npos; }
};

std::vector<std::string> lines() {
    std::ifstream f(APCI_UDEV_RULES);
    EXPECT_TRUE(f) << APCI_UDEV_RULES;
    std::vector<std::string> out;
    std::string line;
    while (std::getline(f, line)) out.push_back(line);
    return out;
}

// The active rules: every line that is neither empty nor a comment.
std::vector<Rule> rules() {
    std::vector<Rule> out;
    const auto all = lines();
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (all[i].empty() || all[i][0] == '#') continue;
        out.push_back({static_cast<int>(i + 1), all[i]});
    }
    return out;
}

// The rules shipped commented out: comment lines "# SUBSYSTEM==...", without the "# ".
std::vector<Rule> commented_rules() {
    std::vector<Rule> out;
    const auto all = lines();
    const std::string prefix = "# SUBSYSTEM==";
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (all[i].rfind(prefix, 0) == 0)
            out.push_back({static_cast<int>(i + 1), all[i].substr(2)});
    }
    return out;
}

// What is left of TEXT after its KEY op "value" pairs, separated by ", ": empty for a
// well-formed rule.
std::string unparsed_rest(const std::string& text) {
    const std::regex pair(R"re([A-Z_]+(\{[A-Za-z_]+\})?(==|!=|\+=|=)"[^"]*")re");
    std::string rest = text;
    std::smatch m;
    while (std::regex_search(rest, m, pair) && m.position(0) == 0) {
        rest = m.suffix().str();
        if (rest.rfind(", ", 0) == 0) rest = rest.substr(2);
    }
    return rest;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos;
         at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

std::vector<Rule> rules_for(const std::string& subsystem) {
    std::vector<Rule> out;
    for (const auto& r : rules())
        if (r.has("SUBSYSTEM==\"" + subsystem + "\"")) out.push_back(r);
    return out;
}

TEST(UdevRules, FirstRuleSkipsEverythingButAddChangeAndBind) {
    const auto all = rules();
    ASSERT_FALSE(all.empty());
    EXPECT_EQ(all.front().text, "ACTION!=\"add|change|bind\", GOTO=\"apci8001_end\"");
    EXPECT_EQ(all.back().text, "LABEL=\"apci8001_end\"");
}

TEST(UdevRules, EveryRuleIsGuardedBySubsystem) {
    const auto all = rules();
    for (std::size_t i = 1; i + 1 < all.size(); ++i)
        EXPECT_TRUE(all[i].has("SUBSYSTEM==\"")) << "line " << all[i].line << ": " << all[i].text;
}

TEST(UdevRules, EveryRuleIsWellFormed) {
    for (const auto& r : rules())
        EXPECT_EQ(unparsed_rest(r.text), "") << "line " << r.line << " does not parse";
}

TEST(UdevRules, AddiDataUsbBoardsGetUaccessMode0660AndPlugdev) {
    bool found = false;
    for (const auto& r : rules_for("usb")) {
        if (!r.has("ATTR{idVendor}==\"15b8\"")) continue;
        found = true;
        EXPECT_TRUE(r.has("ENV{DEVTYPE}==\"usb_device\"")) << r.text;
        EXPECT_TRUE(r.has("TAG+=\"uaccess\"")) << r.text;
        EXPECT_TRUE(r.has("MODE=\"0660\"")) << r.text;
        EXPECT_TRUE(r.has("GROUP=\"plugdev\"")) << r.text;
    }
    EXPECT_TRUE(found) << "no USB rule for vendor 15b8";
}

TEST(UdevRules, AddiDataPciBarResourceFilesBecomeGroupPlugdev0660) {
    bool found = false;
    for (const auto& r : rules_for("pci")) {
        if (!r.has("ATTR{vendor}==\"0x15b8\"")) continue;
        found = true;
        EXPECT_TRUE(r.has("chgrp plugdev /sys%p/resource[0-5]")) << r.text;
        EXPECT_TRUE(r.has("chmod 0660 /sys%p/resource[0-5]")) << r.text;
    }
    EXPECT_TRUE(found) << "no PCI rule for vendor 0x15b8";
}

TEST(UdevRules, AddiDataUioNodesGetUaccessMode0660AndPlugdev) {
    const auto uio = rules_for("uio");
    ASSERT_EQ(uio.size(), 1u);
    EXPECT_TRUE(uio[0].has("ATTRS{vendor}==\"0x15b8\"")) << uio[0].text;
    EXPECT_TRUE(uio[0].has("TAG+=\"uaccess\"") && uio[0].has("MODE=\"0660\"") &&
                uio[0].has("GROUP=\"plugdev\""))
        << uio[0].text;
}

// AMCC's 0x10e8 is on other makers' cards too: no active rule may match it by vendor.
TEST(UdevRules, NoActiveRuleMatchesTheAmccVendorId) {
    for (const auto& r : rules())
        EXPECT_FALSE(r.has("10e8")) << "line " << r.line << ": " << r.text;
}

// The 0x10e8 rules are shipped commented out, one for each active rule, the same rule
// narrowed by a product ID placeholder (NNNN, which matches no device until replaced).
TEST(UdevRules, AmccRulesAreCommentedOutAndNarrowedByProductId) {
    const auto templates = commented_rules();
    ASSERT_EQ(templates.size(), 3u);
    const std::vector<std::pair<std::string, std::string>> narrowing = {
        {"ATTR{idVendor}==\"10e8\", ATTR{idProduct}==\"NNNN\"", "ATTR{idVendor}==\"15b8\""},
        {"ATTR{vendor}==\"0x10e8\", ATTR{device}==\"0xNNNN\"", "ATTR{vendor}==\"0x15b8\""},
        {"ATTRS{vendor}==\"0x10e8\", ATTRS{device}==\"0xNNNN\"", "ATTRS{vendor}==\"0x15b8\""}};
    const auto active = rules();
    for (const auto& t : templates) {
        EXPECT_EQ(unparsed_rest(t.text), "") << "line " << t.line << " does not parse";
        bool narrowed = false;
        for (const auto& [amcc, addi_data] : narrowing) {
            if (!t.has(amcc)) continue;
            narrowed = true;
            // Without its product ID and with ADDI-DATA's vendor it is an active rule.
            const std::string same = replace_all(t.text, amcc, addi_data);
            bool twin = false;
            for (const auto& r : active) twin = twin || r.text == same;
            EXPECT_TRUE(twin) << "line " << t.line << " is not an active rule narrowed: " << t.text;
        }
        EXPECT_TRUE(narrowed) << "line " << t.line << " matches 0x10e8 without a product ID";
    }
}

}  // namespace
