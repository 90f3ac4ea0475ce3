// SPDX-License-Identifier: MIT
#include "apci/run/svg_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "apci/run/text_sink.h"

namespace apci::run {

std::string_view layer_class(PlotLayer l) noexcept {
    switch (l) {
        case PlotLayer::kProgrammed:
            return "programmed";
        case PlotLayer::kRapid:
            return "rapid";
        case PlotLayer::kUncompensated:
            return "uncompensated";
        case PlotLayer::kApproach:
            return "approach";
        case PlotLayer::kDeparture:
            return "departure";
        case PlotLayer::kContour:
            return "contour";
        case PlotLayer::kTransition:
            return "transition";
        case PlotLayer::kCycles:
            return "cycles";
    }
    return "programmed";
}

std::string_view layer_label(PlotLayer l) noexcept {
    switch (l) {
        case PlotLayer::kProgrammed:
            return "programmed contour";
        case PlotLayer::kRapid:
            return "rapid (G0)";
        case PlotLayer::kUncompensated:
            return "uncompensated";
        case PlotLayer::kApproach:
            return "approach";
        case PlotLayer::kDeparture:
            return "departure";
        case PlotLayer::kContour:
            return "tool centre path";
        case PlotLayer::kTransition:
            return "corner transition";
        case PlotLayer::kCycles:
            return "axes per cycle (with OTC offsets)";
    }
    return "";
}

PlotLayer executed_layer(const PathSegment& s) noexcept {
    if (s.kind == SegmentKind::kRapid) return PlotLayer::kRapid;
    switch (s.role) {
        case Role::kContour:
            return PlotLayer::kContour;
        case Role::kTransition:
            return PlotLayer::kTransition;
        case Role::kApproach:
            return PlotLayer::kApproach;
        case Role::kDeparture:
            return PlotLayer::kDeparture;
        case Role::kUncompensated:
            return PlotLayer::kUncompensated;
    }
    return PlotLayer::kUncompensated;
}

void Bounds::add(const Point& p) noexcept {
    if (empty) {
        lo = hi = p;
        empty = false;
        return;
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
}

void Bounds::add(const PathSegment& s) noexcept {
    add(s.start);
    add(s.end);
    if (s.kind != SegmentKind::kArc) return;
    // The circle's extreme points on the plane's axes that the arc passes.
    const PlaneAxes a = plane_axes(s.plane);
    const double r = arc_radius(s);
    const double sweep = arc_sweep(s);
    const double from =
        std::atan2(s.start[a.second] - s.center[a.second], s.start[a.first] - s.center[a.first]);
    for (int quarter = 0; quarter < 4; ++quarter) {
        const double angle = quarter * std::numbers::pi / 2.0;
        // How far along the sweep (0..1) the arc reaches `angle`.
        double d = angle - from;
        const double turn = 2.0 * std::numbers::pi;
        if (sweep > 0) {
            d = std::fmod(std::fmod(d, turn) + turn, turn);
        } else {
            d = -std::fmod(std::fmod(-d, turn) + turn, turn);
        }
        if (d / sweep > 1.0) continue;
        Point p = s.start;
        p[a.first] = s.center[a.first] + r * std::cos(angle);
        p[a.second] = s.center[a.second] + r * std::sin(angle);
        add(p);
    }
}

namespace {

// A record in the temporary file: one segment of one layer.
struct Record {
    std::uint8_t layer;
    std::uint8_t kind;
    std::uint8_t ccw;
    std::uint8_t pad = 0;
    std::int32_t plane;
    double start[3];
    double end[3];
    double center[3];
};

Record make_record(PlotLayer layer, const PathSegment& s) {
    Record r{};
    r.layer = static_cast<std::uint8_t>(layer);
    r.kind = static_cast<std::uint8_t>(s.kind);
    r.ccw = s.ccw ? 1 : 0;
    r.plane = s.plane;
    for (int i = 0; i < 3; ++i) {
        r.start[i] = s.start[i];
        r.end[i] = s.end[i];
        r.center[i] = s.center[i];
    }
    return r;
}

PathSegment segment_of(const Record& r) {
    PathSegment s;
    s.kind = static_cast<SegmentKind>(r.kind);
    s.ccw = r.ccw != 0;
    s.plane = r.plane;
    s.start = Point(r.start[0], r.start[1], r.start[2]);
    s.end = Point(r.end[0], r.end[1], r.end[2]);
    s.center = Point(r.center[0], r.center[1], r.center[2]);
    return s;
}

// The drawing's frame: plane coordinates to SVG user units (second axis flipped up) and the
// number format that resolves it.
class Frame {
  public:
    Frame(int plane, const Bounds& b) : axes_(plane_axes(plane)) {
        if (!b.empty) {
            u0_ = b.lo[axes_.first];
            u1_ = b.hi[axes_.first];
            v0_ = b.lo[axes_.second];
            v1_ = b.hi[axes_.second];
        }
        extent_ = std::max({u1_ - u0_, v1_ - v0_, 1e-3});
        decimals_ = std::clamp(4 - static_cast<int>(std::floor(std::log10(extent_))), 0, 9);
    }
    const PlaneAxes& axes() const noexcept { return axes_; }
    double extent() const noexcept { return extent_; }
    double u0() const noexcept { return u0_; }
    double u1() const noexcept { return u1_; }
    double v0() const noexcept { return v0_; }
    double v1() const noexcept { return v1_; }

    // A coordinate with as many decimals as the plot resolves, trailing zeros dropped.
    void number(TextSink& sink, double v) const {
        char text[64];
        int n = std::snprintf(text, sizeof text, "%.*f", decimals_, v);
        if (n <= 0 || n >= static_cast<int>(sizeof text)) {
            sink.append("0");
            return;
        }
        if (std::memchr(text, '.', static_cast<std::size_t>(n)) != nullptr) {
            while (n > 0 && text[n - 1] == '0') --n;
            if (n > 0 && text[n - 1] == '.') --n;
        }
        std::string_view out(text, static_cast<std::size_t>(n));
        if (out == "-0") out = "0";
        sink.append(out);
    }
    void xy(TextSink& sink, const Point& p) const {
        number(sink, p[axes_.first]);
        sink.put(' ');
        number(sink, -p[axes_.second]);
    }

  private:
    PlaneAxes axes_;
    double u0_ = 0.0, u1_ = 0.0, v0_ = 0.0, v1_ = 0.0;
    double extent_ = 1.0;
    int decimals_ = 3;
};

// Writes one layer's segments as <path> elements: consecutive segments continue one path,
// a gap starts a new subpath ("M"), and a path is closed after kCommandsPerPath commands.
class PathEmitter {
  public:
    static constexpr std::size_t kCommandsPerPath = 2000;

    PathEmitter(TextSink& sink, const Frame& frame, std::string_view css_class)
        : sink_(sink), frame_(frame), class_(css_class) {}
    ~PathEmitter() { close(); }

    void add(const PathSegment& s) {
        const PlaneAxes& a = frame_.axes();
        const bool joined = open_ &&
                            std::abs(s.start[a.first] - last_[a.first]) <= kSamePointTolerance &&
                            std::abs(s.start[a.second] - last_[a.second]) <= kSamePointTolerance;
        if (open_ && commands_ >= kCommandsPerPath) close();
        if (!open_) {
            sink_.print("<path class=\"{}\" d=\"", class_);
            open_ = true;
            commands_ = 0;
        }
        if (!joined || commands_ == 0) {
            sink_.append(commands_ == 0 ? "M" : " M");
            frame_.xy(sink_, s.start);
        }
        if (s.kind == SegmentKind::kArc) {
            arc(s);
        } else {
            line_to(s.end);
        }
        last_ = s.end;
    }

    void close() {
        if (!open_) return;
        sink_.append("\"/>\n");
        open_ = false;
    }

  private:
    void line_to(const Point& p) {
        sink_.append(" L");
        frame_.xy(sink_, p);
        ++commands_;
    }

    void arc(const PathSegment& s) {
        const PlaneAxes& a = frame_.axes();
        const double sweep = arc_sweep(s);
        if (plane_axes(s.plane).third != a.third) {
            // Not in the plotted plane: its projection, as a polyline.
            const int n = std::clamp(
                static_cast<int>(std::ceil(std::abs(sweep) / (std::numbers::pi / 32.0))), 2, 128);
            for (int i = 1; i <= n; ++i) line_to(point_along(s, static_cast<double>(i) / n));
            return;
        }
        // Seen from the positive third axis with the second axis flipped up, counter-clockwise
        // is SVG's negative sweep direction. Arcs beyond a half turn go in two halves, so the
        // large-arc flag is never needed and a full circle draws.
        const double r = arc_radius(s);
        if (std::abs(sweep) > std::numbers::pi) arc_to(r, s.ccw, point_along(s, 0.5));
        arc_to(r, s.ccw, s.end);
    }

    void arc_to(double r, bool ccw, const Point& p) {
        sink_.append(" A");
        frame_.number(sink_, r);
        sink_.put(' ');
        frame_.number(sink_, r);
        sink_.print(" 0 0 {} ", ccw ? 0 : 1);
        frame_.xy(sink_, p);
        ++commands_;
    }

    TextSink& sink_;
    const Frame& frame_;
    std::string_view class_;
    bool open_ = false;
    std::size_t commands_ = 0;
    Point last_ = Point::Zero();
};

// 1, 2 or 5 times a power of ten, at most `limit`.
double round_length(double limit) {
    const double p = std::pow(10.0, std::floor(std::log10(limit)));
    for (const double m : {5.0, 2.0, 1.0})
        if (m * p <= limit) return m * p;
    return p;
}

void append_xml_text(TextSink& sink, std::string_view text) {
    for (const char c : text) {
        switch (c) {
            case '<':
                sink.append("&lt;");
                break;
            case '>':
                sink.append("&gt;");
                break;
            case '&':
                sink.append("&amp;");
                break;
            case '"':
                sink.append("&quot;");
                break;
            default:
                sink.put(c);
        }
    }
}

std::string block_label(const BlockRef& b) {
    if (b.number != kNoBlock) return "N" + std::to_string(b.number);
    if (b.line != 0) return "line " + std::to_string(b.line);
    return "";
}

}  // namespace

SvgPlotWriter::SvgPlotWriter() : records_(std::tmpfile()) {
    if (records_ != nullptr) std::setvbuf(records_, nullptr, _IOFBF, std::size_t{1} << 16);
}

SvgPlotWriter::~SvgPlotWriter() {
    if (records_ != nullptr) std::fclose(records_);
}

void SvgPlotWriter::record(PlotLayer layer, const PathSegment& s) {
    if (!ok()) return;
    const Record r = make_record(layer, s);
    if (std::fwrite(&r, sizeof r, 1, records_) != 1) {
        failed_ = true;
        return;
    }
    bounds_.add(s);
    ++counts_[static_cast<std::size_t>(layer)];
}

void SvgPlotWriter::programmed(const PathSegment& s) {
    if (s.kind == SegmentKind::kRapid) return;  // the executed rapid shows it
    record(PlotLayer::kProgrammed, s);
}

void SvgPlotWriter::executed(const PathSegment& s) {
    record(executed_layer(s), s);
}

void SvgPlotWriter::cycle_vertex(const Point& p) {
    PathSegment s;
    s.kind = SegmentKind::kLine;
    s.start = cycle_kept_;
    s.end = p;
    record(PlotLayer::kCycles, s);
    cycle_kept_ = p;
}

void SvgPlotWriter::cycle(const Point& p) {
    if (!have_cycle_) {
        have_cycle_ = true;
        cycle_kept_ = cycle_last_ = p;
        return;
    }
    if (!cycle_have_dir_) {
        if ((p - cycle_kept_).norm() >= kCycleStep) {
            cycle_dir_ = p;
            cycle_have_dir_ = true;
        }
    } else {
        const Point d = (cycle_dir_ - cycle_kept_).normalized();
        const Point v = p - cycle_kept_;
        const double off = (v - v.dot(d) * d).norm();
        // Leaving the line (or turning back along it): the last point seen is a vertex.
        if (off > kCycleTolerance || v.dot(d) < -kCycleTolerance) {
            cycle_vertex(cycle_last_);
            cycle_have_dir_ = (p - cycle_kept_).norm() >= kCycleStep;
            cycle_dir_ = p;
        }
    }
    cycle_last_ = p;
    cycle_pending_ = cycle_last_ != cycle_kept_;
}

void SvgPlotWriter::error_marker(const BlockRef& block, const Point& where, std::string_view code) {
    if (markers_.size() >= kMaxErrorMarkers) {
        ++markers_dropped_;
        return;
    }
    markers_.push_back(Marker{block, where, std::string(code)});
    bounds_.add(where);
}

bool SvgPlotWriter::finish(std::FILE* out, int plane, std::string_view title) {
    if (cycle_pending_) {
        cycle_vertex(cycle_last_);
        cycle_pending_ = false;
    }
    if (!ok() || std::fflush(records_) != 0) return false;
    const Frame frame(plane, bounds_);
    const double e = frame.extent();
    const double margin = 0.06 * e;
    const double font = 0.028 * e;
    const double stroke = e / 500.0;
    // View box: title band above, plot, footer band below (scale bar, axes, legend).
    const double x0 = frame.u0() - margin;
    const double header = 2.2 * font;
    // Legend entries (layers drawn, then the error marker) in rows of `per_row`.
    const double entry = 14.0 * font;
    std::size_t entries = markers_.empty() && markers_dropped_ == 0 ? 0 : 1;
    for (const std::uint64_t c : counts_) entries += c != 0 ? 1 : 0;
    // Error labels ("N80 KorrError") stand right of and above their markers: room for them.
    double label_right = frame.u1() + margin;
    double label_top = frame.v1() + margin;
    for (const Marker& m : markers_) {
        const double chars = static_cast<double>(block_label(m.block).size() + m.code.size() + 1);
        label_right =
            std::max(label_right, m.where[frame.axes().first] + (1.6 + 0.62 * chars) * font);
        label_top = std::max(label_top, m.where[frame.axes().second] + 2.0 * font);
    }
    const double plot_width = label_right - x0;
    const double box_width = std::max(plot_width, 16.0 * font);
    const auto per_row =
        std::max<std::size_t>(1, static_cast<std::size_t>((box_width - 0.5 * margin) / entry));
    const std::size_t rows = (entries + per_row - 1) / per_row;
    const double footer = (3.0 + 1.5 * static_cast<double>(rows)) * font + margin;
    const double y0 = -label_top - header;
    const double height = (label_top - frame.v0()) + margin + header + footer;
    const double pixels = 1000.0;

    TextSink sink(out);
    sink.append("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    sink.append("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"");
    frame.number(sink, x0);
    sink.put(' ');
    frame.number(sink, y0);
    sink.put(' ');
    frame.number(sink, box_width);
    sink.put(' ');
    frame.number(sink, height);
    sink.print("\" width=\"{:.0f}\" height=\"{:.0f}\">\n", pixels,
               std::ceil(pixels * height / box_width));
    const auto w = [&](double factor) { return fmt::format("{:.6g}", stroke * factor); };
    sink.print(
        "<style>\n"
        "path {{ fill: none; stroke-linecap: round; stroke-linejoin: round; }}\n"
        ".programmed {{ stroke: #222222; stroke-width: {0}; }}\n"
        ".rapid {{ stroke: #9a9a9a; stroke-width: {0}; stroke-dasharray: {3} {4}; }}\n"
        ".uncompensated {{ stroke: #7b3fa0; stroke-width: {1}; }}\n"
        ".approach {{ stroke: #2a9d3a; stroke-width: {1}; stroke-dasharray: {5} {4}; }}\n"
        ".departure {{ stroke: #b8860b; stroke-width: {1}; stroke-dasharray: {5} {4}; }}\n"
        ".contour {{ stroke: #1f5fbf; stroke-width: {1}; }}\n"
        ".transition {{ stroke: #e4572e; stroke-width: {2}; }}\n"
        "{8}"
        ".error {{ fill: none; stroke: #d00000; stroke-width: {1}; }}\n"
        "text {{ font-family: sans-serif; font-size: {6:.6g}px; fill: #222222; }}\n"
        "text.error {{ fill: #d00000; stroke: none; }}\n"
        ".frame {{ fill: none; stroke: #cccccc; stroke-width: {7}; }}\n"
        ".axis {{ fill: none; stroke: #222222; stroke-width: {0}; }}\n"
        "</style>\n",
        w(1.0), w(1.6), w(2.2), w(4.0), w(3.0), w(6.0), font, w(0.5),
        counts_[static_cast<std::size_t>(PlotLayer::kCycles)] == 0
            ? std::string()
            : fmt::format(".cycles {{ stroke: #c2185b; stroke-width: {}; }}\n", w(1.0)));
    sink.print(
        "<rect x=\"{:.6g}\" y=\"{:.6g}\" width=\"{:.6g}\" height=\"{:.6g}\" fill=\"white\"/>\n", x0,
        y0, box_width, height);
    sink.append("<text x=\"");
    frame.number(sink, frame.u0());
    sink.append("\" y=\"");
    frame.number(sink, y0 + 1.4 * font);
    sink.append("\">");
    append_xml_text(sink, title);
    sink.print(" \xe2\x80\x94 G{} plane {}, seen from +{}</text>\n", plane, plane_name(plane),
               axis_letter(frame.axes().third));

    // The layers, one pass over the records each, bottom to top.
    bool read_ok = true;
    for (std::size_t layer = 0; layer < kPlotLayerCount; ++layer) {
        if (counts_[layer] == 0) continue;
        std::rewind(records_);
        PathEmitter emit(sink, frame, layer_class(static_cast<PlotLayer>(layer)));
        Record r;
        while (std::fread(&r, sizeof r, 1, records_) == 1)
            if (r.layer == layer) emit.add(segment_of(r));
        if (std::ferror(records_)) read_ok = false;
    }

    // Error markers: a circle and "N80 KorrError".
    for (const Marker& m : markers_) {
        sink.append("<circle class=\"error\" cx=\"");
        frame.number(sink, m.where[frame.axes().first]);
        sink.append("\" cy=\"");
        frame.number(sink, -m.where[frame.axes().second]);
        sink.print("\" r=\"{:.6g}\"/>\n", 0.9 * font);
        sink.append("<text class=\"error\" x=\"");
        frame.number(sink, m.where[frame.axes().first] + 1.2 * font);
        sink.append("\" y=\"");
        frame.number(sink, -m.where[frame.axes().second] - 1.0 * font);
        sink.append("\">");
        std::string label = block_label(m.block);
        if (!label.empty()) label += ' ';
        append_xml_text(sink, label + m.code);
        sink.append("</text>\n");
    }

    // Footer: scale bar and range, the plane's axes, the legend.
    const double fy = -frame.v0() + margin + 1.2 * font;
    const double bar =
        round_length(0.25 * (frame.u1() - frame.u0() > 0 ? frame.u1() - frame.u0() : e));
    const double bx = frame.u0();
    sink.print(
        "<path class=\"axis\" d=\"M{0:.6g} {1:.6g} L{2:.6g} {1:.6g} M{0:.6g} {3:.6g} L{0:.6g} "
        "{4:.6g} M{2:.6g} {3:.6g} L{2:.6g} {4:.6g}\"/>\n",
        bx, fy, bx + bar, fy - 0.4 * font, fy + 0.4 * font);
    sink.print("<text x=\"{:.6g}\" y=\"{:.6g}\">{:g} mm</text>\n", bx + bar + 0.6 * font,
               fy + 0.35 * font, bar);
    const char first = axis_letter(frame.axes().first);
    const char second = axis_letter(frame.axes().second);
    sink.print("<text x=\"{:.6g}\" y=\"{:.6g}\">", bx + bar + 6.0 * font, fy + 0.35 * font);
    sink.print("{} ", first);
    frame.number(sink, frame.u0());
    sink.append(" .. ");
    frame.number(sink, frame.u1());
    sink.print(", {} ", second);
    frame.number(sink, frame.v0());
    sink.append(" .. ");
    frame.number(sink, frame.v1());
    sink.append(" mm</text>\n");
    // Axis cross at the right end of the footer: the first axis right, the second up.
    const double ax = x0 + box_width - margin - 3.0 * font;
    const double ay = fy + 0.6 * font;
    const double len = 2.2 * font;
    sink.print(
        "<path class=\"axis\" d=\"M{0:.6g} {1:.6g} L{2:.6g} {1:.6g} M{0:.6g} {1:.6g} L{0:.6g} "
        "{3:.6g}"
        " M{4:.6g} {5:.6g} L{2:.6g} {1:.6g} L{4:.6g} {6:.6g}"
        " M{7:.6g} {8:.6g} L{0:.6g} {3:.6g} L{9:.6g} {8:.6g}\"/>\n",
        ax, ay, ax + len, ay - len, ax + len - 0.4 * font, ay - 0.25 * font, ay + 0.25 * font,
        ax - 0.25 * font, ay - len + 0.4 * font, ax + 0.25 * font);
    sink.print("<text x=\"{:.6g}\" y=\"{:.6g}\">{}</text>\n", ax + len + 0.3 * font,
               ay + 0.35 * font, first);
    sink.print("<text x=\"{:.6g}\" y=\"{:.6g}\">{}</text>\n", ax - 0.35 * font,
               ay - len - 0.4 * font, second);
    // Legend: a short sample of each layer drawn, then the error marker.
    std::size_t slot = 0;
    const auto slot_x = [&] { return bx + static_cast<double>(slot % per_row) * entry; };
    const auto slot_y = [&] {
        const std::size_t row = slot / per_row;  // whole rows
        return fy + (2.4 + 1.5 * static_cast<double>(row)) * font;
    };
    for (std::size_t layer = 0; layer < kPlotLayerCount; ++layer) {
        if (counts_[layer] == 0) continue;
        const auto l = static_cast<PlotLayer>(layer);
        const double lx = slot_x(), ly = slot_y();
        sink.print("<path class=\"{}\" d=\"M{:.6g} {:.6g} L{:.6g} {:.6g}\"/>\n", layer_class(l), lx,
                   ly, lx + 2.0 * font, ly);
        sink.print("<text x=\"{:.6g}\" y=\"{:.6g}\">{}</text>\n", lx + 2.5 * font, ly + 0.35 * font,
                   layer_label(l));
        ++slot;
    }
    if (!markers_.empty() || markers_dropped_ != 0) {
        const double lx = slot_x(), ly = slot_y();
        sink.print("<circle class=\"error\" cx=\"{:.6g}\" cy=\"{:.6g}\" r=\"{:.6g}\"/>\n",
                   lx + font, ly, 0.5 * font);
        sink.print("<text x=\"{:.6g}\" y=\"{:.6g}\">error", lx + 2.5 * font, ly + 0.35 * font);
        if (markers_dropped_ != 0) sink.print(" ({} more not drawn)", markers_dropped_);
        sink.append("</text>\n");
    }
    sink.append("</svg>\n");
    return sink.flush() && read_ok;
}

}  // namespace apci::run
