// SPDX-License-Identifier: MIT
#include "linuxcnc.h"
#include "text.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

namespace apci::test {
namespace {

using test_support::read_text;

bool is_file(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

// A scratch directory, removed with its files.
class Scratch {
  public:
    Scratch() {
        const char* tmp = std::getenv("TMPDIR");
        std::string templ = std::string(tmp != nullptr && *tmp ? tmp : "/tmp") + "/apci-rs274-XXXXXX";
        if (::mkdtemp(templ.data()) != nullptr) dir_ = templ;
    }
    ~Scratch() {
        for (const std::string& f : files_) ::unlink(f.c_str());
        if (!dir_.empty()) ::rmdir(dir_.c_str());
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    bool ok() const { return !dir_.empty(); }
    std::string file(const std::string& name) {
        files_.push_back(dir_ + "/" + name);
        return files_.back();
    }
    std::string path(const std::string& name) const { return dir_ + "/" + name; }

  private:
    std::string dir_;
    std::vector<std::string> files_;
};

// The directory the child uses as its home, and what it leaves there.
struct Home {
    std::string dir;
    void remove() const {
        ::unlink((dir + "/.tool.mmap").c_str());
        ::rmdir(dir.c_str());
    }
};

// Starts rs274 on one program, its standard output and error to files. rs274 keeps its tool
// data in $HOME/.tool.mmap (truncated at start): every run gets a home of its own, so runs in
// parallel do not share it and nobody's real home is touched.
pid_t start(const Rs274& rs, const std::string& table, const std::string& ini,
            const std::string& program, const std::string& out, const std::string& err,
            const std::string& home) {
    const pid_t pid = ::fork();
    if (pid != 0) return pid;
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int in = ::open("/dev/null", O_RDONLY);
    if (o < 0 || e < 0 || in < 0) ::_exit(126);
    ::dup2(in, 0);
    ::dup2(o, 1);
    ::dup2(e, 2);
    ::setenv("LD_LIBRARY_PATH", rs.library_path.c_str(), 1);
    ::setenv("HOME", home.c_str(), 1);
    std::vector<const char*> argv{rs.binary.c_str(), "-t", table.c_str()};
    if (!ini.empty()) argv.insert(argv.end(), {"-i", ini.c_str()});
    argv.insert(argv.end(), {"-g", program.c_str(), nullptr});
    ::execv(argv[0], const_cast<char* const*>(argv.data()));
    _exit(127);  // unqualified: cppcheck knows it does not return
}

// The numbers between the parentheses of "NAME(a, b, c)".
std::vector<double> arguments(const std::string& line, std::size_t open) {
    std::vector<double> out;
    const char* p = line.c_str() + open + 1;
    while (*p != '\0' && *p != ')') {
        char* end = nullptr;
        const double v = std::strtod(p, &end);
        if (end == p) break;
        out.push_back(v);
        p = end;
        while (*p == ',' || *p == ' ') ++p;
    }
    return out;
}

// Reads the canonical moves of one run in plane coordinates.
std::vector<CanonMove> parse_moves(const std::string& text, int plane) {
    std::vector<CanonMove> out;
    rwmos::geom::Vec2 at = rwmos::geom::Vec2::Zero();
    std::istringstream lines(text);
    std::string line;
    int compensation = 40;
    const auto to_plane = [plane](const std::vector<double>& v) {
        // STRAIGHT_*(x, y, z, ...)
        return plane == 18 ? rwmos::geom::Vec2(v[2], v[0]) : rwmos::geom::Vec2(v[0], v[1]);
    };
    const auto third_of = [plane](const std::vector<double>& v) {
        return plane == 18 ? v[1] : v[2];
    };
    while (std::getline(lines, line)) {
        std::size_t open = std::string::npos;
        CanonMove m;
        if (line.find("COMMENT(\"interpreter: cutter radius compensation ") != std::string::npos) {
            compensation = line.find("compensation on left") != std::string::npos    ? 41
                           : line.find("compensation on right") != std::string::npos ? 42
                                                                                     : 40;
            continue;
        }
        if ((open = line.find("STRAIGHT_TRAVERSE(")) != std::string::npos) {
            const auto v = arguments(line, line.find('(', open));
            if (v.size() < 3) continue;
            m.rapid = true;
            m.path = rwmos::geom::make_line(at, to_plane(v));
            m.third = third_of(v);
        } else if ((open = line.find("STRAIGHT_FEED(")) != std::string::npos) {
            const auto v = arguments(line, line.find('(', open));
            if (v.size() < 3) continue;
            m.path = rwmos::geom::make_line(at, to_plane(v));
            m.third = third_of(v);
        } else if ((open = line.find("ARC_FEED(")) != std::string::npos) {
            // ARC_FEED(first_end, second_end, first_axis, second_axis, rotation, axis_end, ...):
            // first and second are the plane's (G17 X, Y; G18 Z, X), rotation > 0 ccw.
            const auto v = arguments(line, line.find('(', open));
            if (v.size() < 6) continue;
            m.path = rwmos::geom::make_arc(at, {v[0], v[1]}, {v[2], v[3]}, v[4] > 0);
            m.third = v[5];
        } else {
            continue;
        }
        at = m.path.end;
        m.compensation = compensation;
        out.push_back(m);
    }
    return out;
}

std::string last_line(const std::string& text) {
    std::size_t end = text.find_last_not_of("\n ");
    if (end == std::string::npos) return {};
    std::size_t begin = text.rfind('\n', end);
    begin = begin == std::string::npos ? 0 : begin + 1;
    // rs274 prints the message, then the offending block: keep both, on one line.
    std::size_t before = begin >= 2 ? text.rfind('\n', begin - 2) : std::string::npos;
    before = before == std::string::npos ? 0 : before + 1;
    std::string s = text.substr(before, end + 1 - before);
    for (char& c : s)
        if (c == '\n') c = '|';
    return s;
}

}  // namespace

std::string rs274_tool_table(double radius_mm) {
    char line[96];
    std::snprintf(line, sizeof line, "T1 P1 D%.15f ;tool radius %.6f mm\n", 2 * radius_mm / 25.4,
                  radius_mm);
    return line;
}

Rs274 find_rs274(const std::string& root) {
    Rs274 rs;
    rs.binary = root + "/usr/bin/rs274";
    rs.library_path = root + "/usr/lib:" + root + "/usr/lib/x86_64-linux-gnu";
    rs.ncfiles = root + "/usr/share/linuxcnc/ncfiles";
    if (!is_file(rs.binary)) {
        rs.why = "LinuxCNC's rs274 is not unpacked at " + rs.binary +
                 " (scripts/fetch_linuxcnc.sh fetches Debian's linuxcnc-uspace; ./test.sh runs it)";
        return rs;
    }
    const std::vector<std::string> probe{"G21 G17\nG1 X1 F100\nM2\n"};
    const auto r = run_rs274(rs, probe, rs274_tool_table(1.0), 17, 1);
    if (r.empty() || !r[0].ran || r[0].exit_code != 0 || r[0].moves.empty())
        rs.why = "rs274 at " + rs.binary + " does not run: " +
                 (r.empty() ? std::string("no result") : r[0].error);
    return rs;
}

std::vector<Rs274Result> run_rs274(const Rs274& rs, const std::vector<std::string>& programs,
                                   const std::string& tool_table, int plane, int parallel,
                                   const Rs274Subroutines& subroutines) {
    std::vector<Rs274Result> results(programs.size());
    Scratch scratch;
    if (!scratch.ok()) return results;
    const std::string table = scratch.file("tools.tbl");
    write_file(table, tool_table);
    // The subroutines: the given files in a directory of their own, searched first.
    std::string ini;
    std::optional<Scratch> sub_dir;
    if (!subroutines.empty()) {
        sub_dir.emplace();
        if (!sub_dir->ok()) return results;
        std::string path = sub_dir->path("");
        path.pop_back();  // the directory itself, without the '/'
        for (const auto& [name, text] : subroutines.files) write_file(sub_dir->file(name), text);
        for (const std::string& d : subroutines.directories) path += ":" + d;
        ini = scratch.file("rs274.ini");
        write_file(ini, "[RS274NGC]\nSUBROUTINE_PATH = " + path + "\n");
    }
    struct Job {
        std::size_t index;
        std::string program, out, err;
        Home home;
    };
    std::map<pid_t, Job> running;
    std::size_t next = 0;
    const auto finish_one = [&] {
        int status = 0;
        const pid_t pid = ::waitpid(-1, &status, 0);
        auto it = running.find(pid);
        if (it == running.end()) return;
        Rs274Result& r = results[it->second.index];
        r.ran = WIFEXITED(status);
        r.exit_code = r.ran ? WEXITSTATUS(status) : -1;
        r.moves = parse_moves(read_text(it->second.out), plane);
        if (r.exit_code != 0) r.error = last_line(read_text(it->second.err));
        ::unlink(it->second.program.c_str());
        ::unlink(it->second.out.c_str());
        ::unlink(it->second.err.c_str());
        it->second.home.remove();
        running.erase(it);
    };
    while (next < programs.size() || !running.empty()) {
        while (next < programs.size() && static_cast<int>(running.size()) < parallel) {
            const std::string stem = std::to_string(next);
            Job job{next, scratch.file(stem + ".ngc"), scratch.file(stem + ".out"),
                    scratch.file(stem + ".err"), Home{scratch.path(stem + ".home")}};
            write_file(job.program, programs[next]);
            if (::mkdir(job.home.dir.c_str(), 0700) != 0) break;
            const pid_t pid = start(rs, table, ini, job.program, job.out, job.err, job.home.dir);
            if (pid < 0) {
                job.home.remove();
                break;
            }
            running.emplace(pid, std::move(job));
            ++next;
        }
        if (running.empty()) break;
        finish_one();
    }
    return results;
}

const Rs274& test_rs274() {
    static const Rs274 rs = [] {
        const char* env = std::getenv("APCI_LINUXCNC_ROOT");
        return find_rs274(env != nullptr && *env ? env : APCI_LINUXCNC_ROOT);
    }();
    return rs;
}

}  // namespace apci::test
