// SPDX-License-Identifier: MIT
// udev/60-apci8001.rules and the opt-in udev/61-apci8001-raw-bar.rules (docs/transports.md,
// "Permissions for real boards"): every rule guarded by ACTION and SUBSYSTEM; USB nodes for the
// seat user (uaccess) and group plugdev, mode 0660; no raw access to a PCI board's BARs in the
// rules installed where udev reads them; the raw-BAR grant (PCI resource files, UIO nodes, no
// uaccess) only in the opt-in file, whose header states the risk; ADDI-DATA's vendor ID
// 0x15b8 matched by vendor, AMCC's 0x10e8 (other makers' cards carry it too) only in
// commented-out rules narrowed by product ID. udevadm cannot check rules without a device
// here, so the rules are read the way udev reads them: one rule a line, comma-separated
// KEY op "value" pairs.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Rule {
    int line = 0;
    std::string text;
    bool has(const std::string& part) const { return text.find(part) != std::string::npos; }
};

// The file the tests read: the default rules unless a test names the opt-in file.
std::string g_file = APCI_UDEV_RULES;

std::vector<std::string> lines() {
    std::ifstream f(g_file);
    EXPECT_TRUE(f) << g_file;
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

// Each test reads the file it names; the tests of every file run for both.
class UdevRulesFile : public ::testing::TestWithParam<const char*> {
  protected:
    void SetUp() override { g_file = GetParam(); }
    void TearDown() override { g_file = APCI_UDEV_RULES; }
};
INSTANTIATE_TEST_SUITE_P(Files, UdevRulesFile,
                         ::testing::Values(APCI_UDEV_RULES, APCI_UDEV_RAW_BAR_RULES));

TEST_P(UdevRulesFile, FirstRuleSkipsEverythingButAddChangeAndBind) {
    const auto all = rules();
    ASSERT_FALSE(all.empty());
    const std::string label = g_file == APCI_UDEV_RULES ? "apci8001_end" : "apci8001_raw_bar_end";
    EXPECT_EQ(all.front().text, "ACTION!=\"add|change|bind\", GOTO=\"" + label + "\"");
    EXPECT_EQ(all.back().text, "LABEL=\"" + label + "\"");
}

TEST_P(UdevRulesFile, EveryRuleIsGuardedBySubsystem) {
    const auto all = rules();
    for (std::size_t i = 1; i + 1 < all.size(); ++i)
        EXPECT_TRUE(all[i].has("SUBSYSTEM==\"")) << "line " << all[i].line << ": " << all[i].text;
}

TEST_P(UdevRulesFile, EveryRuleIsWellFormed) {
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

// Raw BAR access is root on a bus-master device without an IOMMU: not in the default rules.
TEST(UdevRules, DefaultRulesGrantNoRawBarAccess) {
    EXPECT_TRUE(rules_for("pci").empty());
    EXPECT_TRUE(rules_for("uio").empty());
    for (const auto& r : rules()) {
        EXPECT_FALSE(r.has("resource")) << "line " << r.line << ": " << r.text;
        EXPECT_FALSE(r.has("RUN")) << "line " << r.line << ": " << r.text;
    }
}

class UdevRawBarRules : public ::testing::Test {
  protected:
    void SetUp() override { g_file = APCI_UDEV_RAW_BAR_RULES; }
    void TearDown() override { g_file = APCI_UDEV_RULES; }
};

// The opt-in file says, before any rule, what it grants and why that is dangerous.
TEST_F(UdevRawBarRules, HeaderStatesTheRiskAndHowToEnableIt) {
    std::string header;
    for (const auto& line : lines()) {
        if (!line.empty() && line[0] != '#') break;
        header += line + "\n";
    }
    const char* const link_command =
        "ln -s /usr/share/apci8001/udev/61-apci8001-raw-bar.rules /etc/udev/rules.d/";
    for (const char* words :
         {"OPT-IN", "bus-master", "DMA", "IOMMU", "power\n# of root", link_command, "vfio"})
        EXPECT_NE(header.find(words), std::string::npos) << words << "\n" << header;
}

TEST_F(UdevRawBarRules, AddiDataPciBarResourceFilesBecomeGroupPlugdev0660) {
    bool found = false;
    for (const auto& r : rules_for("pci")) {
        if (!r.has("ATTR{vendor}==\"0x15b8\"")) continue;
        found = true;
        EXPECT_TRUE(r.has("chgrp plugdev /sys%p/resource[0-5]")) << r.text;
        EXPECT_TRUE(r.has("chmod 0660 /sys%p/resource[0-5]")) << r.text;
    }
    EXPECT_TRUE(found) << "no PCI rule for vendor 0x15b8";
}

// The seat user is not made root by sitting at the machine: no uaccess on a UIO node.
TEST_F(UdevRawBarRules, AddiDataUioNodesGetMode0660AndPlugdevButNoUaccess) {
    const auto uio = rules_for("uio");
    ASSERT_EQ(uio.size(), 1u);
    EXPECT_TRUE(uio[0].has("ATTRS{vendor}==\"0x15b8\"")) << uio[0].text;
    EXPECT_TRUE(uio[0].has("MODE=\"0660\"") && uio[0].has("GROUP=\"plugdev\"")) << uio[0].text;
    EXPECT_FALSE(uio[0].has("uaccess")) << uio[0].text;
    EXPECT_TRUE(rules_for("usb").empty());
}

// AMCC's 0x10e8 is on other makers' cards too: no active rule may match it by vendor.
TEST_P(UdevRulesFile, NoActiveRuleMatchesTheAmccVendorId) {
    for (const auto& r : rules())
        EXPECT_FALSE(r.has("10e8")) << "line " << r.line << ": " << r.text;
}

// The 0x10e8 rules are shipped commented out, one for each active rule, the same rule
// narrowed by a product ID placeholder (NNNN, which matches no device until replaced).
TEST_P(UdevRulesFile, AmccRulesAreCommentedOutAndNarrowedByProductId) {
    const auto templates = commented_rules();
    ASSERT_EQ(templates.size(), g_file == APCI_UDEV_RULES ? 1u : 2u);
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
