// SPDX-License-Identifier: MIT
#include "apci/run/svg_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "apci/run/text_sink.h"

namespace apci::run {

namespace {

// Each layer's CSS class and legend text, in the order of PlotLayer.
struct LayerName {
    std::string_view css_class;
    std::string_view label;
};
constexpr std::array<LayerName, kPlotLayerCount> kLayerNames{{
    {"programmed", "programmed contour"},
    {"rapid", "rapid (G0)"},
    {"uncompensated", "uncompensated"},
    {"approach", "approach"},
    {"departure", "departure"},
    {"contour", "tool centre path"},
    {"transition", "corner transition"},
    {"cycles", "axes per cycle (with OTC offsets)"},
}};
static_assert(static_cast<std::size_t>(PlotLayer::kCycles) + 1 == kPlotLayerCount);

}  // namespace

std::string_view layer_class(PlotLayer l) noexcept {
    const auto i = static_cast<std::size_t>(l);
    return i < kLayerNames.size() ? kLayerNames[i].css_class : "programmed";
}

std::string_view layer_label(PlotLayer l) noexcept {
    const auto i = static_cast<std::size_t>(l);
    return i < kLayerNames.size() ? kLayerNames[i].label : "";
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
    const double sweep = measured_sweep(s);
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
        sink.append(format(text, v));
    }
    std::string text(double v) const {
        char text[64];
        return std::string(format(text, v));
    }
    // The smallest step a written coordinate shows.
    double resolution() const noexcept { return std::pow(10.0, -decimals_); }
    void xy(TextSink& sink, const Point& p) const {
        number(sink, p[axes_.first]);
        sink.put(' ');
        number(sink, -p[axes_.second]);
    }

  private:
    std::string_view format(char (&text)[64], double v) const {
        int n = std::snprintf(text, sizeof text, "%.*f", decimals_, v);
        if (n <= 0 || n >= static_cast<int>(sizeof text)) return "0";
        if (std::memchr(text, '.', static_cast<std::size_t>(n)) != nullptr) {
            while (n > 0 && text[n - 1] == '0') --n;
            if (n > 0 && text[n - 1] == '.') --n;
        }
        std::string_view out(text, static_cast<std::size_t>(n));
        if (out == "-0") out = "0";
        return out;
    }

    PlaneAxes axes_;
    double u0_ = 0.0, u1_ = 0.0, v0_ = 0.0, v1_ = 0.0;
    double extent_ = 1.0;
    int decimals_ = 3;
};

// The segments one layer has drawn, each as its plotted ends (and an arc's centre and sense)
// on a grid of a quarter pixel: a segment with the same key lies within half a pixel of one
// drawn before, everywhere, so drawing it again shows nothing new. A program that runs one
// contour pass after pass (step-downs seen from above, a loop) would otherwise write every
// pass (3 million segments of 20 elements repeated made a 231 MB plot). The table is bounded
// (kSlots, a few MiB): once it is three quarters full, new keys are no longer remembered and
// those segments are drawn, so nothing is ever left out that was not drawn.
class DrawnSegments {
  public:
    static constexpr std::size_t kSlots = std::size_t{1} << 17;

    DrawnSegments(const Frame& frame, double grid) : frame_(frame), grid_(grid) {}

    // True when `s` (in the plotted plane) was drawn before; else remembers it (while there
    // is room) and says false. Arcs out of the plotted plane and lines shorter than half a
    // pixel are never taken for drawn.
    bool drawn_before(const PathSegment& s) {
        Key key{};
        if (!key_of(s, key)) return false;
        if (slots_.empty()) slots_.resize(kSlots);
        std::size_t i = hash(key) & (kSlots - 1);
        while (slots_[i].used) {
            if (slots_[i].key == key) return true;
            i = (i + 1) & (kSlots - 1);
        }
        if (count_ < kSlots / 4 * 3) {
            slots_[i].key = key;
            slots_[i].used = true;
            ++count_;
        }
        return false;
    }

  private:
    struct Key {
        std::array<std::int32_t, 6> v{};  // start, end, centre: plotted coordinates on the grid
        std::uint8_t kind = 0;
        std::uint8_t ccw = 0;
        bool operator==(const Key&) const = default;
    };
    struct Slot {
        Key key;
        bool used = false;
    };

    bool on_grid(double value, double origin, std::int32_t& out) const {
        const double steps = std::round((value - origin) / grid_);
        if (!(std::abs(steps) < 1e9)) return false;
        out = static_cast<std::int32_t>(steps);
        return true;
    }
    bool key_of(const PathSegment& s, Key& key) const {
        const PlaneAxes& a = frame_.axes();
        const bool arc = s.kind == SegmentKind::kArc;
        if (!(grid_ > 0.0) || (arc && plane_axes(s.plane).third != a.third)) return false;
        // A line shorter than two grid steps (half a pixel) is left to the vertices' own
        // simplification (PathEmitter::line_to), which keeps a path's last vertex where the
        // path ends.
        if (!arc && std::hypot(s.end[a.first] - s.start[a.first],
                               s.end[a.second] - s.start[a.second]) < 2.0 * grid_)
            return false;
        key.kind = static_cast<std::uint8_t>(s.kind);
        key.ccw = arc && s.ccw ? 1 : 0;
        Point from = s.start, to = s.end;
        // A line is the same drawn either way.
        if (!arc && std::pair(to[a.first], to[a.second]) < std::pair(from[a.first], from[a.second]))
            std::swap(from, to);
        const Point centre = arc ? s.center : Point::Zero();
        const std::array<const Point*, 3> points{&from, &to, &centre};
        for (std::size_t i = 0; i < 3; ++i)
            if (!on_grid((*points[i])[a.first], frame_.u0(), key.v[2 * i]) ||
                !on_grid((*points[i])[a.second], frame_.v0(), key.v[2 * i + 1]))
                return false;
        return true;
    }
    static std::size_t hash(const Key& key) noexcept {
        std::uint64_t h = (std::uint64_t{key.kind} << 8) | key.ccw;
        for (const std::int32_t v : key.v) {
            h ^= static_cast<std::uint32_t>(v);
            h *= 0x9E3779B97F4A7C15ULL;
            h ^= h >> 29;
        }
        return static_cast<std::size_t>(h);
    }

    const Frame& frame_;
    double grid_;
    std::vector<Slot> slots_;  // allocated at the first segment
    std::size_t count_ = 0;
};

// Writes one layer's segments as <path> elements: consecutive segments continue one path,
// a gap starts a new subpath ("M"), and a path is closed after kCommandsPerPath commands.
class PathEmitter {
  public:
    static constexpr std::size_t kCommandsPerPath = 2000;

    // `min_step`: vertices of lines closer than this (in the drawing's units, in the plotted
    // plane) to the last one written are left out, the last of a run written as it ends: a
    // detail below half a pixel cannot be seen, and a program of millions of tiny segments
    // would otherwise write every one (a 3-million-segment program made an 82 MB SVG).
    // A segment drawn before (DrawnSegments, on a grid of half min_step) is left out, and the
    // next one starts a new subpath where it does not join the last one written.
    PathEmitter(TextSink& sink, const Frame& frame, std::string_view css_class, double min_step)
        : sink_(sink), frame_(frame), class_(css_class), min_step_(min_step),
          drawn_(frame, 0.5 * min_step) {}
    ~PathEmitter() { close(); }

    void add(const PathSegment& s) {
        if (drawn_.drawn_before(s)) {
            skipped_ = true;
            return;
        }
        const PlaneAxes& a = frame_.axes();
        bool joined = open_ &&
                      std::abs(s.start[a.first] - last_[a.first]) <= kSamePointTolerance &&
                      std::abs(s.start[a.second] - last_[a.second]) <= kSamePointTolerance;
        // After segments left out, one that starts less than min_step from the pen goes on
        // from there (the step between is below half a pixel) instead of a new subpath each.
        if (!joined && open_ && skipped_ && written_any_) {
            const Point& pen = has_pending_ ? pending_ : written_;
            if (std::hypot(s.start[a.first] - pen[a.first], s.start[a.second] - pen[a.second]) <
                min_step_) {
                line_to(s.start);
                joined = true;
            }
        }
        skipped_ = false;
        if (open_ && commands_ >= kCommandsPerPath) close();
        if (!open_) {
            sink_.print("<path class=\"{}\" d=\"", class_);
            open_ = true;
            commands_ = 0;
            written_any_ = false;
        }
        if (!joined || !written_any_) {
            flush_pending();
            sink_.append(written_any_ ? " M" : "M");
            frame_.xy(sink_, s.start);
            written_any_ = true;
            written_ = s.start;
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
        flush_pending();
        sink_.append("\"/>\n");
        open_ = false;
    }

  private:
    // A line to p, unless p is within min_step_ of the last vertex written: then it waits, and
    // is written when the next vertex, an arc, a gap or the end of the path comes.
    void line_to(const Point& p) {
        const PlaneAxes& a = frame_.axes();
        if (std::hypot(p[a.first] - written_[a.first], p[a.second] - written_[a.second]) <
            min_step_) {
            pending_ = p;
            has_pending_ = true;
            return;
        }
        write_line(p);
    }

    void write_line(const Point& p) {
        sink_.append(" L");
        frame_.xy(sink_, p);
        ++commands_;
        written_ = p;
        has_pending_ = false;
    }

    void flush_pending() {
        if (has_pending_) write_line(pending_);
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
        flush_pending();
        if (std::abs(sweep) > std::numbers::pi) arc_to(r, s.ccw, point_along(s, 0.5));
        arc_to(r, s.ccw, s.end);
    }

    void arc_to(double r, bool ccw, const Point& p) {
        written_ = p;
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
    double min_step_ = 0.0;
    DrawnSegments drawn_;
    bool skipped_ = false;  // segments were left out since the last one added
    bool open_ = false;
    bool written_any_ = false;  // the open path has its first "M"
    std::size_t commands_ = 0;
    Point last_ = Point::Zero();     // where the last segment added ends
    Point written_ = Point::Zero();  // the last vertex written
    Point pending_ = Point::Zero();  // a vertex left out so far (has_pending_)
    bool has_pending_ = false;
};

// DejaVu Sans advance widths in units of 1/2048 em, for ' ' (32) .. '~' (126).
constexpr std::array<std::uint16_t, 95> kDejaVuSansAdvance{
    651,  821,  942,  1716, 1303, 1946, 1597, 563,  799,  799,  1024, 1716, 651,  739,  651,  690,
    1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 690,  690,  1716, 1716, 1716, 1087,
    2048, 1401, 1405, 1430, 1577, 1294, 1178, 1587, 1540, 604,  604,  1343, 1141, 1767, 1532, 1612,
    1235, 1612, 1423, 1300, 1251, 1499, 1401, 2025, 1403, 1251, 1403, 799,  690,  799,  1716, 1024,
    1024, 1255, 1300, 1126, 1300, 1260, 721,  1300, 1298, 569,  569,  1186, 569,  1995, 1298, 1253,
    1300, 1300, 842,  1067, 803,  1298, 1212, 1675, 1212, 1212, 1075, 1303, 690,  1303, 1716};
constexpr double kUnitsPerEm = 2048.0;
// The font size of the plot's text in its own units (the text is scaled into the drawing).
constexpr double kTextUnits = 10.0;
// The title widens the page up to this many em; a longer one is wrapped.
constexpr double kTitleEms = 40.0;

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

// "N80 KorrError", or the error's name alone.
std::string marker_label(const BlockRef& b, std::string_view code) {
    std::string label = block_label(b);
    if (!label.empty()) label += ' ';
    return label.append(code);
}

}  // namespace

double text_width(std::string_view text, double size) noexcept {
    double units = 0.0;
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c >= 32 && c <= 126) {
            units += kDejaVuSansAdvance[static_cast<std::size_t>(c - 32)];
        } else if ((c & 0xC0U) != 0x80U) {  // not a UTF-8 continuation byte: one character
            units += kUnitsPerEm;
        }
    }
    return units / kUnitsPerEm * size;
}

std::vector<std::string> wrap_text(std::string_view text, double width, double size) {
    std::vector<std::string> lines;
    while (!text.empty()) {
        // The longest start that fits (at least one character), cut after its last space or
        // slash if it has one; a UTF-8 character is never cut.
        std::size_t fits = 0, cut = 0;
        for (std::size_t i = 1; i <= text.size(); ++i) {
            if (i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0U) == 0x80U) continue;
            if (fits != 0 && text_width(text.substr(0, i), size) > width) break;
            fits = i;
            if (text[i - 1] == ' ' || text[i - 1] == '/') cut = i;
        }
        const std::size_t n = fits == text.size() || cut == 0 ? fits : cut;
        std::string_view line = text.substr(0, n);
        while (line.size() > 1 && line.back() == ' ') line.remove_suffix(1);
        lines.emplace_back(line);
        text.remove_prefix(n);
    }
    return lines;
}

double scale_bar_length(double width) noexcept {
    if (!(width > 0.0) || !std::isfinite(width)) return 1.0;
    const double quarter = width / 4.0;
    const int exponent = static_cast<int>(std::floor(std::log10(quarter)));
    double best = 0.0;
    // The candidates around the quarter: 1, 2, 5 times 10^(exponent - 1 .. exponent + 1). A
    // negative power divides by an exact power of ten, so 0.0005 is the double nearest 5e-4.
    for (int k = exponent - 1; k <= exponent + 1; ++k) {
        for (const double m : {1.0, 2.0, 5.0}) {
            const double v = k >= 0 ? m * std::pow(10.0, k) : m / std::pow(10.0, -k);
            if (best == 0.0 || std::abs(std::log(v / quarter)) < std::abs(std::log(best / quarter)))
                best = v;
        }
    }
    return best;
}

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
    add_marker(block, where, code, false);
}

void SvgPlotWriter::warning_marker(const BlockRef& block, const Point& where,
                                   std::string_view code) {
    add_marker(block, where, code, true);
}

void SvgPlotWriter::add_marker(const BlockRef& block, const Point& where, std::string_view code,
                               bool warning) {
    if (markers_.size() >= kMaxErrorMarkers) {
        ++markers_dropped_;
        return;
    }
    markers_.push_back(Marker{block, where, std::string(code), warning});
    bounds_.add(where);
}

// The page around the drawing: its measures (from the drawing's bounds and the texts beside
// it: title, coordinate ranges, legend, scale bar) and the writing of each of its parts.
class SvgPlotWriter::Page {
  public:
    static constexpr double kPixels = 1000.0;  // the page's width in pixels

    Page(const SvgPlotWriter& plot, int plane, std::string_view title)
        : plot_(plot), plane_(plane), frame_(plane, plot.bounds_), axes_(frame_.axes()),
          first_(axis_letter(axes_.first)), second_(axis_letter(axes_.second)),
          margin_(0.06 * frame_.extent()), font_(0.028 * frame_.extent()),
          stroke_(frame_.extent() / 500.0), gap_(1.5 * font_) {
        measure_plot_band();
        measure_texts(title);
        measure_legend();
        measure_width();
        measure_heights();
    }

    // The document; false when it could not be written or the records not read back.
    bool write(std::FILE* out) const {
        TextSink sink(out);
        write_head(sink);
        write_style(sink);
        write_title(sink);
        const bool read_ok = write_layers(sink);
        write_markers(sink);
        write_scale_and_ranges(sink);
        write_axis_cross(sink);
        write_legend(sink);
        sink.append("</svg>\n");
        return sink.flush() && read_ok;
    }

  private:
    double width_of(std::string_view text) const { return text_width(text, font_); }
    std::string at(double v) const { return frame_.text(v); }
    std::string stroke_width(double factor) const {
        return fmt::format("{:.6g}", stroke_ * factor);
    }
    // A legend row's sample line.
    double row_y(std::size_t row) const {
        return fy_ + (3.4 + 1.5 * static_cast<double>(row)) * font_;
    }

    // Plot band: the drawing, and the error labels ("N80 KorrError") right of and above their
    // markers.
    void measure_plot_band() {
        x0_ = frame_.u0() - margin_;
        plot_right_ = frame_.u1() + margin_;
        plot_top_ = frame_.v1() + margin_;
        for (const Marker& m : plot_.markers_) {
            plot_right_ = std::max(plot_right_, m.where[axes_.first] + 1.2 * font_ +
                                                    width_of(marker_label(m.block, m.code)) + gap_);
            plot_top_ = std::max(plot_top_, m.where[axes_.second] + 2.0 * font_);
        }
    }

    // The texts, measured: title, coordinate ranges.
    void measure_texts(std::string_view title) {
        heading_ = fmt::format("{} \xe2\x80\x94 G{} plane {}, seen from +{}", title, plane_,
                               plane_name(plane_), axis_letter(axes_.third));
        ranges_ = fmt::format("{} {} .. {}, {} {} .. {} mm", first_, frame_.text(frame_.u0()),
                              frame_.text(frame_.u1()), second_, frame_.text(frame_.v0()),
                              frame_.text(frame_.v1()));
    }

    // The legend: the layers drawn, then the markers' kinds ("error", "warning"), the last
    // with those not drawn; `entry_`, the widest entry (its sample of 2 em, then its label).
    void measure_legend() {
        for (std::size_t layer = 0; layer < kPlotLayerCount; ++layer)
            if (plot_.counts_[layer] != 0)
                legend_.emplace_back(layer_label(static_cast<PlotLayer>(layer)));
        const std::vector<Marker>& markers = plot_.markers_;
        warnings_ =
            std::any_of(markers.begin(), markers.end(), [](const Marker& m) { return m.warning; });
        if (std::any_of(markers.begin(), markers.end(), [](const Marker& m) { return !m.warning; }))
            marker_kinds_.push_back("error");
        if (warnings_) marker_kinds_.push_back("warning");
        for (std::size_t k = 0; k < marker_kinds_.size(); ++k)
            legend_.emplace_back(k + 1 < marker_kinds_.size() || plot_.markers_dropped_ == 0
                                     ? std::string(marker_kinds_[k])
                                     : fmt::format("{} ({} more not drawn)", marker_kinds_[k],
                                                   plot_.markers_dropped_));
        for (const std::string& label : legend_)
            entry_ = std::max(entry_, 2.5 * font_ + width_of(label));
    }

    // The page's width: the plot band, the ranges beside the axis cross, one legend entry, the
    // title (wrapped rather than widen the page beyond kTitleEms), the scale bar and its label
    // beside the cross. The bar follows the width (a 1-2-5 length near a quarter of it), and
    // the width the bar: repeated until the bar fits (it is at most 0.4 of the width).
    void measure_width() {
        cross_ = 0.35 * font_ + 2.2 * font_ + 0.3 * font_ + width_of(std::string(1, first_));
        width_ = std::max({plot_right_ - x0_, 2.0 * margin_ + width_of(ranges_) + gap_ + cross_,
                           2.0 * margin_ + entry_});
        width_ = std::max(width_, std::min(2.0 * margin_ + width_of(heading_),
                                           std::max(width_, 2.0 * margin_ + kTitleEms * font_)));
        title_lines_ = wrap_text(heading_, width_ - 2.0 * margin_, font_);
        for (int pass = 0; pass < 64; ++pass) {
            bar_ = scale_bar_length(width_);
            bar_label_ = fmt::format("{} mm", bar_);
            const double needs =
                2.0 * margin_ + bar_ + 0.6 * font_ + width_of(bar_label_) + gap_ + cross_;
            if (needs <= width_) break;
            width_ = needs;
        }
    }

    // Heights: title band, plot band, footer (scale bar, ranges, legend rows); then the view
    // box, out to what the coordinates as written resolve.
    void measure_heights() {
        line_pitch_ = 1.25 * font_;
        const double header =
            2.2 * font_ + static_cast<double>(title_lines_.size() - 1) * line_pitch_;
        y0_ = -plot_top_ - header;
        fy_ = -frame_.v0() + margin_ + 1.2 * font_;
        ranges_y_ = fy_ + 1.85 * font_;
        per_row_ = static_cast<std::size_t>(
            std::max(1.0, std::floor((width_ - 2.0 * margin_ - entry_) / (entry_ + gap_)) + 1.0));
        const std::size_t rows = (legend_.size() + per_row_ - 1) / per_row_;
        const double bottom = rows == 0 ? ranges_y_ + kTextDescent * font_
                                        : row_y(rows - 1) + (0.35 + kTextDescent) * font_;
        const double step = frame_.resolution();
        box_x_ = std::floor(x0_ / step) * step;
        box_y_ = std::floor(y0_ / step) * step;
        box_width_ = std::ceil((x0_ + width_) / step) * step - box_x_;
        box_height_ = std::ceil((bottom + 0.5 * margin_) / step) * step - box_y_;
    }

    // The XML declaration, the <svg> element with its view box, and the document's title
    // (what a viewer shows as its name, and a screen reader reads).
    void write_head(TextSink& sink) const {
        sink.append("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
        sink.append("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"");
        sink.print("{} {} {} {}", at(box_x_), at(box_y_), at(box_width_), at(box_height_));
        sink.print("\" width=\"{:.0f}\" height=\"{:.0f}\">\n", kPixels,
                   std::ceil(kPixels * box_height_ / box_width_));
        sink.append("<title>");
        append_xml_text(sink, heading_);
        sink.append("</title>\n");
    }

    // The style sheet (the cycles' and the warnings' styles only where there are some: plots
    // without stay as they were), then the page's white background.
    void write_style(TextSink& sink) const {
        const auto w = [&](double factor) { return stroke_width(factor); };
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
            "{9}"
            "text {{ font-family: 'DejaVu Sans', sans-serif; font-size: {6}px; fill: #222222; }}\n"
            "text.error {{ fill: #d00000; stroke: none; }}\n"
            "{10}"
            ".frame {{ fill: none; stroke: #cccccc; stroke-width: {7}; }}\n"
            ".axis {{ fill: none; stroke: #222222; stroke-width: {0}; }}\n"
            "</style>\n",
            w(1.0), w(1.6), w(2.2), w(4.0), w(3.0), w(6.0), kTextUnits, w(0.5),
            plot_.counts_[static_cast<std::size_t>(PlotLayer::kCycles)] == 0
                ? std::string()
                : fmt::format(".cycles {{ stroke: #c2185b; stroke-width: {}; }}\n", w(1.0)),
            warnings_ ? fmt::format(".warning {{ fill: none; stroke: #e07b00; stroke-width: {}; }}\n",
                                    w(1.6))
                      : std::string(),
            warnings_ ? std::string("text.warning { fill: #b35f00; stroke: none; }\n")
                      : std::string());
        sink.print("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"white\"/>\n",
                   at(box_x_), at(box_y_), at(box_width_), at(box_height_));
    }

    // Text in its own units (kTextUnits to the font size), placed and scaled into the drawing's,
    // so that no renderer sees a font size of a tiny part's fraction of a millimetre.
    void put_text(TextSink& sink, double x, double y, std::string_view attributes,
                  std::string_view content) const {
        sink.print("<text{} transform=\"translate({} {}) scale({:.6g})\">", attributes, at(x),
                   at(y), font_ / kTextUnits);
        append_xml_text(sink, content);
        sink.append("</text>\n");
    }

    void write_title(TextSink& sink) const {
        for (std::size_t i = 0; i < title_lines_.size(); ++i)
            put_text(sink, frame_.u0(), y0_ + 1.4 * font_ + static_cast<double>(i) * line_pitch_,
                     " class=\"title\"", title_lines_[i]);
    }

    // The layers, one pass over the records each, bottom to top. False when reading failed.
    bool write_layers(TextSink& sink) const {
        bool read_ok = true;
        std::FILE* records = plot_.records_;
        for (std::size_t layer = 0; layer < kPlotLayerCount; ++layer) {
            if (plot_.counts_[layer] == 0) continue;
            std::rewind(records);
            PathEmitter emit(sink, frame_, layer_class(static_cast<PlotLayer>(layer)),
                             0.5 * box_width_ / kPixels);
            Record r;
            while (std::fread(&r, sizeof r, 1, records) == 1)
                if (r.layer == layer) emit.add(segment_of(r));
            if (std::ferror(records)) read_ok = false;
        }
        return read_ok;
    }

    // Error and warning markers: a circle and "N80 KorrError".
    void write_markers(TextSink& sink) const {
        for (const Marker& m : plot_.markers_) {
            sink.append(m.warning ? "<circle class=\"warning\" cx=\""
                                  : "<circle class=\"error\" cx=\"");
            frame_.number(sink, m.where[axes_.first]);
            sink.append("\" cy=\"");
            frame_.number(sink, -m.where[axes_.second]);
            sink.print("\" r=\"{:.6g}\"/>\n", 0.9 * font_);
            put_text(sink, m.where[axes_.first] + 1.2 * font_,
                     -m.where[axes_.second] - 1.0 * font_,
                     m.warning ? " class=\"warning\"" : " class=\"error\"",
                     marker_label(m.block, m.code));
        }
    }

    // Footer: the scale bar and its length, the coordinate ranges below.
    void write_scale_and_ranges(TextSink& sink) const {
        const double bx = frame_.u0();
        sink.print(
            "<path class=\"axis\" id=\"scale-bar\" d=\"M{0} {1} L{2} {1} M{0} {3} L{0} {4} M{2} "
            "{3} L{2} {4}\"/>\n",
            at(bx), at(fy_), at(bx + bar_), at(fy_ - 0.4 * font_), at(fy_ + 0.4 * font_));
        put_text(sink, bx + bar_ + 0.6 * font_, fy_ + 0.35 * font_, " id=\"scale-label\"",
                 bar_label_);
        put_text(sink, bx, ranges_y_, "", ranges_);
    }

    // The plane's axes at the right of the footer: the first axis right, the second up.
    void write_axis_cross(TextSink& sink) const {
        const double ax = x0_ + width_ - margin_ - (cross_ - 0.35 * font_);
        const double ay = fy_ + 1.5 * font_;
        const double len = 2.2 * font_;
        sink.print(
            "<path class=\"axis\" d=\"M{0} {1} L{2} {1} M{0} {1} L{0} {3} M{4} {5} L{2} {1} L{4} "
            "{6} M{7} {8} L{0} {3} L{9} {8}\"/>\n",
            at(ax), at(ay), at(ax + len), at(ay - len), at(ax + len - 0.4 * font_),
            at(ay - 0.25 * font_), at(ay + 0.25 * font_), at(ax - 0.25 * font_),
            at(ay - len + 0.4 * font_), at(ax + 0.25 * font_));
        put_text(sink, ax + len + 0.3 * font_, ay + 0.35 * font_, "", std::string(1, first_));
        put_text(sink, ax - 0.35 * font_, ay - len - 0.4 * font_, "", std::string(1, second_));
    }

    // Legend: a short sample of each layer drawn, then each kind of marker drawn.
    void write_legend(TextSink& sink) const {
        const double bx = frame_.u0();
        std::size_t slot = 0;
        for (std::size_t layer = 0; layer < kPlotLayerCount; ++layer) {
            if (plot_.counts_[layer] == 0) continue;
            const auto l = static_cast<PlotLayer>(layer);
            const double lx = bx + static_cast<double>(slot % per_row_) * (entry_ + gap_);
            const double ly = row_y(slot / per_row_);
            sink.print("<path class=\"{}\" d=\"M{} {} L{} {}\"/>\n", layer_class(l), at(lx),
                       at(ly), at(lx + 2.0 * font_), at(ly));
            put_text(sink, lx + 2.5 * font_, ly + 0.35 * font_, "", legend_[slot]);
            ++slot;
        }
        for (const char* kind : marker_kinds_) {
            const double lx = bx + static_cast<double>(slot % per_row_) * (entry_ + gap_);
            const double ly = row_y(slot / per_row_);
            sink.print("<circle class=\"{}\" cx=\"{}\" cy=\"{}\" r=\"{:.6g}\"/>\n", kind,
                       at(lx + font_), at(ly), 0.5 * font_);
            put_text(sink, lx + 2.5 * font_, ly + 0.35 * font_, "", legend_[slot]);
            ++slot;
        }
    }

    const SvgPlotWriter& plot_;
    int plane_;
    Frame frame_;
    const PlaneAxes& axes_;
    char first_;   // the plane's axes' letters
    char second_;
    double margin_;
    double font_;
    double stroke_;
    double gap_;  // between texts side by side
    double x0_ = 0.0;
    double plot_right_ = 0.0;
    double plot_top_ = 0.0;
    std::string heading_;
    std::string ranges_;
    std::vector<std::string> legend_;       // the layers drawn, then the markers drawn
    std::vector<const char*> marker_kinds_;  // "error", "warning"
    bool warnings_ = false;
    double entry_ = 0.0;  // a legend entry: its sample (2 em), then its label
    double cross_ = 0.0;  // the axis cross's width
    double width_ = 0.0;
    std::vector<std::string> title_lines_;
    double bar_ = 0.0;
    std::string bar_label_;
    double line_pitch_ = 0.0;
    double y0_ = 0.0;
    double fy_ = 0.0;        // the scale bar's line
    double ranges_y_ = 0.0;  // the ranges' baseline
    std::size_t per_row_ = 1;
    double box_x_ = 0.0;
    double box_y_ = 0.0;
    double box_width_ = 0.0;
    double box_height_ = 0.0;
};

bool SvgPlotWriter::finish(std::FILE* out, int plane, std::string_view program) {
    // The program's file name, not where it lies: a plot shared or published does not carry
    // the directories of the machine it was made on.
    const std::string title = std::filesystem::path(program).filename().string();
    if (cycle_pending_) {
        cycle_vertex(cycle_last_);
        cycle_pending_ = false;
    }
    if (!ok() || std::fflush(records_) != 0) return false;
    return Page(*this, plane, title).write(out);
}

}  // namespace apci::run
