// SPDX-License-Identifier: MIT
// Where apcictl writes (docs/apcictl.md, "Outputs"): `run`'s outputs are written beside their
// targets and renamed into place only when the whole run was written (a failed write, a full
// device, a signal leave the targets as they were and no temporary file behind); `-` is
// standard output; a program on standard input is bounded; `diff` compares runs of any length
// in the same memory.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apci/run/csv_writer.h"
#include "apci/run/run_files.h"
#include "process.h"
#include "scratch_dir.h"
#include "text.h"

namespace {

using test_support::contains;
using test_support::names_in;
using test_support::path_exists;
using test_support::read_text;
using nlohmann::json;

// How a child process is started.
struct Start {
    std::string cwd;
    std::string stdin_file = "/dev/null";
    std::vector<std::pair<std::string, std::string>> env;
    rlim_t file_size_limit = RLIM_INFINITY;  // RLIMIT_FSIZE
    bool ignore_sigxfsz = false;             // a write past the limit fails with EFBIG
    mode_t umask_value = 022;
};

struct Finished {
    int exit_code = -1;  // -1: ended by a signal
    int signal = 0;
    std::string out;
    std::string err;
    long max_rss_kib = 0;  // ru_maxrss of the child
};

class Child {
  public:
    // Starts apcictl with `args`; its standard output and error go to files in `log_dir`.
    Child(const std::vector<std::string>& args, const Start& how, const std::string& log_dir)
        : out_(log_dir + "/stdout"), err_(log_dir + "/stderr") {
        pid_ = ::fork();
        if (pid_ != 0) return;
        if (!how.cwd.empty() && ::chdir(how.cwd.c_str()) != 0) ::_exit(126);
        const int in = ::open(how.stdin_file.c_str(), O_RDONLY);
        const int out = ::open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (in < 0 || out < 0 || err < 0) ::_exit(126);
        ::dup2(in, 0);
        ::dup2(out, 1);
        ::dup2(err, 2);
        for (const auto& [name, value] : how.env) ::setenv(name.c_str(), value.c_str(), 1);
        const rlimit limit{how.file_size_limit, how.file_size_limit};
        if (how.file_size_limit != RLIM_INFINITY) ::setrlimit(RLIMIT_FSIZE, &limit);
        std::signal(SIGXFSZ, how.ignore_sigxfsz ? SIG_IGN : SIG_DFL);
        for (int sig : {SIGTERM, SIGINT, SIGHUP, SIGPIPE}) std::signal(sig, SIG_DFL);
        ::umask(how.umask_value);
        std::vector<char*> argv{const_cast<char*>(APCICTL_PATH)};
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    pid_t pid() const noexcept { return pid_; }
    Finished wait() {
        Finished f;
        int status = 0;
        rusage usage{};
        ::wait4(pid_, &status, 0, &usage);
        f.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        f.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
        f.max_rss_kib = usage.ru_maxrss;
        f.out = read_text(out_);
        f.err = read_text(err_);
        return f;
    }

  private:
    std::string out_, err_;
    pid_t pid_ = -1;
};

class ApcictlOutputs : public ::testing::Test {
  protected:
    void SetUp() override {
        ASSERT_FALSE(root_.path().empty()) << "no scratch directory";
        ASSERT_EQ(::mkdir(dir().c_str(), 0755), 0);
        ASSERT_EQ(::mkdir(tmp().c_str(), 0755), 0);
        ASSERT_EQ(::mkdir(logs().c_str(), 0755), 0);
    }

    // Where the outputs go, the child's TMPDIR, its standard output and error.
    std::string dir() const { return root_.file("out"); }
    std::string tmp() const { return root_.file("tmp"); }
    std::string logs() const { return root_.file("logs"); }
    std::string path(const std::string& name) const { return dir() + "/" + name; }
    std::string write(const std::string& name, const std::string& text) const {
        return test_support::write_text(path(name), text);
    }
    Finished run(const std::vector<std::string>& args, Start how = {}) {
        if (how.cwd.empty()) how.cwd = dir();
        how.env.emplace_back("TMPDIR", tmp());
        Child child(args, how, logs());
        return child.wait();
    }

    test_support::ScratchDir root_{"apcictl_outputs_"};
};

// A line of 10 mm at 600 mm/min: 1000 cycles.
const std::string kShort = "N10 G1 X10 F600\nM30\n";
// A line of 1000 mm at 60 mm/min: a million cycles (some seconds with --csv).
const std::string kLong = "N10 G1 X1000 F60\nM30\n";

// ---- The bound on standard input

TEST(ReadBounded, ReadsUpToTheLimitAndRefusesOneByteMore) {
    for (const std::size_t size : {std::size_t{0}, std::size_t{999}, std::size_t{1000}}) {
        int fds[2];
        ASSERT_EQ(::pipe(fds), 0);
        const std::string text(size, 'x');
        ASSERT_EQ(::write(fds[1], text.data(), text.size()), static_cast<ssize_t>(size));
        ::close(fds[1]);
        std::string got;
        int error = 0;
        EXPECT_EQ(apci::run::read_bounded(fds[0], 1000, got, error), apci::run::BoundedRead::kOk);
        EXPECT_EQ(got, text);
        ::close(fds[0]);
    }
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const std::string text(1001, 'x');
    ASSERT_EQ(::write(fds[1], text.data(), text.size()), 1001);  // the writer stays open
    std::string got;
    int error = 0;
    EXPECT_EQ(apci::run::read_bounded(fds[0], 1000, got, error), apci::run::BoundedRead::kTooLarge);
    EXPECT_EQ(got.size(), 1001u);  // refused at the first byte past the limit, no waiting
    ::close(fds[0]);
    ::close(fds[1]);
    // A read error is reported with its errno.
    std::string none;
    EXPECT_EQ(apci::run::read_bounded(-1, 1000, none, error), apci::run::BoundedRead::kError);
    EXPECT_EQ(error, EBADF);
}

TEST_F(ApcictlOutputs, StandardInputLargerThanTheLimitIsRefusedQuicklyAndNothingRuns) {
    // One byte past the limit, through a pipe (a valid program's text, repeated).
    std::string input;
    input.reserve(apci::run::kStdinProgramLimit + 1);
    while (input.size() <= apci::run::kStdinProgramLimit) input += "N10 G1 X1 F600\n";
    input.resize(apci::run::kStdinProgramLimit + 1);
    const auto begin = std::chrono::steady_clock::now();
    const auto r = test_support::run_process({APCICTL_PATH, "run", "-", "--json", path("big.json")},
                                             input, {{"TMPDIR", tmp()}});
    const auto took = std::chrono::steady_clock::now() - begin;
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(contains(r.err,
                         "apcictl: run: standard input is larger than 64 MiB; save the "
                         "program to a file and give its path instead of -\n"))
        << r.err;
    EXPECT_LT(took, std::chrono::seconds(20));
    EXPECT_FALSE(path_exists(path("big.json")));
    EXPECT_TRUE(names_in(tmp()).empty());  // no copy of standard input anywhere
    // At the limit it is read (and here parsed: a program without M30 at its end).
    input.resize(apci::run::kStdinProgramLimit - 1);
    input += "\n";
    const auto at_limit = test_support::run_process({APCICTL_PATH, "run", "-"}, input);
    EXPECT_FALSE(contains(at_limit.err, "larger than")) << at_limit.err;
}

TEST_F(ApcictlOutputs, ProgramFromStandardInputLeavesNoTemporaryFile) {
    write("p.nc", kShort);
    Start how;
    how.stdin_file = path("p.nc");
    const auto r = run({"run", "-", "--json", "p.json"}, how);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "<stdin>: 2 blocks")) << r.out;
    EXPECT_TRUE(names_in(tmp()).empty());
}

// ---- Signals

// SIGTERM, SIGINT and SIGHUP during a run (the program from standard input, --json and --csv
// under way): the process ends by the signal, no temporary file is left (of the outputs or of
// standard input), and an existing target keeps its old content.
TEST_F(ApcictlOutputs, SignalDuringARunLeavesNoTemporaryFileAndTheTargetsAsTheyWere) {
    write("long.nc", kLong);
    for (const int sig : {SIGTERM, SIGINT, SIGHUP}) {
        write("out.json", "old json\n");
        Start how;
        how.cwd = dir();
        how.stdin_file = path("long.nc");
        how.env.emplace_back("TMPDIR", tmp());
        Child child({"run", "-", "--json", "out.json", "--csv", "out.csv"}, how, logs());
        // Wait until the CSV's temporary file beside its target has grown: the run is under way.
        bool under_way = false;
        for (int i = 0; i < 1000 && !under_way; ++i) {
            for (const std::string& name : names_in(dir())) {
                struct stat st {};
                if (name.rfind(".out.csv.apcictl-", 0) == 0 &&
                    ::stat(path(name).c_str(), &st) == 0 && st.st_size > (1 << 20))
                    under_way = true;
            }
            if (!under_way) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        EXPECT_TRUE(under_way) << "signal " << sig;
        ::kill(child.pid(), sig);
        const Finished f = child.wait();
        EXPECT_EQ(f.signal, sig) << f.err;
        EXPECT_EQ(names_in(dir()), (std::set<std::string>{"long.nc", "out.json"}))
            << "signal " << sig;
        EXPECT_EQ(read_text(path("out.json")), "old json\n");
        EXPECT_TRUE(names_in(tmp()).empty()) << "signal " << sig;
    }
}

// ---- Write failures

// A write past the file size limit fails with EFBIG: the error names the output and the
// cause, no output is published (the JSON, written completely, neither), the existing CSV is
// as it was, and no temporary file remains.
TEST_F(ApcictlOutputs, FailedWriteNamesTheCauseAndPublishesNothing) {
    write("p.nc", "N10 G1 X100 F600\nM30\n");  // 10,000 cycles: about 350 KB of CSV
    write("out.csv", "old csv\n");
    Start how;
    how.file_size_limit = rlim_t{64} * 1024;
    how.ignore_sigxfsz = true;
    const auto r = run({"run", "p.nc", "--json", "out.json", "--csv", "out.csv"}, how);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "apcictl: run: cannot write out.csv: File too large\n")) << r.err;
    EXPECT_EQ(read_text(path("out.csv")), "old csv\n");
    EXPECT_EQ(names_in(dir()), (std::set<std::string>{"p.nc", "out.csv"}));
}

// The same limit with SIGXFSZ at its default: the signal ends the process, and the temporary
// files go with it.
TEST_F(ApcictlOutputs, SignalFromAFailedWriteRemovesTheTemporaryFiles) {
    write("p.nc", "N10 G1 X100 F600\nM30\n");
    Start how;
    how.file_size_limit = rlim_t{64} * 1024;
    const auto r = run({"run", "p.nc", "--json", "out.json", "--csv", "out.csv"}, how);
    EXPECT_EQ(r.signal, SIGXFSZ);
    EXPECT_EQ(names_in(dir()), (std::set<std::string>{"p.nc"}));
}

// A full device (/dev/full, written in place as any existing non-regular file is).
TEST_F(ApcictlOutputs, FullDeviceIsReportedWithItsCause) {
    write("p.nc", kShort);
    const auto r = run({"run", "p.nc", "--json", "/dev/full", "--csv", "out.csv"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "apcictl: run: cannot write /dev/full: No space left on device\n"))
        << r.err;
    EXPECT_EQ(names_in(dir()), (std::set<std::string>{"p.nc"}));  // the CSV was not published
}

// A full file system (a small tmpfs in a mount namespace of our own, where one can be made).
TEST_F(ApcictlOutputs, FullFileSystemLeavesTheTargetAndNoTemporaryFile) {
    write("p.nc", "N10 G1 X100 F600\nM30\n");
    const std::string fs = root_.file("fs");
    ASSERT_EQ(::mkdir(fs.c_str(), 0755), 0);
    const std::string script = "mount -t tmpfs -o size=128k tmpfs '" + fs + "' || exit 77\n" +
                               "printf 'old csv\\n' > '" + fs + "/out.csv'\n'" + APCICTL_PATH +
                               "' run '" + path("p.nc") + "' --json '" + fs + "/out.json' --csv '" +
                               fs + "/out.csv'\necho \"exit $?\"\nls -A '" + fs + "'\ncat '" + fs +
                               "/out.csv'\n";
    const auto r = test_support::run_process({"/usr/bin/unshare", "-rm", "/bin/sh", "-c", script});
    if (r.exit_code == 77 || r.exit_code == 127 || r.exit_code == 1)
        GTEST_SKIP() << "no tmpfs in a mount namespace here: " << r.err;
    // The CSV fills the file system; which output's write meets it first varies.
    EXPECT_TRUE(
        std::regex_search(r.err, std::regex("apcictl: run: cannot write " + fs +
                                            "/out\\.(json|csv): No space left on device\n")))
        << r.err;
    EXPECT_TRUE(contains(r.out, "exit 1\nout.csv\nold csv\n")) << r.out;
}

// ---- Replacing targets

TEST_F(ApcictlOutputs, OutputsReplaceTheirTargetsWithTheModeOfANewFile) {
    write("p.nc", kShort);
    write("out.json", "old json\n");
    ASSERT_EQ(::chmod(path("out.json").c_str(), 0640), 0);
    // A symbolic link stays a link: the file it names is replaced.
    write("real.csv", "old csv\n");
    ASSERT_EQ(::symlink("real.csv", path("link.csv").c_str()), 0);
    Start how;
    how.umask_value = 027;
    const auto r = run({"run", "p.nc", "--json", "out.json", "--csv", "link.csv", "--svg",
                        "/dev/null", "--tools-out", "out.tools"},
                       how);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json doc = json::parse(read_text(path("out.json")));
    EXPECT_EQ(doc.at("segments").size(), 1u);
    struct stat st {};
    ASSERT_EQ(::stat(path("out.json").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0640u);  // 0666 less the umask 027
    ASSERT_EQ(::stat(path("out.tools").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0640u);
    ASSERT_EQ(::lstat(path("link.csv").c_str(), &st), 0);
    EXPECT_TRUE(S_ISLNK(st.st_mode));
    EXPECT_TRUE(read_text(path("real.csv")).rfind("cycle,time_s,X,Y,Z", 0) == 0);
    ASSERT_EQ(::stat("/dev/null", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
    EXPECT_EQ(names_in(dir()),
              (std::set<std::string>{"p.nc", "out.json", "real.csv", "link.csv", "out.tools"}));
}

TEST_F(ApcictlOutputs, OutputThatCannotBeMadeIsRefusedBeforeTheRun) {
    write("p.nc", kShort);
    ASSERT_EQ(::mkdir(path("adir").c_str(), 0755), 0);
    const auto r = run({"run", "p.nc", "--json", "adir"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(contains(r.err, "apcictl: run: cannot write adir: Is a directory\n")) << r.err;
    const auto missing = run({"run", "p.nc", "--csv", "no/such/out.csv"});
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_TRUE(contains(missing.err,
                         "apcictl: run: cannot write no/such/out.csv: No such file or directory\n"))
        << missing.err;
    EXPECT_EQ(names_in(dir()), (std::set<std::string>{"p.nc", "adir"}));
}

// ---- OutputFile in the process

// The write(2) calls this thread has made (/proc/thread-self/io: a sanitizer's or the test
// framework's other threads do not count), -1 when the kernel does not count.
long write_calls() {
    std::ifstream io("/proc/thread-self/io");
    std::string key;
    long value = -1;
    while (io >> key >> value)
        if (key == "syscw:") return value;
    return -1;
}

// Published whole, in large writes: 100,000 CSV lines (about 4 MB) reach the file in pieces of
// 1 MiB (the bound below allows one write per 64 KiB), not one write a line; until publish() the target keeps its old content, and
// discard() leaves it so.
TEST_F(ApcictlOutputs, OutputFileWritesInLargePiecesAndPublishesByRename) {
    write("trace.csv", "old\n");
    apci::run::OutputFile out;
    ASSERT_EQ(out.open(path("trace.csv")), "");
    EXPECT_EQ(out.temporary().rfind(path(".trace.csv.apcictl-"), 0), 0u) << out.temporary();
    const long before = write_calls();
    {
        const std::vector<std::string> axes{"X", "Y", "Z"};
        apci::run::TraceCsvWriter csv(out.file(), axes);
        const std::array<double, 3> p{1.25, -2.5, 0.125};
        for (std::uint64_t i = 1; i <= 100000; ++i) csv.sample(i, 0.001 * i, p);
        ASSERT_TRUE(csv.finish());
    }
    ASSERT_EQ(out.close(), "");
    const long calls = write_calls() - before;
    struct stat st {};
    ASSERT_EQ(::stat(out.temporary().c_str(), &st), 0);
    // AddressSanitizer makes write(2) calls of its own on this thread (16 bytes to a pipe, its
    // check that memory is readable), so the count means something only without it.
#if defined(__SANITIZE_ADDRESS__)
    constexpr bool kCounted = false;
#else
    constexpr bool kCounted = true;
#endif
    if (kCounted && before >= 0) {
        EXPECT_LE(calls, st.st_size / 65536 + 4)
            << st.st_size << " bytes in " << calls << " writes";
    }
    EXPECT_EQ(read_text(path("trace.csv")), "old\n");
    ASSERT_EQ(out.publish(), "");
    EXPECT_EQ(read_text(path("trace.csv")).size(), static_cast<std::size_t>(st.st_size));
    EXPECT_EQ(names_in(dir()), (std::set<std::string>{"trace.csv"}));

    apci::run::OutputFile dropped;
    ASSERT_EQ(dropped.open(path("trace.csv")), "");
    std::fputs("new\n", dropped.file());
    dropped.discard();
    EXPECT_EQ(read_text(path("trace.csv")).size(), static_cast<std::size_t>(st.st_size));
    EXPECT_EQ(names_in(dir()), (std::set<std::string>{"trace.csv"}));
}

// ---- "-" is standard output

TEST_F(ApcictlOutputs, DashWritesTheOutputToStandardOutputAndTheSummaryToStandardError) {
    write("p.nc", kShort);
    const auto j = run({"run", "p.nc", "--json", "-", "--csv", "out.csv"});
    ASSERT_EQ(j.exit_code, 0) << j.err;
    const json doc = json::parse(j.out);  // nothing else on standard output
    EXPECT_EQ(doc.at("segments").size(), 1u);
    EXPECT_TRUE(contains(j.err, "p.nc: 2 blocks, 2 sent to the board, 1 segment executed")) << j.err;
    EXPECT_TRUE(path_exists(path("out.csv")));
    const auto c = run({"run", "p.nc", "--csv", "-"});
    ASSERT_EQ(c.exit_code, 0) << c.err;
    EXPECT_TRUE(c.out.rfind("cycle,time_s,X,Y,Z", 0) == 0) << c.out.substr(0, 100);
    EXPECT_EQ(std::count(c.out.begin(), c.out.end(), '\n'), 1001);
    const auto s = run({"run", "p.nc", "--svg", "-"});
    ASSERT_EQ(s.exit_code, 0) << s.err;
    EXPECT_TRUE(contains(s.out, "<svg")) << s.out.substr(0, 200);
    EXPECT_TRUE(contains(s.out, "</svg>\n"));
    // The program from standard input and the output on standard output.
    Start how;
    how.stdin_file = path("p.nc");
    const auto both = run({"run", "-", "--json", "-"}, how);
    ASSERT_EQ(both.exit_code, 0) << both.err;
    EXPECT_EQ(json::parse(both.out).at("segments").size(), 1u);
    EXPECT_EQ(names_in(dir()), (std::set<std::string>{"p.nc", "out.csv"}));  // no file "-"
}

// Outputs named by a link to a pipe: /dev/stdout and /dev/stderr when they are pipes, and
// /dev/fd/N (what a shell's >(...) gives). The link names the pipe as "pipe:[N]", which is no
// path: resolving it said "cannot write /dev/stdout: No such file or directory". Written in
// place through the link; the summary goes to standard error when the output is standard
// output under another name.
TEST_F(ApcictlOutputs, AnOutputThatIsALinkToAPipeIsWrittenThroughIt) {
    const std::string program = write("p.nc", kShort);
    auto r = test_support::run_process({APCICTL_PATH, "run", program, "--json", "/dev/stdout"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(json::parse(r.out).at("segments").size(), 1u);  // the summary is not in it
    EXPECT_TRUE(contains(r.err, "p.nc: 2 blocks, 2 sent to the board, 1 segment executed")) << r.err;
    r = test_support::run_process({APCICTL_PATH, "run", program, "--svg", "/dev/stderr"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "</svg>\n")) << r.err.substr(0, 200);
    EXPECT_TRUE(contains(r.out, "p.nc: 2 blocks")) << r.out;
    // /dev/fd/3, a pipe (the test's own standard output pipe, as 3>&1), as >(...) would be.
    r = test_support::run_process({"/bin/sh", "-c",
                                   "exec \"$0\" run \"$1\" --csv /dev/fd/3 3>&1 1>/dev/null",
                                   APCICTL_PATH, program});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.out.starts_with("cycle,time_s,X,Y,Z")) << r.out.substr(0, 100);
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1001);
    EXPECT_EQ(names_in(dir()), (std::set<std::string>{"p.nc"}));
}

// A program that is not a regular file (a pipe: /dev/stdin, a shell's <(...)) is read once:
// where the program is validated before it runs (an output on standard output, any board but
// the embedded one) it was read twice, and the second pass found the pipe empty: "the
// program ends without M30".
TEST_F(ApcictlOutputs, AProgramFromAPipeIsReadOnce) {
    auto r = test_support::run_process({APCICTL_PATH, "run", "/dev/stdin", "--json", "-"}, kShort);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(json::parse(r.out).at("segments").size(), 1u);
    EXPECT_TRUE(contains(r.err, "/dev/stdin: 2 blocks, 2 sent to the board, 1 segment executed")) << r.err;
    r = test_support::run_process({APCICTL_PATH, "run", "/dev/stdin", "--csv", "-"}, kShort);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1001);
    // An error names the pipe's line as it would a file's.
    r = test_support::run_process({APCICTL_PATH, "run", "/dev/stdin", "--json", "-"},
                                  "N10 G1 X10 F600\nN20 G7\nM30\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "/dev/stdin:2:")) << r.err;
    EXPECT_FALSE(contains(r.err, "without M30")) << r.err;
}

TEST_F(ApcictlOutputs, TwoOutputsOnStandardOutputAreAUsageError) {
    write("p.nc", kShort);
    const auto r = run({"run", "p.nc", "--json", "-", "--svg", "-"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(contains(r.err,
                         "apcictl: run: --json and --svg both write to standard output "
                         "(-); give one of them a file\n"))
        << r.err;
    const auto c = run({"run", "p.nc", "--csv", "-", "--tools-out", "-"});
    EXPECT_EQ(c.exit_code, 2);
    EXPECT_TRUE(contains(c.err, "--csv and --tools-out both write to standard output")) << c.err;
    // The same-file check still holds for the file outputs beside a "-".
    const auto same = run({"run", "p.nc", "--json", "-", "--csv", "x", "--svg", "x"});
    EXPECT_EQ(same.exit_code, 2);
    EXPECT_TRUE(contains(same.err, "--csv 'x' is the same file as --svg 'x'")) << same.err;
    EXPECT_EQ(names_in(dir()), (std::set<std::string>{"p.nc"}));
}

// ---- diff in bounded memory

// A million interpolation cycles (a slow 1000 mm move) on both boards: the old diff kept
// every cycle of both runs in memory (about 190 MB here); now its peak stays that of a short
// run.
TEST_F(ApcictlOutputs, DiffOfAMillionCyclesStaysInBoundedMemory) {
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer keeps freed memory in its quarantine (256 MB by default) and shadows
    // every byte: the peak RSS of an instrumented apcictl says nothing about what it keeps.
    // The measurement runs in every build without ASan.
    GTEST_SKIP() << "peak RSS of an AddressSanitizer build is the sanitizer's";
#endif
    write("long.nc", kLong);
    const auto r = run({"diff", "--against", "emu:", "long.nc"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "(1000000 interpolation cycles compared)")) << r.out;
    EXPECT_LT(r.max_rss_kib, 64 * 1024) << "peak RSS " << r.max_rss_kib << " KiB";
}

}  // namespace
