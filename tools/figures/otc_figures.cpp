// SPDX-License-Identifier: MIT
// otc_figures: draws the figures of docs/otc.md that apcictl's plot cannot show (the wear is
// millimetres on paths of hundreds): the emulator itself (rwmos_emu) runs each scene, cycle by
// cycle, and the figures plot the offsets it computed.
//
//   otc_figures DIR           writes DIR/otc-<name>.svg
//   otc_figures --check DIR   exit 1 if a file in DIR differs from what would be written
//
// Scenes ([ISG-OTC]): the three modes on LENGTH (section 2.1), the tilted disc (2.3.1),
// TOOL_DIR with the B head (2.4), SURF_NORM_DIR on the profile of [ISG-OTC] (2.5).
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "figure_files.h"
#include "objif/descriptor.h"
#include "rwmos/board.h"
#include "rwmos/board_state.h"
#include "rwmos/geometry/kinematics.h"
#include "rwmos/object_map.h"
#include "rwmos/otc/direction.h"

namespace {

namespace otc = rwmos::otc;
using rwmos::motion::AxisVector;
using rwmos::motion::Profile;
using rwmos::motion::ProfileKind;

// ---- The emulator, driven as the tests drive it

class Scene {
  public:
    Scene() {
        write_int(otc::kDevTool, otc::kIdxToolNumber, 1);
        write_int(otc::kDevTool, otc::kIdxToolType, otc::kGrindingToolType);
        write_double(otc::kDevTool, otc::kIdxToolWearConst, 100000.0);  // [ISG-OTC] 2.6
        write_double(otc::kDevTool, otc::kIdxToolMaxInfeed, 200000.0);
    }
    void write_int(std::int32_t dev, std::int32_t idx, std::int32_t v, std::int32_t sub = 0) {
        objif::Descriptor d{{otc::kBus, dev, idx, sub}, 0};
        check(board_.write(d, objif::Value::of_int(v)));
    }
    void write_double(std::int32_t dev, std::int32_t idx, double v, std::int32_t sub = 0) {
        objif::Descriptor d{{otc::kBus, dev, idx, sub}, 0};
        check(board_.write(d, objif::Value::of_double(v)));
    }
    void on(otc::ProcessingType t, otc::Mode m) {
        write_int(otc::kDevChannel, otc::kIdxProcessingType, static_cast<std::int32_t>(t));
        write_int(otc::kDevChannel, otc::kIdxMode, static_cast<std::int32_t>(m));
        write_int(otc::kDevChannel, otc::kIdxActive, 1);
    }
    void b_head() {
        write_int(otc::kDevChannel, otc::kIdxKinematics, rwmos::geom::kBHeadKinematicsId);
        write_int(otc::kDevChannel, otc::kIdxTrafo, 1);
    }
    void axis_unit(int axis, std::int32_t tenth_um) {
        write_int(otc::kDevAxisUnits, axis, 1, otc::kSubEnable);
        write_int(otc::kDevAxisUnits, axis, tenth_um, otc::kSubCommand);
    }
    void line(const AxisVector& target, double feed, bool rapid = false) {
        Profile p;
        p.kind = rapid ? ProfileKind::kRapid : ProfileKind::kLine;
        p.feed = rapid ? 0.0 : feed;
        p.axes = 0x1F;
        p.target = target;
        const auto r = board_.spool(p);
        if (!r.ok()) {
            std::fprintf(stderr, "otc_figures: spool refused: %.*s\n",
                         static_cast<int>(r.message.size()), r.message.data());
            std::exit(1);
        }
    }
    // Runs the queue cycle by cycle; `each` sees the nominal and the actual axes.
    void run(const std::function<void(const AxisVector&, const AxisVector&)>& each) {
        auto& e = board_.state().motion.executor();
        while (e.fill() > 0) {
            board_.step(1);
            each(e.nominal_position(), e.position());
        }
    }
    void board_run_idle() { board_.run_until_idle(100'000'000); }

  private:
    static void check(objif::Status s) {
        if (!objif::ok(s)) {
            std::fprintf(stderr, "otc_figures: a write was refused\n");
            std::exit(1);
        }
    }
    rwmos::EmulatedBoard board_;
};

AxisVector at(double x, double z, double b = 0.0) {
    AxisVector v{};
    v[0] = x;
    v[2] = z;
    v[4] = b;
    return v;
}

// ---- SVG

std::string num(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", v);
    std::string s(text);
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    return s == "-0" ? "0" : s;
}

struct Series {
    std::string label;
    std::string colour;
    std::vector<std::pair<double, double>> points;
    bool dashed = false;
};

// A chart 640 x 300 with its own scale on each axis.
class Chart {
  public:
    Chart(std::string title, std::string xlabel, std::string ylabel, double x0, double x1,
          double y0, double y1)
        : title_(std::move(title)),
          xlabel_(std::move(xlabel)),
          ylabel_(std::move(ylabel)),
          x0_(x0),
          x1_(x1),
          y0_(y0),
          y1_(y1) {}
    void add(Series s) { series_.push_back(std::move(s)); }
    void note(double x, double y, std::string text) { notes_.push_back({x, y, std::move(text)}); }

    std::string svg(double xstep, double ystep) const {
        std::ostringstream o;
        const double w = 780, h = 420, l = 80, r = 40, t = 40, b = 110;
        const auto px = [&](double x) { return l + (x - x0_) / (x1_ - x0_) * (w - l - r); };
        const auto py = [&](double y) { return t + (y1_ - y) / (y1_ - y0_) * (h - t - b); };
        o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << w << ' ' << h
          << "\" width=\"" << w << "\" height=\"" << h << "\">\n"
          << "<rect width=\"" << w << "\" height=\"" << h << "\" fill=\"white\"/>\n"
          << "<style>text { font-family: sans-serif; font-size: 13px; fill: #222222; }"
          << " .grid { stroke: #dddddd; stroke-width: 1; } .axis { stroke: #222222; stroke-width: "
             "1; fill: none; }"
          << " path.s { fill: none; stroke-width: 2; }</style>\n"
          << "<text x=\"" << l << "\" y=\"24\">" << title_ << "</text>\n";
        // Grid lines at whole multiples of the step (no accumulated rounding).
        for (auto k = static_cast<long>(std::ceil(x0_ / xstep));; ++k) {
            const double x = static_cast<double>(k) * xstep;
            if (x > x1_ + 1e-9) break;
            o << "<path class=\"grid\" d=\"M" << num(px(x)) << ' ' << num(py(y0_)) << " L"
              << num(px(x)) << ' ' << num(py(y1_)) << "\"/>\n"
              << "<text x=\"" << num(px(x) - 8) << "\" y=\"" << num(py(y0_) + 18) << "\">" << num(x)
              << "</text>\n";
        }
        for (auto k = static_cast<long>(std::ceil(y0_ / ystep));; ++k) {
            const double y = static_cast<double>(k) * ystep;
            if (y > y1_ + 1e-9) break;
            o << "<path class=\"grid\" d=\"M" << num(px(x0_)) << ' ' << num(py(y)) << " L"
              << num(px(x1_)) << ' ' << num(py(y)) << "\"/>\n"
              << "<text x=\"" << num(l - 40) << "\" y=\"" << num(py(y) + 4) << "\">" << num(y)
              << "</text>\n";
        }
        o << "<path class=\"axis\" d=\"M" << num(px(x0_)) << ' ' << num(py(y1_)) << " L"
          << num(px(x0_)) << ' ' << num(py(y0_)) << " L" << num(px(x1_)) << ' ' << num(py(y0_))
          << "\"/>\n"
          << "<text x=\"" << num((l + w - r) / 2 - 40) << "\" y=\"" << num(py(y0_) + 38) << "\">"
          << xlabel_ << "</text>\n"
          << "<text transform=\"translate(18 " << num((t + h - b) / 2 + 60) << ") rotate(-90)\">"
          << ylabel_ << "</text>\n";
        for (std::size_t i = 0; i < series_.size(); ++i) {
            const Series& s = series_[i];
            o << "<path class=\"s\" stroke=\"" << s.colour << "\""
              << (s.dashed ? " stroke-dasharray=\"6 4\"" : "") << " d=\"";
            for (std::size_t k = 0; k < s.points.size(); ++k)
                o << (k == 0 ? "M" : " L") << num(px(s.points[k].first)) << ' '
                  << num(py(s.points[k].second));
            o << "\"/>\n";
            const auto column = i % 3, row = i / 3;  // three legend entries a row
            const double lx = l + static_cast<double>(column) * 240.0;
            const double ly = h - 36 + static_cast<double>(row) * 18.0;
            o << "<path class=\"s\" stroke=\"" << s.colour << "\""
              << (s.dashed ? " stroke-dasharray=\"6 4\"" : "") << " d=\"M" << num(lx) << ' '
              << num(ly) << " L" << num(lx + 24) << ' ' << num(ly) << "\"/>\n"
              << "<text x=\"" << num(lx + 30) << "\" y=\"" << num(ly + 4) << "\">" << s.label
              << "</text>\n";
        }
        for (const auto& n : notes_)
            o << "<text x=\"" << num(px(n.x)) << "\" y=\"" << num(py(n.y)) << "\">" << n.text
              << "</text>\n";
        o << "</svg>\n";
        return o.str();
    }

  private:
    struct Note {
        double x, y;
        std::string text;
    };
    std::string title_, xlabel_, ylabel_;
    double x0_, x1_, y0_, y1_;
    std::vector<Series> series_;
    std::vector<Note> notes_;
};

// A point every `every` cycles (and the last).
template <class F>
std::vector<std::pair<double, double>> sampled(Scene& s, int every, F&& point) {
    std::vector<std::pair<double, double>> out;
    int k = 0;
    std::pair<double, double> last{};
    s.run([&](const AxisVector& nominal, const AxisVector& actual) {
        last = point(nominal, actual);
        if (k++ % every == 0) out.push_back(last);
    });
    out.push_back(last);
    return out;
}

// ---- The figures

// [ISG-OTC] section 2.1, modes: G1 X200 F1200 on LENGTH; the PLC commands 1 mm at X100.
std::string modes() {
    Chart c(
        "LENGTH: the offset on Z along G1 X200 (F1200; wear constant 100000 x 0.1 um/m; PLC: 1 mm "
        "at X100)",
        "X (mm)", "offset on Z (mm)", 0, 200, -3.5, 0.5);
    const struct {
        otc::Mode mode;
        const char* label;
        const char* colour;
    } runs[] = {{otc::Mode::kCont, "CONT: path x wear constant", "#1f5fbf"},
                {otc::Mode::kDisc, "DISC: the PLC's 1 mm, ramped", "#e4572e"},
                {otc::Mode::kAuto, "AUTO: the sum", "#2a9d3a"}};
    for (const auto& r : runs) {
        Scene s;
        s.on(otc::ProcessingType::kLength, r.mode);
        s.line(at(100, 0), 1200);
        auto first = sampled(s, 50, [](const AxisVector& n, const AxisVector& a) {
            return std::make_pair(n[0], a[2] - n[2]);
        });
        s.axis_unit(2, 10000);
        s.line(at(200, 0), 1200);
        auto second = sampled(s, 50, [](const AxisVector& n, const AxisVector& a) {
            return std::make_pair(n[0], a[2] - n[2]);
        });
        first.insert(first.end(), second.begin(), second.end());
        c.add({r.label, r.colour, first, r.mode == otc::Mode::kDisc});
    }
    return c.svg(20, 0.5);
}

// [ISG-OTC] section 2.3.1: a disc tilted by 30 degrees splits the wear over X and Z.
std::string tilt() {
    Chart c("LENGTH with the disc tilted by 30 degrees (P-TOOL-00138): G1 X1000 F10000", "X (mm)",
            "offset (mm)", 0, 1000, -10, 1);
    Scene s;
    s.write_double(otc::kDevTool, otc::kIdxToolTiltAngle, 300000.0);
    s.on(otc::ProcessingType::kLength, otc::Mode::kCont);
    s.line(at(1000, 0), 10000);
    std::vector<std::pair<double, double>> x{{0, 0}}, z{{0, 0}}, w{{0, 0}};
    s.run([&](const AxisVector& n, const AxisVector& a) {
        if (static_cast<int>(n[0] * 6) % 100 != 0 && n[0] != 1000.0) return;
        x.emplace_back(n[0], a[0] - n[0]);
        z.emplace_back(n[0], a[2] - n[2]);
        w.emplace_back(n[0], -std::hypot(a[0] - n[0], a[2] - n[2]));
    });
    c.add({"on X: -W sin 30", "#e4572e", x});
    c.add({"on Z: -W cos 30", "#1f5fbf", z});
    c.add({"-W (along the disc axis)", "#888888", w, true});
    return c.svg(100, 1);
}

// A side view, X right and Z up (seen from -Y), for the 5-axis types.
class SideView {
  public:
    SideView(std::string title, double x0, double x1, double z0, double z1)
        : title_(std::move(title)), x0_(x0), x1_(x1), z0_(z0), z1_(z1) {}
    void path(std::vector<std::pair<double, double>> p, std::string colour, double width,
              std::string label) {
        paths_.push_back({std::move(p), std::move(colour), width, std::move(label)});
    }
    void arrow(double x, double z, double dx, double dz, std::string colour,
               std::string label = {}) {
        arrows_.push_back({x, z, dx, dz, std::move(colour), std::move(label)});
    }
    std::string svg() const {
        std::ostringstream o;
        const double scale = 640.0 / (x1_ - x0_);
        const double w = 700, h = (z1_ - z0_) * scale + 120;
        const auto px = [&](double x) { return 30 + (x - x0_) * scale; };
        const auto pz = [&](double z) { return 40 + (z1_ - z) * scale; };
        o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << w << ' ' << num(h)
          << "\" width=\"" << w << "\" height=\"" << num(h) << "\">\n"
          << "<rect width=\"" << w << "\" height=\"" << num(h) << "\" fill=\"white\"/>\n"
          << "<style>text { font-family: sans-serif; font-size: 13px; fill: #222222; }"
          << " path { fill: none; stroke-linejoin: round; }</style>\n"
          << "<text x=\"30\" y=\"24\">" << title_ << "</text>\n";
        for (std::size_t i = 0; i < paths_.size(); ++i) {
            const auto& p = paths_[i];
            o << "<path stroke=\"" << p.colour << "\" stroke-width=\"" << num(p.width) << "\" d=\"";
            for (std::size_t k = 0; k < p.points.size(); ++k)
                o << (k == 0 ? "M" : " L") << num(px(p.points[k].first)) << ' '
                  << num(pz(p.points[k].second));
            o << "\"/>\n";
            const double ly = h - 60 + static_cast<double>(i) * 18.0;
            o << "<path stroke=\"" << p.colour << "\" stroke-width=\"" << num(p.width)
              << "\" d=\"M30 " << num(ly) << " L54 " << num(ly) << "\"/>\n"
              << "<text x=\"60\" y=\"" << num(ly + 4) << "\">" << p.label << "</text>\n";
        }
        for (const auto& a : arrows_) {
            const double x2 = px(a.x + a.dx), z2 = pz(a.z + a.dz);
            const double ux = x2 - px(a.x), uz = z2 - pz(a.z);
            const double len = std::hypot(ux, uz);
            const double hx = ux / len * 7, hz = uz / len * 7;
            o << "<path stroke=\"" << a.colour << "\" stroke-width=\"1.5\" d=\"M" << num(px(a.x))
              << ' ' << num(pz(a.z)) << " L" << num(x2) << ' ' << num(z2) << " M"
              << num(x2 - hx - hz * 0.5) << ' ' << num(z2 - hz + hx * 0.5) << " L" << num(x2) << ' '
              << num(z2) << " L" << num(x2 - hx + hz * 0.5) << ' ' << num(z2 - hz - hx * 0.5)
              << "\"/>\n";
            if (!a.label.empty())
                o << "<text x=\"" << num(x2 + 6) << "\" y=\"" << num(z2 + 4) << "\">" << a.label
                  << "</text>\n";
        }
        o << "<text x=\"" << num(w - 150) << "\" y=\"" << num(h - 24)
          << "\">X right, Z up (from -Y)</text>\n</svg>\n";
        return o.str();
    }

  private:
    struct Path {
        std::vector<std::pair<double, double>> points;
        std::string colour;
        double width;
        std::string label;
    };
    struct Arrow {
        double x, z, dx, dz;
        std::string colour;
        std::string label;
    };
    std::string title_;
    double x0_, x1_, z0_, z1_;
    std::vector<Path> paths_;
    std::vector<Arrow> arrows_;
};

// [ISG-OTC] section 2.4: B45, the zig-zag X10 Z-10 / X-10 Z10, 1 mm along the tool (here
// exaggerated to 3 mm so that it shows at the drawing's scale).
std::string tool_dir() {
    Scene s;
    s.b_head();
    s.line(at(100, 50, 45), 0, true);
    s.board_run_idle();
    s.on(otc::ProcessingType::kToolDir, otc::Mode::kDisc);
    s.write_int(otc::kDevChannel, otc::kIdxRadiusOffsetUnit, 1, otc::kSubEnable);
    s.write_int(otc::kDevChannel, otc::kIdxRadiusOffsetUnit, 30000, otc::kSubCommand);
    for (int i = 0; i < 3; ++i) {
        s.line(at(110, 40, 45), 2000);
        s.line(at(100, 50, 45), 2000);
    }
    std::vector<std::pair<double, double>> nominal, actual;
    int k = 0;
    s.run([&](const AxisVector& n, const AxisVector& a) {
        if (k++ % 10 != 0) return;
        nominal.emplace_back(n[0], n[2]);
        actual.emplace_back(a[0], a[2]);
    });
    SideView v("TOOL_DIR: B45, the PLC's wear (3 mm here) along the tool direction t(B)", 96, 116,
               36, 54);
    v.path(nominal, "#1f5fbf", 2, "programmed (nominal) path: X10 Z-10 / X-10 Z10, three times");
    v.path(actual, "#c2185b", 1.5, "axes per cycle: the offset ramps in to -W t(45)");
    const Eigen::Vector3d t = rwmos::geom::b_head_tool_direction(45.0);
    v.arrow(108, 46, 4 * t.x(), 4 * t.z(), "#222222", "t(B) = (sin B, 0, cos B)");
    return v.svg();
}

// [ISG-OTC] section 2.5: one pass of its profile with B0; 0.5 mm along the surface
// normal through the third axis's unit (a fast ramp, so each block shows its own normal).
std::string surf_norm_dir() {
    Scene s;
    s.b_head();
    s.write_double(otc::kDevChannel, otc::kIdxRampVelocity, 1000.0);
    s.write_double(otc::kDevChannel, otc::kIdxRampAcceleration, 1.0e6);
    s.line(at(100, 50), 1000);
    s.board_run_idle();
    s.on(otc::ProcessingType::kSurfNormDir, otc::Mode::kDisc);
    s.axis_unit(2, 5000);
    const double steps[][2] = {{3, -3}, {2, -2}, {5, -2}, {5, -1}, {5, 0},
                               {5, -1}, {5, -2}, {2, -2}, {3, -3}};
    double x = 100, z = 50;
    std::vector<std::pair<double, double>> nominal{{x, z}}, actual;
    SideView v(
        "SURF_NORM_DIR: 0.5 mm along the surface normal fn (tool direction B0, path tangent)", 98,
        137, 33, 52);
    for (const auto& st : steps) {
        const Eigen::Vector3d fn = otc::surface_normal({0, 0, 1}, {st[0], 0, st[1]}, {0, 0, 1});
        v.arrow(x + st[0] / 2, z + st[1] / 2, 2.5 * fn.x(), 2.5 * fn.z(), "#222222");
        x += st[0];
        z += st[1];
        s.line(at(x, z), 2000);
    }
    int k = 0;
    s.run([&](const AxisVector& n, const AxisVector& a) {
        if (k++ % 5 != 0) return;
        nominal.emplace_back(n[0], n[2]);
        actual.emplace_back(a[0], a[2]);
    });
    v.path(nominal, "#1f5fbf", 2, "programmed (nominal) path");
    v.path(actual, "#c2185b", 1.5, "axes per cycle: -0.5 mm x fn (fn: arrows)");
    return v.svg();
}

}  // namespace

int main(int argc, char** argv) {
    return figure_files::write_figures(argc, argv, "otc_figures",
                                       {{"otc-modes", modes},
                                        {"otc-tilt", tilt},
                                        {"otc-tool-dir-side", tool_dir},
                                        {"otc-surf-norm-dir-side", surf_norm_dir}});
}
