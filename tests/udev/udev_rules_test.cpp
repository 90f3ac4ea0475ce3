// SPDX-License-Identifier: MIT
// udev/60-apci8001.rules (docs/transports.md, "Permissions for real boards"): every rule
// guarded by ACTION and SUBSYSTEM; USB and UIO nodes for the seat user
// (uaccess) and group plugdev, mode 0660; the PCI BAR resource files made
// group-accessible; both vendor IDs. udevadm cannot check rules without a
// device here, so the rules are read the way udev reads them: one rule a
// line, comma-separated KEY op "value" pairs.
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

std::vector<Rule> rules() {
    std::ifstream f(APCI_UDEV_RULES);
    EXPECT_TRUE(f) << APCI_UDEV_RULES;
    std::vector<Rule> out;
    std::string line;
    for (int n = 1; std::getline(f, line); ++n) {
        if (line.empty() || line[0] == '#') continue;
        out.push_back({n, line});
    }
    return out;
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
    // KEY[{attr}] op "value", separated by ", ".
    const std::regex pair(R"re([A-Z_]+(\{[A-Za-z_]+\})?(==|!=|\+=|=)"[^"]*")re");
    for (const auto& r : rules()) {
        std::string rest = r.text;
        std::smatch m;
        while (std::regex_search(rest, m, pair) && m.position(0) == 0) {
            rest = m.suffix().str();
            if (rest.rfind(", ", 0) == 0) rest = rest.substr(2);
        }
        EXPECT_EQ(rest, "") << "line " << r.line << " does not parse from: " << rest;
    }
}

TEST(UdevRules, UsbBoardsOfBothVendorsGetUaccessMode0660AndPlugdev) {
    const auto usb = rules_for("usb");
    for (const char* vendor : {"15b8", "10e8"}) {
        bool found = false;
        for (const auto& r : usb) {
            if (!r.has(std::string("ATTR{idVendor}==\"") + vendor + "\"")) continue;
            found = true;
            EXPECT_TRUE(r.has("ENV{DEVTYPE}==\"usb_device\"")) << r.text;
            EXPECT_TRUE(r.has("TAG+=\"uaccess\"")) << r.text;
            EXPECT_TRUE(r.has("MODE=\"0660\"")) << r.text;
            EXPECT_TRUE(r.has("GROUP=\"plugdev\"")) << r.text;
        }
        EXPECT_TRUE(found) << "no USB rule for vendor " << vendor;
    }
}

TEST(UdevRules, PciBarResourceFilesOfBothVendorsBecomeGroupPlugdev0660) {
    const auto pci = rules_for("pci");
    for (const char* vendor : {"0x15b8", "0x10e8"}) {
        bool found = false;
        for (const auto& r : pci) {
            if (!r.has(std::string("ATTR{vendor}==\"") + vendor + "\"")) continue;
            found = true;
            EXPECT_TRUE(r.has("chgrp plugdev /sys%p/resource[0-5]")) << r.text;
            EXPECT_TRUE(r.has("chmod 0660 /sys%p/resource[0-5]")) << r.text;
        }
        EXPECT_TRUE(found) << "no PCI rule for vendor " << vendor;
    }
}

TEST(UdevRules, UioNodesOfBothVendorsGetUaccessMode0660AndPlugdev) {
    const auto uio = rules_for("uio");
    ASSERT_EQ(uio.size(), 2u);
    for (const auto& r : uio) {
        EXPECT_TRUE(r.has("TAG+=\"uaccess\"") && r.has("MODE=\"0660\"") &&
                    r.has("GROUP=\"plugdev\""))
            << r.text;
    }
}

}  // namespace
