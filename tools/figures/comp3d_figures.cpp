// SPDX-License-Identifier: MIT
// comp3d_figures: draws the figures of docs/3d-compensation.md with the 3D compensation
// library itself (rwmos_comp3d), so that the figures show what the code computes.
//
//   comp3d_figures DIR           writes DIR/3d-<shape>-<output>.svg
//   comp3d_figures --check DIR   exit 1 if a file in DIR differs from what would be written
//
// Each figure is the section through the tool axis T and the surface normal N (both in the
// Z-X plane; the figure shows X to the right, Z up): the design surface through S, the tool
// of the tool table at the programmed point (dashed), the tool as dimensioned by the deltas at
// the compensated tip (solid), and the points and vectors of the formulas. The deltas are
// exaggerated (DR -0.8, DR2 -0.5 with R 5) so that the shift is visible.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "figure_files.h"
#include "rwmos/comp3d/compensation.h"
#include "rwmos/comp3d/vectors.h"

namespace {

using rwmos::comp3d::Compensated;
using rwmos::comp3d::Deltas;
using rwmos::comp3d::ReferencePoint;
using rwmos::comp3d::Settings;
using rwmos::comp3d::ToolDimensions;
using V = Eigen::Vector3d;

struct Figure {
    std::string name;   // file name without ".svg"
    std::string title;  // first line of the caption
    ToolDimensions tool;
    Deltas deltas;
    ReferencePoint reference;
};

double radians(double deg) {
    return deg * std::numbers::pi / 180.0;
}

// Figure plane: X to the right, Z up; every point used here has Y = 0.
const V kS(0.0, 0.0, 0.0);
const V kN(std::sin(radians(-35.0)), 0.0, std::cos(radians(-35.0)));
const V kT(std::sin(radians(15.0)), 0.0, std::cos(radians(15.0)));
constexpr double kShankHeight = 9.0;  // how much of the tool above its tip is drawn
constexpr double kScale = 26.0;       // pixels per mm
constexpr double kMargin = 1.2;       // mm around the drawing
constexpr double kMinWidth = 700.0;   // pixels, so that the caption fits

// The outline of a tool (tip, axis t) in the figure plane: up the shank on one side, round
// the lower end, up the other side.
std::vector<V> tool_outline(const V& tip, const V& t, const ToolDimensions& d) {
    const V across = t.cross(V(0.0, 1.0, 0.0)).normalized();  // in the plane, across the axis
    const double a = d.r - d.r2;
    std::vector<V> pts;
    auto at = [&](double along, double side) { return V(tip + along * t + side * across); };
    pts.push_back(at(kShankHeight, -d.r));
    constexpr int kArcSteps = 24;
    for (int i = 0; i <= kArcSteps; ++i) {  // corner on the -across side, from its equator down
        const double phi = std::numbers::pi / 2 * i / kArcSteps;
        pts.push_back(at(d.r2 - d.r2 * std::sin(phi), -a - d.r2 * std::cos(phi)));
    }
    for (int i = 0; i <= kArcSteps; ++i) {  // corner on the +across side, up to its equator
        const double phi = std::numbers::pi / 2 * i / kArcSteps;
        pts.push_back(at(d.r2 - d.r2 * std::cos(phi), a + d.r2 * std::sin(phi)));
    }
    pts.push_back(at(kShankHeight, d.r));
    return pts;
}

class Svg {
  public:
    Svg(double xmin, double xmax, double zmin, double zmax)
        : xmin_(xmin),
          zmax_(zmax),
          width_(std::max((xmax - xmin) * kScale, kMinWidth)),
          height_((zmax - zmin) * kScale) {}

    double x(const V& p) const { return (p.x() - xmin_) * kScale; }
    double y(const V& p) const { return (zmax_ - p.z()) * kScale; }

    void polyline(const std::vector<V>& pts, const char* style) {
        out_ << "<polyline style=\"" << style << "\" points=\"";
        for (const V& p : pts) out_ << fmt(x(p)) << ',' << fmt(y(p)) << ' ';
        out_ << "\"/>\n";
    }
    void line(const V& a, const V& b, const char* style) {
        out_ << "<line x1=\"" << fmt(x(a)) << "\" y1=\"" << fmt(y(a)) << "\" x2=\"" << fmt(x(b))
             << "\" y2=\"" << fmt(y(b)) << "\" style=\"" << style << "\"/>\n";
    }
    void arrow(const V& from, const V& to, const char* colour) {
        out_ << "<line x1=\"" << fmt(x(from)) << "\" y1=\"" << fmt(y(from)) << "\" x2=\""
             << fmt(x(to)) << "\" y2=\"" << fmt(y(to)) << "\" style=\"stroke:" << colour
             << ";stroke-width:1.6\" marker-end=\"url(#head)\"/>\n";
    }
    void dot(const V& p, const char* colour) {
        out_ << "<circle cx=\"" << fmt(x(p)) << "\" cy=\"" << fmt(y(p))
             << "\" r=\"3\" style=\"fill:" << colour << "\"/>\n";
    }
    void text(const V& p, double dx, double dy, const std::string& s, const char* colour) {
        out_ << "<text x=\"" << fmt(x(p) + dx) << "\" y=\"" << fmt(y(p) + dy)
             << "\" style=\"font:13px sans-serif;fill:" << colour << "\">" << s << "</text>\n";
    }
    void caption(const std::vector<std::string>& lines) {
        double yy = height_ + 18.0;
        for (const std::string& l : lines) {
            out_ << "<text x=\"8\" y=\"" << fmt(yy) << "\" style=\"font:13px sans-serif\">" << l
                 << "</text>\n";
            yy += 17.0;
        }
        caption_height_ = yy - height_;
    }
    std::string str() const {
        std::ostringstream o;
        const double h = height_ + caption_height_;
        o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << fmt(width_) << "\" height=\""
          << fmt(h) << "\" viewBox=\"0 0 " << fmt(width_) << ' ' << fmt(h) << "\">\n"
          << "<!-- SPDX-License-Identifier: MIT -->\n"
          << "<!-- generated by tools/figures/comp3d_figures.cpp; do not edit -->\n"
          << "<defs><marker id=\"head\" markerWidth=\"8\" markerHeight=\"8\" refX=\"7\" "
             "refY=\"4\" orient=\"auto\"><path d=\"M0,0 L8,4 L0,8 z\" style=\"fill:#333\"/>"
             "</marker></defs>\n"
          << "<rect width=\"100%\" height=\"100%\" style=\"fill:white\"/>\n"
          << out_.str() << "</svg>\n";
        return o.str();
    }

  private:
    static std::string fmt(double v) {
        char b[32];
        std::snprintf(b, sizeof b, "%.1f", v);
        return b;
    }
    double xmin_, zmax_, width_, height_;
    double caption_height_ = 0.0;
    std::ostringstream out_;
};

std::string number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%+.1f", v);
    return b;
}

std::string draw(const Figure& f) {
    using namespace rwmos::comp3d;
    const V cam_tip = tip_touching(kS, kN, kT, f.tool);
    const V programmed =
        f.reference == ReferencePoint::kCentre ? V(centre_of(cam_tip, kT, f.tool)) : cam_tip;
    Settings s;
    s.tool = f.tool;
    s.deltas = f.deltas;
    s.reference = f.reference;
    const Compensated c = compensate(programmed, kN, kT, s);
    const ToolDimensions actual = effective_tool(f.tool, f.deltas);
    const V actual_tip = c.tip - f.deltas.dl * kT;
    const V cr2_nominal = corner_centre(cam_tip, kN, kT, f.tool);
    const V cr2_actual = corner_centre(actual_tip, kN, kT, actual);
    const std::vector<V> nominal = tool_outline(cam_tip, kT, f.tool);
    const std::vector<V> compensated = tool_outline(actual_tip, kT, actual);

    // The design surface: the line through S across N, hatched on the material side.
    const V along_surface = V(0.0, 1.0, 0.0).cross(kN).normalized();
    const V s0 = kS - 7.0 * along_surface;
    const V s1 = kS + 7.0 * along_surface;

    double xmin = 1e9, xmax = -1e9, zmin = 1e9, zmax = -1e9;
    const std::vector<V> surface{s0, s1};
    for (const auto* outline : {&nominal, &compensated, &surface}) {
        for (const V& p : *outline) {
            xmin = std::min(xmin, p.x());
            xmax = std::max(xmax, p.x());
            zmin = std::min(zmin, p.z());
            zmax = std::max(zmax, p.z());
        }
    }
    Svg svg(xmin - kMargin, xmax + kMargin, zmin - kMargin, zmax + kMargin);
    for (int i = 0; i <= 28; ++i) {
        const V p = s0 + (s1 - s0) * (i / 28.0);
        svg.line(p, V(p - 0.6 * kN - 0.3 * along_surface), "stroke:#999;stroke-width:1");
    }
    svg.line(s0, s1, "stroke:#000;stroke-width:2.5");

    svg.polyline(nominal, "fill:none;stroke:#888;stroke-width:1.5;stroke-dasharray:6,4");
    svg.polyline(compensated, "fill:rgba(40,90,200,0.08);stroke:#2a5ac8;stroke-width:2");
    svg.line(c.tip + 0.0 * kT, c.tip + kShankHeight * kT,
             "stroke:#2a5ac8;stroke-width:0.8;stroke-dasharray:2,3");

    svg.arrow(kS, kS + 2.5 * kN, "#000");
    svg.text(kS + 2.5 * kN, -16, -2, "N", "#000");
    svg.arrow(programmed, programmed + 2.5 * kT, "#000");
    svg.text(programmed + 2.5 * kT, 4, 0, "T", "#000");
    svg.dot(kS, "#000");
    svg.text(kS, 6, 16, "S (design surface point)", "#000");
    const bool p_is_cr2 = (cr2_nominal - programmed).norm() < 1e-9;
    if (f.tool.r2 > 0.0) {
        svg.dot(cr2_nominal, "#888");
        if (!p_is_cr2) svg.text(cr2_nominal, 8, -4, "CR2", "#888");
        svg.dot(cr2_actual, "#2a5ac8");
        svg.text(cr2_actual, 6, 14, "CR2'", "#2a5ac8");
    }
    svg.dot(programmed, "#c0392b");
    svg.text(programmed, -18, -8,
             p_is_cr2                                 ? "P = CR2 (centre)"
             : f.reference == ReferencePoint::kCentre ? "P (centre)"
                                                      : "P (tip)",
             "#c0392b");
    svg.dot(c.tip, "#2a5ac8");
    svg.text(c.tip, 8, 16, "TCP", "#2a5ac8");

    svg.caption({f.title + ": R " + number(f.tool.r) + ", R2 " + number(f.tool.r2) + ", DL " +
                     number(f.deltas.dl) + ", DR " + number(f.deltas.dr) + ", DR2 " +
                     number(f.deltas.dr2) + " (deltas exaggerated)",
                 "dashed: the tool of the tool table at the programmed point P (the CAM output);",
                 "solid: the tool as dimensioned by the deltas at the commanded tip TCP: it "
                 "touches S along N."});
    return svg.str();
}

std::vector<Figure> figures() {
    const Deltas reground{0.0, -0.8, -0.5};
    const Deltas ball{0.0, -0.8, -0.8};
    const Deltas end_mill{0.0, -0.8, 0.0};
    return {
        {"3d-end-mill-tip", "End mill, tip output", {5.0, 0.0}, end_mill, ReferencePoint::kTip},
        {"3d-end-mill-centre",
         "End mill, centre output",
         {5.0, 0.0},
         end_mill,
         ReferencePoint::kCentre},
        {"3d-toroidal-tip",
         "Toroidal mill, tip output",
         {5.0, 2.0},
         reground,
         ReferencePoint::kTip},
        {"3d-toroidal-centre",
         "Toroidal mill, centre output",
         {5.0, 2.0},
         reground,
         ReferencePoint::kCentre},
        {"3d-ball-tip", "Ball mill, tip output", {5.0, 5.0}, ball, ReferencePoint::kTip},
        {"3d-ball-centre", "Ball mill, centre output", {5.0, 5.0}, ball, ReferencePoint::kCentre},
    };
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<figure_files::FigureFile> files;
    for (const Figure& f : figures()) files.push_back({f.name, [f] { return draw(f); }});
    return figure_files::write_figures(argc, argv, "comp3d_figures", files);
}
