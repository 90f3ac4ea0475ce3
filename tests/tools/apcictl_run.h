// SPDX-License-Identifier: MIT
// What the tests of `apcictl run` as a process share: the fixture (a scratch directory, the
// program's files, apcictl run with --json), the JSON documents' segments read back, and the
// checks of a compensated path against its programmed contour.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apci/run/path.h"
#include "apci/run/self_approach.h"
#include "apcictl.h"
#include "rwmos/comp3d/compensation.h"
#include "rwmos/geometry/shared.h"
#include "rwmos/geometry/kinematics.h"
#include "scratch_test.h"
#include "text.h"

namespace apcictl_run_test {

using nlohmann::json;
using test_support::apcictl;
using test_support::contains;
using test_support::names_in;
using test_support::ProcessResult;
using test_support::read_text;
// geom:: is the geometry board and host share (geometry/element.h, also named rwmos::geom).
namespace c3 = rwmos::comp3d;

inline const std::string kSource = APCI_SOURCE_DIR;
inline const std::string kExamples = kSource + "/examples";
inline const std::string kFigures = APCI_SOURCE_DIR "/docs/figures";
inline constexpr double kTol = 1e-6;

inline bool exists(const std::string& path) { return test_support::path_exists(path); }

// Starts the emulator daemon serving a socket at `socket` (its standard error to /dev/null) and
// waits up to 5 s for the socket; the child's pid, or -1.
inline pid_t start_daemon(const std::string& socket) {
    const pid_t daemon = ::fork();
    if (daemon == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 2);
        ::execl(RWMOS_EMU_PATH, RWMOS_EMU_PATH, "--socket", socket.c_str(), nullptr);
        ::_exit(127);
    }
    for (int i = 0; daemon > 0 && i < 500 && !exists(socket); ++i) ::usleep(10'000);
    return daemon;
}

class ApcictlRun : public test_support::ScratchTest {
  protected:
    ApcictlRun() : ScratchTest("apcictl_run_") {}

    // A tool list with D1 of radius r and length len, in mm.
    std::string tools(double r, double len = 0.0) const {
        return write("t.tools", "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius " +
                                    std::to_string(r) + "\nwz[1].laenge " + std::to_string(len) +
                                    "\n");
    }
    // Runs a program with --json (and the given extra arguments); returns the JSON document.
    json run_json(const std::string& program, std::vector<std::string> extra = {},
                  int expected_exit = 0) {
        std::vector<std::string> args{"run", program, "--json", path("out.json")};
        args.insert(args.end(), extra.begin(), extra.end());
        last_ = apcictl(args);
        EXPECT_EQ(last_.exit_code, expected_exit) << last_.out << last_.err;
        return json::parse(read_text(path("out.json")));
    }

    ProcessResult last_;
};

// ---- JSON helpers

inline apci::run::Point point(const json& a) {
    return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()};
}

inline apci::run::PathSegment segment_of(const json& s) {
    apci::run::PathSegment p;
    p.start = point(s.at("start"));
    p.end = point(s.at("end"));
    p.kind = s.at("kind") == "arc" ? apci::run::SegmentKind::kArc : apci::run::SegmentKind::kLine;
    if (p.kind == apci::run::SegmentKind::kArc) {
        p.center = point(s.at("center"));
        p.ccw = s.at("ccw").get<bool>();
        p.plane = s.at("plane").get<int>();
    }
    return p;
}

inline std::vector<json> with_role(const json& doc, const std::string& role) {
    std::vector<json> out;
    for (const auto& s : doc.at("segments"))
        if (s.at("role") == role) out.push_back(s);
    return out;
}

inline std::string roles(const json& doc) {
    std::string out;
    for (const auto& s : doc.at("segments")) {
        if (!out.empty()) out += ' ';
        out += s.at("role").get<std::string>() + "/" + std::to_string(s.at("block").get<int>());
    }
    return out;
}

// The distance from p (in the plane's coordinates) to the nearest programmed element.
inline double distance_to_contour(const std::vector<geom::Element>& contour, const geom::Vec2& p) {
    double d = INFINITY;
    for (const auto& e : contour) d = std::min(d, geom::distance_to(e, p));
    return d;
}

// Every point of every segment with one of `roles` (21 samples each), in the plane `plane`,
// lies `r` from the programmed contour (exactly, or at least when `at_least`).
// Segments of the blocks in `skip` are left out.
inline void expect_at_radius(const json& doc, const std::vector<geom::Element>& contour, double r,
                      const std::vector<std::string>& which, bool at_least = false, int plane = 17,
                      const std::vector<int>& skip = {}) {
    const apci::run::PlaneAxes a = apci::run::plane_axes(plane);
    int checked = 0;
    for (const auto& s : doc.at("segments")) {
        if (std::find(which.begin(), which.end(), s.at("role").get<std::string>()) == which.end())
            continue;
        if (std::find(skip.begin(), skip.end(), s.at("block").get<int>()) != skip.end()) continue;
        const apci::run::PathSegment seg = segment_of(s);
        for (int i = 0; i <= 20; ++i) {
            const apci::run::Point q = apci::run::point_along(seg, i / 20.0);
            const double d = distance_to_contour(contour, {q[a.first], q[a.second]});
            if (at_least) {
                EXPECT_GE(d, r - kTol) << s.dump() << " at t=" << i / 20.0;
            } else {
                EXPECT_NEAR(d, r, kTol) << s.dump() << " at t=" << i / 20.0;
            }
            ++checked;
        }
    }
    EXPECT_GT(checked, 0);
}

inline void expect_continuous(const json& doc) {
    const auto& segs = doc.at("segments");
    for (std::size_t i = 1; i < segs.size(); ++i)
        EXPECT_LT((point(segs[i].at("start")) - point(segs[i - 1].at("end"))).norm(), 1e-9)
            << segs[i - 1].dump() << "\n"
            << segs[i].dump();
}

inline void expect_registers_clear(const json& doc) {
    for (const char* g : {"1", "2", "3"}) {
        EXPECT_EQ(doc.at("registers").at(g).at("ERROR"), 0) << g;
        EXPECT_EQ(doc.at("registers").at(g).at("STATUS"), 0) << g;
    }
}


}  // namespace apcictl_run_test
