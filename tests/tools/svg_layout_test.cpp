// SPDX-License-Identifier: MIT
// The layout of `apcictl run --svg`: for parts of any aspect ratio and size, the title, the
// coordinate ranges, the legend and the labels lie inside the view box and do not overlap, by
// the same text metric the writer lays them out with; the scale bar is a 1-2-5 length about a
// quarter of the page's width and its label says the length drawn.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apci/run/svg_writer.h"
#include "test_segments.h"

namespace apci::run {
namespace {

std::string write_svg(SvgPlotWriter& w, int plane, std::string_view title) {
    std::FILE* f = std::tmpfile();
    EXPECT_NE(f, nullptr);
    if (f == nullptr) return {};
    EXPECT_TRUE(w.finish(f, plane, title));
    std::rewind(f);
    std::string text;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) text.append(buffer, n);
    std::fclose(f);
    return text;
}

PathSegment line(const Point& a, const Point& b, Role role) {
    return test_segments::line(10, a, b, role);
}

double number(const std::string& text) {
    return std::stod(text);
}

std::string xml_text(std::string text) {
    for (const auto& [entity, c] : std::vector<std::pair<std::string, std::string>>{
             {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&amp;", "&"}}) {
        for (auto at = text.find(entity); at != std::string::npos; at = text.find(entity, at + 1))
            text.replace(at, entity.size(), c);
    }
    return text;
}

struct Box {
    double x0, y0, x1, y1;
    std::string text;
};

struct Layout {
    double vx = 0, vy = 0, vw = 0, vh = 0;  // the viewBox
    std::vector<Box> texts;
    std::vector<double> sizes;       // each text's font size in the drawing's units
    std::vector<std::string> title;  // the title's lines
    double bar = 0.0;                // the scale bar's drawn length
    double bar_label = 0.0;          // what its label says, in mm
};

// Reads the view box, the font sizes of the stylesheet, every <text> (as a box by
// text_width, kTextAscent and kTextDescent), the scale bar and its label.
Layout parse(const std::string& svg) {
    Layout out;
    std::smatch m;
    EXPECT_TRUE(
        std::regex_search(svg, m, std::regex("viewBox=\"([^ ]+) ([^ ]+) ([^ ]+) ([^\"]+)\"")));
    out.vx = number(m[1]);
    out.vy = number(m[2]);
    out.vw = number(m[3]);
    out.vh = number(m[4]);
    EXPECT_TRUE(std::regex_search(svg, m, std::regex("\ntext \\{[^}]*font-size: ([^p]+)px")));
    const double font = number(m[1]);  // in the text's own units, scaled into the drawing's
    const std::regex text_element("<text ([^>]*)>([^<]*)</text>");
    const std::regex placed("transform=\"translate\\(([^ ]+) ([^)]+)\\) scale\\(([^)]+)\\)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), text_element);
         it != std::sregex_iterator(); ++it) {
        const std::string attributes = (*it)[1];
        const std::string content = xml_text((*it)[2]);
        std::smatch a;
        EXPECT_TRUE(std::regex_search(attributes, a, placed)) << attributes;
        const double x = number(a[1]);
        const double y = number(a[2]);
        const double size = font * number(a[3]);
        out.texts.push_back(Box{x, y - kTextAscent * size, x + text_width(content, size),
                                y + kTextDescent * size, content});
        out.sizes.push_back(size);
        if (attributes.find("class=\"title\"") != std::string::npos) out.title.push_back(content);
        if (attributes.find("id=\"scale-label\"") != std::string::npos) {
            EXPECT_TRUE(content.ends_with(" mm")) << content;
            out.bar_label = number(content.substr(0, content.size() - 3));
        }
    }
    EXPECT_TRUE(std::regex_search(
        svg, m, std::regex("id=\"scale-bar\" d=\"M([^ ]+) ([^ ]+) L([^ ]+) ([^ ]+) ")));
    out.bar = number(m[3]) - number(m[1]);
    EXPECT_EQ(m[2], m[4]);  // horizontal
    return out;
}

bool is_1_2_5(double v) {
    const double p = std::pow(10.0, std::floor(std::log10(v) + 1e-9));
    const double mantissa = v / p;
    for (const double m : {1.0, 2.0, 5.0})
        if (std::abs(mantissa - m) < 1e-9 * m) return true;
    return false;
}

// Whether a 1-2-5 value lies in lo..hi.
bool any_1_2_5_within(double lo, double hi) {
    for (int k = -12; k <= 12; ++k)
        for (const double m : {1.0, 2.0, 5.0})
            if (m * std::pow(10.0, k) >= lo && m * std::pow(10.0, k) <= hi) return true;
    return false;
}

void check_layout(const std::string& svg, const std::string& what) {
    SCOPED_TRACE(what);
    const Layout l = parse(svg);
    ASSERT_GT(l.vw, 0.0);
    ASSERT_GT(l.vh, 0.0);
    ASSERT_FALSE(l.texts.empty());
    const double slack = 1e-9 * std::max(l.vw, l.vh);
    for (const Box& b : l.texts) {
        EXPECT_GE(b.x0, l.vx - slack) << b.text;
        EXPECT_LE(b.x1, l.vx + l.vw + slack)
            << b.text << " ends at " << b.x1 << ", the page at " << l.vx + l.vw;
        EXPECT_GE(b.y0, l.vy - slack) << b.text;
        EXPECT_LE(b.y1, l.vy + l.vh + slack) << b.text;
    }
    for (std::size_t i = 0; i < l.texts.size(); ++i) {
        for (std::size_t j = i + 1; j < l.texts.size(); ++j) {
            const Box& a = l.texts[i];
            const Box& b = l.texts[j];
            const bool apart = a.x1 <= b.x0 || b.x1 <= a.x0 || a.y1 <= b.y0 || b.y1 <= a.y0;
            EXPECT_TRUE(apart) << "'" << a.text << "' overlaps '" << b.text << "'";
        }
    }
    // The bar: a 1-2-5 length, its label the length drawn, about a quarter of the page.
    EXPECT_TRUE(is_1_2_5(l.bar_label)) << l.bar_label;
    EXPECT_NEAR(l.bar, l.bar_label, 1e-3 * l.bar_label);
    EXPECT_GE(l.bar, l.vw / 6.33) << "page " << l.vw;
    EXPECT_LE(l.bar, l.vw / 2.53) << "page " << l.vw;
    if (any_1_2_5_within(l.vw / 5.0, l.vw / 3.0)) {
        EXPECT_GE(l.bar, l.vw / 5.0 * (1 - 1e-6)) << "page " << l.vw;
        EXPECT_LE(l.bar, l.vw / 3.0 * (1 + 1e-6)) << "page " << l.vw;
    }
}

// A rectangle w x h at (x, y): programmed, executed as a contour, and (with `everything`)
// every other layer, per-cycle points and two error markers, so the legend is full.
std::string rectangle_svg(double x, double y, double w, double h, bool everything,
                          std::string_view title = "part.nc") {
    SvgPlotWriter plot;
    const Point a(x, y, 0), b(x + w, y, 0), c(x + w, y + h, 0), d(x, y + h, 0);
    for (const auto& [p, q] : {std::pair{a, b}, {b, c}, {c, d}, {d, a}}) {
        plot.programmed(line(p, q, Role::kContour));
        plot.executed(line(p, q, Role::kContour));
    }
    if (everything) {
        PathSegment rapid = line(a, c, Role::kUncompensated);
        rapid.kind = SegmentKind::kRapid;
        plot.executed(rapid);
        plot.executed(line(a, c, Role::kUncompensated));
        plot.executed(line(b, d, Role::kApproach));
        plot.executed(line(d, b, Role::kDeparture));
        plot.executed(line(a, d, Role::kTransition));
        plot.cycle(a);
        plot.cycle(c);
        BlockRef n80;
        n80.number = 80;
        plot.error_marker(n80, a, "KorrError");
        BlockRef line12;
        line12.line = 12;
        plot.error_marker(line12, c, "CalcError");
    }
    return write_svg(plot, 17, title);
}

// ---- the text metric and the bar's length (pure functions)

TEST(SvgLayout, TextWidthIsDejaVuSansAdvanceWidths) {
    EXPECT_EQ(text_width("", 10.0), 0.0);
    EXPECT_DOUBLE_EQ(text_width("A", 2048.0), 1401.0);
    EXPECT_DOUBLE_EQ(text_width(" ", 2048.0), 651.0);
    EXPECT_DOUBLE_EQ(text_width("mm", 2048.0), 2.0 * 1995.0);
    EXPECT_DOUBLE_EQ(text_width("X 0 .. 10", 1.0), 2.0 * text_width("X 0 .. 10", 0.5));
    EXPECT_LT(text_width("iiii", 1.0), text_width("MMMM", 1.0));
    // Any other character, the em dash (three UTF-8 bytes) among them, is one em.
    EXPECT_DOUBLE_EQ(text_width("\xe2\x80\x94", 10.0), 10.0);
    EXPECT_DOUBLE_EQ(text_width("a\xc3\xa9z", 2048.0), 1255.0 + 2048.0 + 1075.0);
}

TEST(SvgLayout, ScaleBarIsTheOneTwoFiveLengthNearestAQuarterOfTheWidth) {
    EXPECT_EQ(scale_bar_length(100.0), 20.0);  // a quarter: 25
    EXPECT_EQ(scale_bar_length(224.0), 50.0);  // 56
    EXPECT_EQ(scale_bar_length(135.0), 50.0);  // 33.75: nearer 50 than 20 by ratio
    EXPECT_EQ(scale_bar_length(0.0112), 0.002);
    EXPECT_EQ(scale_bar_length(0.002), 0.0005);  // the double nearest 5e-4, printed so
    EXPECT_EQ(fmt::format("{}", scale_bar_length(0.002)), "0.0005");
    for (int step = 0; step < 400; ++step) {  // widths from 1e-4 to beyond 1e7
        const double width = 1e-4 * std::pow(1.07, step);
        const double bar = scale_bar_length(width);
        EXPECT_TRUE(is_1_2_5(bar)) << width;
        EXPECT_GE(bar, width / 6.33) << width;
        EXPECT_LE(bar, width / 2.53) << width;
        if (any_1_2_5_within(width / 5.0, width / 3.0)) {
            EXPECT_GE(bar, width / 5.0 * (1 - 1e-12)) << width;
            EXPECT_LE(bar, width / 3.0 * (1 + 1e-12)) << width;
        }
    }
}

// ---- pages of any shape

TEST(SvgLayout, TallPartOneToTwenty) {
    check_layout(rectangle_svg(0, 0, 10, 200, false), "10 x 200");
    check_layout(rectangle_svg(0, 0, 10, 200, true), "10 x 200, every layer and markers");
}

TEST(SvgLayout, WidePartTwentyToOne) {
    check_layout(rectangle_svg(0, 0, 200, 10, false), "200 x 10");
    check_layout(rectangle_svg(0, 0, 200, 10, true), "200 x 10, every layer and markers");
}

TEST(SvgLayout, SquarePart) {
    check_layout(rectangle_svg(0, 0, 100, 100, false), "100 x 100");
    check_layout(rectangle_svg(-50, -50, 100, 100, true), "100 x 100, every layer and markers");
}

TEST(SvgLayout, TinyPart) {
    check_layout(rectangle_svg(0, 0, 0.01, 0.01, false), "0.01 x 0.01");
    check_layout(rectangle_svg(1000, -1000, 0.01, 0.01, true), "0.01 x 0.01 at (1000, -1000)");
}

TEST(SvgLayout, HugePart) {
    check_layout(rectangle_svg(0, 0, 1e5, 1e5, false), "1e5 x 1e5");
    check_layout(rectangle_svg(-1e5, 0, 1e5, 2e3, true), "1e5 x 2e3, every layer and markers");
}

TEST(SvgLayout, EmptyPlotAndASinglePoint) {
    SvgPlotWriter empty;
    check_layout(write_svg(empty, 17, "empty.nc"), "nothing drawn");
    SvgPlotWriter point;
    BlockRef n10;
    n10.number = 10;
    point.error_marker(n10, Point(5, 5, 0), "KorrError");
    check_layout(write_svg(point, 18, "point.nc"), "one error marker");
}

TEST(SvgLayout, LongTitleIsWrappedOnThePage) {
    const std::string name = "a very long program name " + std::string(250, 'W') + ".nc";
    const std::string svg = rectangle_svg(0, 0, 10, 200, false, "/a/directory/" + name);
    check_layout(svg, "long title");
    const Layout l = parse(svg);
    ASSERT_GT(l.title.size(), 2u);
    std::string joined;
    for (const std::string& line : l.title) joined += line;
    // Cut at the space before the long word (the space ends the line, not drawn).
    EXPECT_EQ(joined, "a very long program name" + std::string(250, 'W') +
                          ".nc \xe2\x80\x94 G17 plane X-Y, seen from +Z");
    EXPECT_EQ(l.title.front(), "a very long program name");
    // Every text at one size, the page not many times the drawing's width.
    for (const double size : l.sizes) EXPECT_DOUBLE_EQ(size, l.sizes.front());
    EXPECT_LT(l.vw, 45.0 * l.sizes.front());
}

// The plot names the program by its file name: the directories of the machine it was drawn on
// stay there. The document's <title> says what the heading says.
TEST(SvgTitle, NamesTheProgramsFileNameNotItsDirectories) {
    const std::string svg = rectangle_svg(0, 0, 10, 20, false, "/home/someone/secret/part.nc");
    EXPECT_EQ(svg.find("/home/someone"), std::string::npos) << svg;
    EXPECT_EQ(svg.find("secret"), std::string::npos);
    const auto open = svg.find("<title>");
    ASSERT_NE(open, std::string::npos);
    EXPECT_LT(open, svg.find("<style>"));  // the first child of <svg>
    EXPECT_EQ(svg.substr(open, svg.find("</title>") - open),
              "<title>part.nc \xe2\x80\x94 G17 plane X-Y, seen from +Z");
    const Layout l = parse(svg);
    ASSERT_EQ(l.title.size(), 1u);
    EXPECT_EQ(l.title.front(), "part.nc \xe2\x80\x94 G17 plane X-Y, seen from +Z");
    // Characters XML reserves, escaped in both.
    const std::string amp = rectangle_svg(0, 0, 10, 20, false, "a&b<c>.nc");
    EXPECT_NE(amp.find("<title>a&amp;b&lt;c&gt;.nc"), std::string::npos) << amp;
}

// The vertices of a layer's paths ("M.. L.. L.."), as numbers in pairs; the layer's last path,
// its sample in the legend, left out. Scanned by hand: libstdc++'s std::regex recurses once per
// character it matches, and a path of 100,000 characters overflows the stack under
// AddressSanitizer.
std::vector<std::pair<double, double>> path_vertices(const std::string& svg, std::string_view css) {
    const std::string open = "<path class=\"" + std::string(css) + "\" d=\"";
    std::vector<std::string_view> paths;
    for (std::size_t at = svg.find(open); at != std::string::npos; at = svg.find(open, at)) {
        at += open.size();
        const std::size_t end = svg.find('"', at);
        if (end == std::string::npos) break;
        paths.emplace_back(svg.data() + at, end - at);
        at = end;
    }
    if (!paths.empty()) paths.pop_back();
    std::vector<std::pair<double, double>> out;
    for (const std::string_view d : paths) {
        std::istringstream in{std::string(d)};
        char command = 0;
        double x = 0.0, y = 0.0;
        while (in >> command) {
            EXPECT_TRUE(command == 'M' || command == 'L') << "path command " << command;
            if (!(in >> x >> y)) break;
            out.emplace_back(x, y);
        }
    }
    return out;
}

// A program of many segments far below a pixel (a spiral of 300,000 steps of 0.2 um on a
// 1000-pixel page 100 mm wide: 1/500 pixel each) is drawn with vertices at least half a pixel
// apart, and ends where the path ends; segments longer than a pixel keep every vertex.
TEST(SvgSimplification, VerticesBelowHalfAPixelAreLeftOut) {
    SvgPlotWriter plot;
    const Point corner0(0, 0, 0), corner1(100, 100, 0);
    plot.programmed(line(corner0, corner1, Role::kContour));  // spans the drawing: 100 x 100 mm
    constexpr int kSteps = 300'000;
    Point last(50, 50, 0);
    for (int i = 1; i <= kSteps; ++i) {
        const double t = 0.06 * i / kSteps * 2 * 3.141592653589793 * 10;  // ~2 turns
        const double r = 10.0 + 20.0 * i / kSteps;
        const Point p(50 + r * std::cos(t), 50 + r * std::sin(t), 0);
        plot.executed(line(last, p, Role::kContour));
        last = p;
    }
    const std::string svg = write_svg(plot, 17, "spiral.nc");
    EXPECT_LT(svg.size(), 200'000u) << "the plot of 300,000 sub-pixel segments is "
                                    << svg.size() << " bytes";
    const auto v = path_vertices(svg, "contour");
    ASSERT_GT(v.size(), 100u);
    // The page's pixel in the drawing's units: the view box's width over 1000 pixels.
    const std::size_t box = svg.find("viewBox=\"");
    ASSERT_NE(box, std::string::npos);
    double box_x = 0.0, box_y = 0.0, box_width = 0.0;
    std::istringstream(svg.substr(box + 9, 100)) >> box_x >> box_y >> box_width;
    const double pixel = box_width / 1000.0;
    // Coordinates are written to 0.01 at this size: two of those below half a pixel at most.
    const double written = 0.01;
    for (std::size_t i = 1; i + 1 < v.size(); ++i)
        EXPECT_GE(std::hypot(v[i].first - v[i - 1].first, v[i].second - v[i - 1].second),
                  0.5 * pixel - 2 * written)
            << "vertex " << i;
    // The last vertex is the path's end (y drawn upwards: negated).
    EXPECT_NEAR(v.back().first, last.x(), written);
    EXPECT_NEAR(v.back().second, -last.y(), written);

    // Long segments: every vertex stays.
    SvgPlotWriter coarse;
    Point from(0, 0, 0);
    for (int i = 1; i <= 100; ++i) {
        const Point to(i, (i % 2) * 10.0, 0);
        coarse.executed(line(from, to, Role::kContour));
        from = to;
    }
    EXPECT_EQ(path_vertices(write_svg(coarse, 17, "zigzag.nc"), "contour").size(), 101u);
}

// A contour run pass after pass (a loop, step-downs seen from above: the plot's plane does not
// show the depth) is drawn once: 50,000 passes of a 20-sided polygon (1,000,000 segments, every
// other pass the way back) give the plot of one pass.
// A pass two millimetres (about 18 pixels) aside is a second line and is drawn; segments that
// all differ are all drawn, more of them than the table of drawn segments remembers.
TEST(SvgSimplification, SegmentsDrawnAgainAreLeftOut) {
    constexpr int kSides = 20;
    std::vector<Point> corners;
    for (int i = 0; i < kSides; ++i) {
        const double t = 2 * 3.141592653589793 * i / kSides;
        corners.emplace_back(50 + 50 * std::cos(t), 50 + 50 * std::sin(t), 0);
    }
    const auto draw = [&](SvgPlotWriter& plot, int passes, double shift) {
        for (int pass = 0; pass < passes; ++pass)
            for (int i = 0; i < kSides; ++i) {
                // Odd passes go the way back, corner to corner.
                const int from = pass % 2 == 0 ? i : kSides - i;
                const int to = pass % 2 == 0 ? i + 1 : kSides - i - 1;
                Point a = corners[static_cast<std::size_t>(from % kSides)];
                Point b = corners[static_cast<std::size_t>(to % kSides)];
                for (Point* p : {&a, &b}) {
                    p->x() += pass % 2 == 1 ? shift : 0.0;
                    p->z() = -0.001 * pass;  // one step down a pass
                }
                plot.executed(line(a, b, Role::kContour));
            }
    };
    SvgPlotWriter once;
    draw(once, 1, 0.0);
    SvgPlotWriter passes;
    draw(passes, 50'000, 0.0);
    const std::string svg = write_svg(passes, 17, "passes.nc");
    EXPECT_LT(svg.size(), 10'000u) << "1,000,000 segments of one contour drawn again and again";
    EXPECT_EQ(path_vertices(svg, "contour"),
              path_vertices(write_svg(once, 17, "passes.nc"), "contour"));

    SvgPlotWriter aside;
    draw(aside, 1'000, 2.0);
    // Each of the two lines once: M and kSides vertices each.
    EXPECT_EQ(path_vertices(write_svg(aside, 17, "aside.nc"), "contour").size(),
              2u * (kSides + 1));

    // 150,000 different lines a pixel or more apart (ends on a 0.25 mm grid; the page is about
    // 120 mm wide, 0.12 mm a pixel): each drawn, M and L.
    SvgPlotWriter distinct;
    constexpr int kDistinct = 150'000;
    for (int k = 0; k < kDistinct; ++k)
        distinct.executed(line(Point(0.25 * (k % 400), 0, 0), Point(0.25 * (k / 400), 100, 0),
                               Role::kContour));
    EXPECT_EQ(path_vertices(write_svg(distinct, 17, "distinct.nc"), "contour").size(),
              2u * kDistinct);
}

PathSegment arc(const Point& a, const Point& b, const Point& centre, bool ccw, int plane) {
    return test_segments::arc(10, a, b, centre, ccw, Role::kContour, plane);
}

// The commands of a layer's paths (the legend's sample left out), each with its end point:
// "M", "L" or "A" and x, y as written.
struct Command {
    char c;
    double x, y;
};
std::vector<Command> path_commands(const std::string& svg, std::string_view css) {
    const std::string open = "<path class=\"" + std::string(css) + "\" d=\"";
    std::vector<std::string> paths;
    for (std::size_t at = svg.find(open); at != std::string::npos; at = svg.find(open, at)) {
        at += open.size();
        const std::size_t end = svg.find('"', at);
        if (end == std::string::npos) break;
        paths.push_back(svg.substr(at, end - at));
        at = end;
    }
    if (!paths.empty()) paths.pop_back();
    std::vector<Command> out;
    for (const std::string& d : paths) {
        std::istringstream in{d};
        char c = 0;
        while (in >> c) {
            double skip = 0.0;
            if (c == 'A')
                for (int i = 0; i < 5; ++i) in >> skip;  // rx ry rotation large-arc sweep
            Command k{c, 0.0, 0.0};
            if (!(in >> k.x >> k.y)) break;
            out.push_back(k);
        }
    }
    return out;
}
std::string letters(const std::vector<Command>& commands) {
    std::string out;
    for (const Command& k : commands) out += k.c;
    return out;
}

// The frame of the tests below: a programmed diagonal over 100 x 100 mm, about 0.12 mm a
// pixel of the 1000-pixel page, coordinates written to 0.01 mm.
void frame_100(SvgPlotWriter& plot) {
    plot.programmed(line(Point(0, 0, 0), Point(100, 100, 0), Role::kContour));
}

// An arc of the plotted plane is the same drawn again only with the same ends, centre and
// sense: the other way round between the same ends (the rest of its circle) and another
// circle through them are other arcs.
TEST(SvgSimplification, AnArcIsDrawnAgainOnlyWithItsEndsCentreAndSense) {
    SvgPlotWriter plot;
    frame_100(plot);
    const Point a(60, 50, 0), b(50, 60, 0);
    plot.executed(arc(a, b, Point(50, 50, 0), true, 17));   // a quarter: one A
    plot.executed(arc(a, b, Point(50, 50, 0), false, 17));  // three quarters: two halves
    plot.executed(arc(a, b, Point(60, 60, 0), false, 17));  // a quarter of another circle
    plot.executed(arc(a, b, Point(50, 50, 0), true, 17));   // the first again: left out
    const std::string drawn = letters(path_commands(write_svg(plot, 17, "arcs.nc"), "contour"));
    EXPECT_EQ(std::count(drawn.begin(), drawn.end(), 'A'), 4) << drawn;
}

// An arc out of the plotted plane is drawn as its projection whatever was drawn before: two
// half circles in the YZ plane from one point, of radius 10 and 20, both project onto the
// point (50, 50) at their ends and centres, yet reach 10 and 20 mm along Y seen from above.
TEST(SvgSimplification, ArcsOutOfThePlottedPlaneAreNeverTakenForDrawn) {
    SvgPlotWriter plot;
    frame_100(plot);
    plot.executed(arc(Point(50, 50, 0), Point(50, 50, 20), Point(50, 50, 10), true, 19));
    plot.executed(arc(Point(50, 50, 0), Point(50, 50, 40), Point(50, 50, 20), true, 19));
    double reach = 0.0;
    for (const Command& k : path_commands(write_svg(plot, 17, "yz.nc"), "contour")) {
        EXPECT_NEAR(k.x, 50.0, 0.01);
        reach = std::max(reach, std::abs(-k.y - 50.0));
    }
    EXPECT_NEAR(reach, 20.0, 0.05);  // the polyline's vertex nearest the top
}

// Lines a pixel and more apart (0.15 mm, a pixel about 0.12 mm) are each drawn: the table of
// drawn segments keys them on a quarter pixel, not coarser.
TEST(SvgSimplification, LinesAPixelApartAreEachDrawn) {
    SvgPlotWriter plot;
    frame_100(plot);
    constexpr int kLines = 20;
    for (int k = 0; k < kLines; ++k)
        plot.executed(line(Point(0, 20 + 0.15 * k, 0), Point(100, 20 + 0.15 * k, 0),
                           Role::kContour));
    EXPECT_EQ(letters(path_commands(write_svg(plot, 17, "hatch.nc"), "contour")),
              [] {
                  std::string ml;
                  for (int k = 0; k < kLines; ++k) ml += "ML";
                  return ml;
              }());
}

// A line under half a pixel is left to the vertices' simplification, even where the same one
// was drawn before: a path that ends with it ends where it ends (0.04 mm past the corner).
TEST(SvgSimplification, AShortLineDrawnBeforeStillEndsItsPath) {
    SvgPlotWriter plot;
    frame_100(plot);
    const PathSegment tail = line(Point(50, 50, 0), Point(50.04, 50, 0), Role::kContour);
    plot.executed(tail);
    plot.executed(line(Point(0, 80, 0), Point(50, 50, 0), Role::kContour));
    plot.executed(tail);
    const std::vector<Command> drawn = path_commands(write_svg(plot, 17, "tail.nc"), "contour");
    ASSERT_FALSE(drawn.empty());
    EXPECT_NEAR(drawn.back().x, 50.04, 0.005);
    EXPECT_NEAR(drawn.back().y, -50.0, 0.005);
}

// After segments left out, a segment that starts within half a pixel of where the pen stands
// goes on from there (a line to its start, then the segment) instead of a subpath of its own;
// a gap as small with nothing left out before it starts a subpath ("M"), as any gap does.
TEST(SvgSimplification, AfterSegmentsLeftOutTheNextGoesOnFromThePen) {
    SvgPlotWriter plot;
    frame_100(plot);
    const std::vector<Point> square{Point(0, 0, 0), Point(50, 0, 0), Point(50, 50, 0),
                                    Point(0, 50, 0), Point(0, 0, 0)};
    for (int pass = 0; pass < 2; ++pass)
        for (std::size_t i = 0; i + 1 < square.size(); ++i)
            plot.executed(line(square[i], square[i + 1], Role::kContour));
    // The second pass was left out; the pen stands at (0, 0). A quarter arc from 0.02 mm
    // beside it.
    plot.executed(arc(Point(0.02, 0, 0), Point(10.02, -10, 0), Point(0.02, -10, 0), false, 17));
    const std::vector<Command> drawn = path_commands(write_svg(plot, 17, "pen.nc"), "contour");
    EXPECT_EQ(letters(drawn), "MLLLLLA");
    ASSERT_EQ(drawn.size(), 7u);
    EXPECT_NEAR(drawn[5].x, 0.02, 0.005);  // the line to the arc's start
    EXPECT_NEAR(drawn[5].y, 0.0, 0.005);

    SvgPlotWriter gap;
    frame_100(gap);
    gap.executed(line(Point(0, 0, 0), Point(50, 0, 0), Role::kContour));
    gap.executed(line(Point(50.02, 0, 0), Point(50.02, 50, 0), Role::kContour));
    EXPECT_EQ(letters(path_commands(write_svg(gap, 17, "gap.nc"), "contour")), "MLML");
}

TEST(SvgLayout, WrapCutsAfterASpaceOrSlashElseBetweenCharacters) {
    const double size = 1.0;
    const auto width = [&](std::string_view t) { return text_width(t, size); };
    EXPECT_EQ(wrap_text("", 10.0, size), std::vector<std::string>{});
    EXPECT_EQ(wrap_text("abc def", 100.0, size), std::vector<std::string>{"abc def"});
    EXPECT_EQ(wrap_text("abc def", width("abc de"), size),
              (std::vector<std::string>{"abc", "def"}));
    EXPECT_EQ(wrap_text("/dir/file.nc", width("/dir/file"), size),
              (std::vector<std::string>{"/dir/", "file.nc"}));
    EXPECT_EQ(wrap_text("abcdef", width("abcd"), size), (std::vector<std::string>{"abcd", "ef"}));
    // Narrower than one character: one a line. A UTF-8 character is never cut.
    EXPECT_EQ(wrap_text("ab", 0.01, size), (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(wrap_text("a\xe2\x80\x94"
                        "b",
                        width("a") + 0.5, size),
              (std::vector<std::string>{"a", "\xe2\x80\x94", "b"}));
}

// The text is set in its own units, scaled into the drawing's: a tiny part's font size is
// not a fraction of a micrometre, which renderers round to nothing.
TEST(SvgLayout, TextUnitsDoNotShrinkWithThePart) {
    for (const double size : {0.01, 1.0, 1e5}) {
        const std::string svg = rectangle_svg(0, 0, size, size, false);
        std::smatch m;
        ASSERT_TRUE(std::regex_search(svg, m, std::regex("\ntext \\{[^}]*font-size: ([^p]+)px")));
        EXPECT_EQ(m[1], "10") << size;
    }
}

}  // namespace
}  // namespace apci::run
