// SPDX-License-Identifier: MIT
// apcictl as the conventions of command-line tools have it (docs/apcictl.md): `help COMMAND`,
// --version naming program, package and version, an exit status that says when the output
// could not be written, and object-name suggestions that keep the index typed without brackets.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <regex>

#include "apcictl.h"
#include "objif/names.h"

namespace {

using test_support::ProcessResult;

// apcictl ARGS with its standard output sent to `redirect` (a shell redirection: ">/dev/full",
// ">&-" closes it).
ProcessResult apcictl_with_stdout(const std::string& args, const std::string& redirect,
                                  const std::string& input = {}) {
    return test_support::run_process(
        {"/bin/sh", "-c", std::string("exec \"$0\" ") + args + " " + redirect, APCICTL_PATH},
        input);
}

// ---- help and --version

TEST(ApcictlHelp, HelpCommandShowsTheCommandsHelp) {
    for (const std::string command : {"read", "run", "script", "status"}) {
        const auto help = test_support::apcictl({"help", command});
        const auto flag = test_support::apcictl({command, "--help"});
        EXPECT_EQ(help.exit_code, 0) << help.err;
        EXPECT_EQ(help.err, "");
        EXPECT_EQ(help.out, flag.out) << command;
        EXPECT_NE(help.out.find("Usage: apcictl " + command), std::string::npos) << help.out;
    }
}

// The commands `apcictl --help` lists under "Subcommands:", `help` among them.
std::vector<std::string> listed_commands() {
    const auto help = test_support::apcictl({"--help"});
    std::vector<std::string> commands;
    bool in_list = false;
    std::size_t start = 0;
    while (start < help.out.size()) {
        std::size_t end = help.out.find('\n', start);
        if (end == std::string::npos) end = help.out.size();
        const std::string line = help.out.substr(start, end - start);
        start = end + 1;
        if (line == "Subcommands:") {
            in_list = true;
        } else if (in_list) {
            std::smatch m;
            if (!std::regex_match(line, m, std::regex("  ([a-z]+) .*"))) break;
            commands.push_back(m[1]);
        }
    }
    return commands;
}

// `help COMMAND` for every command apcictl lists, `help` too (it said "unknown command 'help';
// did you mean 'shell'?"): the command's own --help, exit 0.
TEST(ApcictlHelp, HelpOfEveryListedCommandIsItsHelp) {
    const auto commands = listed_commands();
    ASSERT_GE(commands.size(), 14u) << "apcictl --help lists too few commands";
    EXPECT_NE(std::find(commands.begin(), commands.end(), "help"), commands.end());
    for (const std::string& command : commands) {
        SCOPED_TRACE(command);
        const auto help = test_support::apcictl({"help", command});
        const auto flag = test_support::apcictl({command, "--help"});
        EXPECT_EQ(help.exit_code, 0) << help.err;
        EXPECT_EQ(help.err, "");
        EXPECT_EQ(help.out, flag.out);
        EXPECT_NE(help.out.find("Usage: apcictl " + command + " "), std::string::npos) << help.out;
    }
}

TEST(ApcictlHelp, HelpAloneShowsTheProgramsHelp) {
    const auto help = test_support::apcictl({"help"});
    EXPECT_EQ(help.exit_code, 0) << help.err;
    EXPECT_EQ(help.out, test_support::apcictl({"--help"}).out);
    EXPECT_NE(help.out.find("Usage: apcictl [OPTIONS] SUBCOMMAND"), std::string::npos);
    // Through --device too (the option before the command, as for every command).
    EXPECT_EQ(test_support::apcictl({"--device", "emu:", "help", "read"}).out,
              test_support::apcictl({"read", "--help"}).out);
}

TEST(ApcictlHelp, HelpOfAnUnknownCommandSaysWhatWasMeant) {
    const auto r = test_support::apcictl({"help", "raed"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "apcictl: help: unknown command 'raed'; did you mean 'read'?\n");
    const auto far = test_support::apcictl({"help", "frobnicate"});
    EXPECT_EQ(far.exit_code, 2);
    EXPECT_EQ(far.err.rfind("apcictl: help: unknown command 'frobnicate' (commands: read, ", 0),
              0u)
        << far.err;
}

TEST(ApcictlHelp, MistypedHelpMeansHelpNotShell) {
    const auto r = test_support::apcictl({"hlep"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "apcictl: unknown command 'hlep'; did you mean 'help'?\n");
}

TEST(ApcictlHelp, HelpIsNoScriptLine) {
    const auto r = test_support::apcictl({"script", "-"}, "help read\n");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("apcictl: line 1: "), std::string::npos) << r.err;
}

TEST(ApcictlVersion, VersionNamesProgramPackageVersionAndLibrary) {
    const auto r = test_support::apcictl({"--version"});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out, std::string("apcictl (apci8001) ") + APCI8001_VERSION + "\nlibapci " +
                         APCI8001_VERSION + "\n");
    EXPECT_EQ(r.err, "");
}

// ---- the output cannot be written

// Each command that prints, with its standard output on a full device and closed: exit 1 and
// one line saying so, never 0, never "internal error".
TEST(ApcictlOutput, FailedWriteOfTheOutputIsAnError) {
    const std::vector<std::pair<std::string, std::string>> commands{
        {"read 1300 1 1 7", ""},
        {"read tc.group[0].radius", ""},
        {"status", ""},
        {"dump", ""},
        {"dump --json", ""},
        {"list", ""},
        {"help", ""},
        {"--version", ""},
        {"read --help", ""},
        {"script -", "read 1300 1 1 7\nstatus\n"},
        {"status --json", ""},
        {"step 10", ""},
        {"shell", "read 1300 1 1 7\nstatus\n"},
        {"run " + std::string(APCI_SOURCE_DIR) + "/examples/wr_quad_disc.nc --tools " +
             APCI_SOURCE_DIR + "/examples/tools/wr_quad_disc.tools",
         ""},
        {"diff --against emu: " + std::string(APCI_SOURCE_DIR) + "/examples/wr_quad_disc.nc " +
             "--tools " + APCI_SOURCE_DIR + "/examples/tools/wr_quad_disc.tools",
         ""},
    };
    for (const auto& [args, input] : commands) {
        for (const auto& [redirect, reason] :
             {std::pair<std::string, std::string>{">/dev/full", "No space left on device"},
              {">&-", "Bad file descriptor"}}) {
            SCOPED_TRACE(args + " " + redirect);
            const auto r = apcictl_with_stdout(args, redirect, input);
            if (args == "list" && r.exit_code == 0) continue;  // no boards: nothing to write
            EXPECT_EQ(r.exit_code, 1);
            EXPECT_EQ(r.err, "apcictl: cannot write standard output: " + reason + "\n");
        }
    }
}

TEST(ApcictlOutput, OutputThatFitsStillExitsZero) {
    const auto r = apcictl_with_stdout("read 1300 1 1 7", ">/dev/null");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
}

// ---- status --json

// The same registers as the text: each group's ERROR and STATUS values, the plane, the spooler.
TEST(ApcictlStatusJson, SaysWhatTheTextSays) {
    // A refused STATUS = 1 sets group 1's InitError first (docs/apcictl.md, "status").
    const std::string script = "write 1300 1 1 3 1\n";
    const auto text = test_support::apcictl({"script", "--keep-going", "-"}, script + "status\n");
    const auto json = test_support::apcictl({"script", "--keep-going", "-"}, script + "status --json\n");
    ASSERT_EQ(text.exit_code, 1) << text.err;
    ASSERT_EQ(json.exit_code, 1) << json.err;
    const auto j = nlohmann::json::parse(json.out);
    EXPECT_EQ(j["tc"]["groups"][0]["error"]["value"], 1);
    EXPECT_EQ(j["tc"]["groups"][0]["error"]["set"], nlohmann::json::array({"InitError"}));
    EXPECT_EQ(j["spooler"]["fill"], 0);
    EXPECT_EQ(j["spooler"]["capacity"], 256);
    EXPECT_NE(text.out.find("spooler 0 of 256 profiles"), std::string::npos) << text.out;
    EXPECT_EQ(j["tc"]["plane"], 17);
    EXPECT_EQ(j["tc"]["plane_name"], "X-Y");
    ASSERT_EQ(j["tc"]["groups"].size(), 4u);
    const std::regex line(R"re((group \d|active group): ERROR 0x([0-9A-F]+) [^;]*; STATUS 0x([0-9A-F]+))re");
    std::size_t k = 0;
    for (std::sregex_iterator it(text.out.begin(), text.out.end(), line), end; it != end; ++it, ++k) {
        ASSERT_LT(k, 4u);
        const auto& g = j["tc"]["groups"][k];
        EXPECT_EQ(g["group"], k < 3 ? static_cast<int>(k + 1) : 0);
        EXPECT_EQ(g["active"], k == 3);
        EXPECT_EQ(g["error"]["value"], std::stoi((*it)[2].str(), nullptr, 16)) << (*it)[0];
        EXPECT_EQ(g["status"]["value"], std::stoi((*it)[3].str(), nullptr, 16)) << (*it)[0];
        for (const char* reg : {"error", "status"})
            EXPECT_EQ(g[reg]["set"].size(),
                      static_cast<std::size_t>(std::popcount(g[reg]["value"].get<unsigned>())));
    }
    EXPECT_EQ(k, 4u);
}

TEST(ApcictlStatusJson, WithoutOptionTcTheTcIsNull) {
    const auto r = test_support::apcictl({"--device", "emu:?no-option-tc", "status", "--json"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out,
              "{\"motion\":{\"held\":false,\"served\":true},\"spooler\":{\"capacity\":256,"
              "\"fill\":0},\"tc\":null}\n");
}

// ---- object names typed without brackets

TEST(ObjectNameSuggestion, IndexTypedWithoutBracketsIsKept) {
    EXPECT_EQ(objif::closest_names("tc.group2.radius"),
              std::vector<std::string_view>{"tc.group[2].radius"});
    EXPECT_EQ(objif::closest_names("tc.group3.radius"),
              std::vector<std::string_view>{"tc.group[3].radius"});
    // A module key with a digit (comp3d) is not taken for an index.
    EXPECT_EQ(objif::closest_names("comp3d.tool5.r"),
              std::vector<std::string_view>{"comp3d.tool[5].r"});
    EXPECT_EQ(objif::closest_names("comp3d.tool17.r"),
              std::vector<std::string_view>{"comp3d.tool[17].r"});
    // Out of the range: brought into it, as for a bracketed index.
    EXPECT_EQ(objif::closest_names("tc.group7.radius"),
              std::vector<std::string_view>{"tc.group[3].radius"});
    // Bracketed, as before.
    EXPECT_EQ(objif::closest_names("tc.group[1].radus"),
              std::vector<std::string_view>{"tc.group[1].radius"});
}

TEST(ObjectNameSuggestion, ApcictlSuggestsTheTypedGroup) {
    const auto r = test_support::apcictl({"read", "tc.group2.radius"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err,
              "apcictl: unknown object 'tc.group2.radius'; did you mean 'tc.group[2].radius'?\n");
}

}  // namespace
