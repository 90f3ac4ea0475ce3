// SPDX-License-Identifier: MIT
// `apcictl run --svg`: a plot of one run in one plane (17 X-Y, 18 Z-X, 19 Y-Z): the programmed
// contour, the compensated tool-centre path, its transitions, approach and departure moves in
// their own styles, rapid moves, error markers with block number and error name, a scale bar,
// the plane's axes and a legend; the view box fits the drawing, and the page is wide enough
// for the title, the coordinate ranges and the legend (text measured, text_width below).
//
// Streamed: segments go to a temporary file as fixed-size records while the run goes (memory
// stays flat however long the program); finish() reads them back, one pass per layer, and
// writes the document. Seen from the positive third axis of the plane, as the NC program's
// G2/G3 and G41/G42 are: the first axis points right, the second up.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "apci/run/path.h"

namespace apci::run {

// What a segment is in the plot; one style each, drawn in this order.
enum class PlotLayer : std::uint8_t {
    kProgrammed = 0,     // the programmed contour (G01/G02/G03 of the program)
    kRapid = 1,          // executed G00
    kUncompensated = 2,  // executed G01/G02/G03 without compensation
    kApproach = 3,
    kDeparture = 4,
    kContour = 5,  // compensated tool-centre path
    kTransition = 6,
    kCycles = 7,  // the axes cycle by cycle (nominal path plus offsets such as OTC's)
};
inline constexpr std::size_t kPlotLayerCount = 8;
std::string_view layer_class(PlotLayer l) noexcept;  // the CSS class: "programmed", ...
std::string_view layer_label(PlotLayer l) noexcept;  // the legend text
// The layer of an executed segment.
PlotLayer executed_layer(const PathSegment& s) noexcept;

// Axis-aligned bounds in X, Y, Z; empty until the first point.
struct Bounds {
    Point lo = Point::Constant(0.0);
    Point hi = Point::Constant(0.0);
    bool empty = true;
    void add(const Point& p) noexcept;
    // The segment's points and, for arcs, the extreme points of the circle it passes.
    void add(const PathSegment& s) noexcept;
};

class SvgPlotWriter {
  public:
    SvgPlotWriter();
    ~SvgPlotWriter();
    SvgPlotWriter(const SvgPlotWriter&) = delete;
    SvgPlotWriter& operator=(const SvgPlotWriter&) = delete;

    // False when the temporary file could not be made (or written); finish() then fails too.
    bool ok() const noexcept { return records_ != nullptr && !failed_; }

    void programmed(const PathSegment& s);  // a move of the program, before compensation
    void executed(const PathSegment& s);    // a segment of the executed tool-centre path
    // The axes (X, Y, Z) after one interpolation cycle: drawn as the kCycles polyline,
    // simplified as it streams in (Reumann-Witkam): a vertex is kept where the path leaves, by
    // more than kCycleTolerance, the line through the last vertex and the first point at least
    // kCycleStep from it; the last point is always drawn. Straight stretches become one line.
    static constexpr double kCycleStep = 0.02;         // mm
    static constexpr double kCycleTolerance = 0.001;   // mm
    void cycle(const Point& p);
    // A red marker at `where` labelled "N80 KorrError".
    void error_marker(const BlockRef& block, const Point& where, std::string_view code);
    // An orange one, for a warning ("N70 SelfApproach"). Errors and warnings have each their
    // entry in the legend; at most kMaxErrorMarkers of both are drawn.
    void warning_marker(const BlockRef& block, const Point& where, std::string_view code);

    // Writes the document, drawn in `plane` (17, 18, 19), titled with the file name of
    // `program` (its directories left out) in the heading and the <title>. Vertices closer
    // than half a pixel of the 1000-pixel-wide page to the last one drawn are left out (the
    // run's last point of each stretch always drawn). True when written.
    bool finish(std::FILE* out, int plane, std::string_view program);

    const Bounds& bounds() const noexcept { return bounds_; }
    std::uint64_t count(PlotLayer l) const noexcept { return counts_[static_cast<std::size_t>(l)]; }

  private:
    class Page;  // the page around the drawing: measured, then written by finish()
    struct Marker {
        BlockRef block;
        Point where;
        std::string code;
        bool warning = false;
    };
    void add_marker(const BlockRef& block, const Point& where, std::string_view code, bool warning);
    void record(PlotLayer layer, const PathSegment& s);

    std::FILE* records_ = nullptr;
    bool failed_ = false;
    bool have_cycle_ = false;
    bool cycle_pending_ = false;    // the last point seen was not drawn yet
    bool cycle_have_dir_ = false;   // cycle_dir_ is set
    Point cycle_kept_ = Point::Zero();  // the last vertex drawn
    Point cycle_dir_ = Point::Zero();   // a point giving the direction from it
    Point cycle_last_ = Point::Zero();  // the last point seen
    void cycle_vertex(const Point& p);
    Bounds bounds_;
    std::array<std::uint64_t, kPlotLayerCount> counts_{};
    std::vector<Marker> markers_;
    std::uint64_t markers_dropped_ = 0;
};

// Markers kept for the plot; further errors are counted in a note, not drawn.
inline constexpr std::size_t kMaxErrorMarkers = 100;

// The plot's text is set in DejaVu Sans (CSS: 'DejaVu Sans', sans-serif), and the layout
// measures it: text_width is the advance width of `text` (UTF-8) at font size `size`, from
// DejaVu Sans's advance widths for printable ASCII; any other character counts one em (the em
// dash of the title is one em). The usual fallbacks (Helvetica, Arial, Liberation Sans) are
// narrower, so text measured so fits with them too. A line of text reaches kTextAscent em
// above its baseline and kTextDescent em below (DejaVu Sans: 1901 and 483 of 2048 units).
double text_width(std::string_view text, double size) noexcept;
inline constexpr double kTextAscent = 0.93;
inline constexpr double kTextDescent = 0.24;

// `text` in lines of at most `width` at font size `size` (by text_width), cut after a space or
// a slash where one fits, else between two characters; a line holds at least one character.
std::vector<std::string> wrap_text(std::string_view text, double width, double size);

// The scale bar's length for a page `width` wide: the 1-2-5 value (1, 2 or 5 times a power of
// ten) nearest, by ratio, to a quarter of the width. It lies between width / 5 and width / 3
// whenever a 1-2-5 value does, and always between width / 6.33 and width / 2.53.
double scale_bar_length(double width) noexcept;

}  // namespace apci::run
