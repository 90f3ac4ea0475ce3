// SPDX-License-Identifier: MIT
// The numbers of `apcictl run --json` (JsonRunWriter) are the text of append_json_number
// (std::to_chars, the shortest that reads back exactly; whole numbers as integers; null where
// not finite), whichever faster way the writer takes to them: program-like values with a few
// decimals, computed values with 17 digits, the notation boundaries (1e-3, 1e-4, 1e15), -0,
// and a start written again from the end before it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "memory_file.h"
#include "apci/run/json_writer.h"
#include "apci/run/text_sink.h"

namespace {

using apci::run::JsonRunWriter;
using apci::run::PathSegment;
using apci::run::Point;

using apci_test::MemoryFile;

// The reference: append_json_number, the text before the writer had its own formatting. One
// sink for every value: a sink holds a 1 MiB buffer, and one for each of the random test's
// 900,000 values took longer than its time limit under AddressSanitizer.
std::string reference(double v) {
    static MemoryFile file;
    static apci::run::TextSink sink(file.get());
    static std::size_t read = 0;
    apci::run::append_json_number(sink, v);
    EXPECT_TRUE(sink.flush());
    const std::string_view written = file.view();
    std::string text(written.substr(read));
    read = written.size();
    return text;
}

std::string reference_point(const Point& p) {
    return "[" + reference(p.x()) + "," + reference(p.y()) + "," + reference(p.z()) + "]";
}

PathSegment arc(const Point& start, const Point& end, const Point& center) {
    PathSegment s;
    s.block.number = 10;
    s.kind = apci::run::SegmentKind::kArc;
    s.role = apci::run::Role::kContour;
    s.start = start;
    s.end = end;
    s.center = center;
    return s;
}

// The segments' lines of the writer's JSON, against the reference text of their points.
void expect_same_text(const std::vector<PathSegment>& segments) {
    MemoryFile f;
    {
        JsonRunWriter w(f.get());
        for (const auto& s : segments) w.segment(s);
        ASSERT_TRUE(w.finish({}, {}));
    }
    std::string expected = "{\"segments\":[";
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const PathSegment& s = segments[i];
        expected += i == 0 ? "\n{" : ",\n{";
        expected += "\"block\":10,\"kind\":\"arc\",\"role\":\"contour\",\"start\":" +
                    reference_point(s.start) + ",\"end\":" + reference_point(s.end) +
                    ",\"center\":" + reference_point(s.center) + ",\"ccw\":false,\"plane\":17}";
    }
    expected += "],\n";
    const std::string got = f.text();
    ASSERT_GE(got.size(), expected.size());
    // Compare line by line: a difference names its segment.
    std::size_t at = 0, line = 0;
    while (at < expected.size()) {
        const std::size_t end = expected.find('\n', at);
        const std::size_t stop = end == std::string::npos ? expected.size() : end + 1;
        ASSERT_EQ(got.substr(at, stop - at), expected.substr(at, stop - at)) << "line " << line;
        at = stop;
        ++line;
    }
}

TEST(JsonNumbers, EdgeValuesAreWrittenAsStdToChars) {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<double> values{0.0,
                                     -0.0,
                                     1.0,
                                     -1.0,
                                     0.5,
                                     -0.5,
                                     0.1,
                                     0.2,
                                     0.3,
                                     1.0 / 3.0,
                                     2.0 / 3.0,
                                     92.373,
                                     -61.5396,
                                     86.65039999999999,
                                     63.180600000000005,
                                     1e-3,
                                     -1e-3,
                                     1.2e-3,
                                     0.001,
                                     0.0015,
                                     0.00099999,
                                     1e-4,
                                     -1e-4,
                                     2e-4,
                                     0.0001234,
                                     0.00012,
                                     1.5e-5,
                                     1e-7,
                                     1.4210854715202004e-14,
                                     5e-324,
                                     2.2250738585072014e-308,
                                     999999999.9999,
                                     999999999.99999,
                                     1e9 + 0.5,
                                     123456789.1234,
                                     1e15 - 0.5,
                                     1e15 + 0.5,
                                     1e15,
                                     -1e15,
                                     1e16,
                                     9007199254740993.0,
                                     1e21,
                                     1e22,
                                     1.7976931348623157e308,
                                     -1.7976931348623157e308,
                                     99999.99999999999,
                                     100000.00000000001,
                                     0.30000000000000004,
                                     inf,
                                     -inf,
                                     nan};
    std::vector<PathSegment> segments;
    segments.reserve(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double a = values[i], b = values[(i + 1) % values.size()];
        const double c = values[(i + 7) % values.size()];
        segments.push_back(arc({a, b, c}, {b, c, a}, {c, a, b}));
    }
    expect_same_text(segments);
}

TEST(JsonNumbers, RandomValuesOfEveryKindAreWrittenAsStdToChars) {
    std::mt19937_64 rnd(20261126);
    std::uniform_real_distribution<double> coordinate(-2000.0, 2000.0);
    std::uniform_int_distribution<int> decimals(0, 6), kind(0, 3);
    std::uniform_int_distribution<std::uint64_t> bits;
    const auto value = [&]() -> double {
        switch (kind(rnd)) {
            case 0: {  // as programmed: a few decimals
                const double scale = std::pow(10.0, decimals(rnd));
                return std::round(coordinate(rnd) * scale) / scale;
            }
            case 1:  // computed: 15 to 17 digits
                return coordinate(rnd) + 1.0 / 3.0;
            case 2: {  // small, about the notation boundaries 1e-3 and 1e-4
                const double scale = std::pow(10.0, decimals(rnd));
                return std::round(coordinate(rnd) * scale) / scale * 1e-6;
            }
            default: {  // any bit pattern
                double v = 0.0;
                const std::uint64_t b = bits(rnd);
                std::memcpy(&v, &b, sizeof v);
                return v;
            }
        }
    };
    constexpr int kSegments = 100000;
    std::vector<PathSegment> segments;
    segments.reserve(kSegments);
    for (int i = 0; i < kSegments; ++i)
        segments.push_back(arc({value(), value(), value()}, {value(), value(), value()},
                               {value(), value(), value()}));
    expect_same_text(segments);
}

// Fixed notation with the point among the digits, at every place it can be: whole parts of 1
// to 15 digits with fractions of 1 to 17 - whole digits (every digit count of the shortest
// text), both signs; 17-digit values of every magnitude there; the last values below and the
// first above each power of ten; and the texts with no whole part (0.00123, down to 1e-3) and
// beyond 1e15.
TEST(JsonNumbers, EveryPlaceOfThePointAndEveryDigitCountIsWrittenAsStdToChars) {
    std::mt19937_64 rnd(20261127);
    std::uniform_int_distribution<int> digit(0, 9), nonzero(1, 9);
    std::vector<double> values{-0.0, 0.0};
    for (int whole = 1; whole <= 15; ++whole) {
        for (int fraction = 1; whole + fraction <= 17; ++fraction)
            for (int k = 0; k < 40; ++k) {
                std::string text = k % 2 == 0 ? "-" : "";
                for (int i = 0; i < whole + fraction; ++i) {
                    if (i == whole) text += '.';
                    const bool edge = i == 0 || i == whole + fraction - 1;
                    text += static_cast<char>('0' + (edge ? nonzero(rnd) : digit(rnd)));
                }
                values.push_back(std::strtod(text.c_str(), nullptr));
            }
        const double low = std::pow(10.0, whole - 1), high = std::pow(10.0, whole);
        std::uniform_real_distribution<double> within(low, high);
        for (int k = 0; k < 200; ++k) values.push_back(k % 2 == 0 ? within(rnd) : -within(rnd));
        for (const double p : {low, high}) {
            double below = p, above = p;
            for (int k = 0; k < 4; ++k) {
                below = std::nextafter(below, 0.0);
                above = std::nextafter(above, INFINITY);
                values.insert(values.end(), {below, above, -below, -above});
            }
        }
    }
    std::uniform_real_distribution<double> small(1e-3, 1.0), tiny(1e-300, 1e-3), huge(1e15, 1e300);
    for (int k = 0; k < 2000; ++k)
        values.insert(values.end(),
                      {small(rnd), -small(rnd), tiny(rnd), -tiny(rnd), huge(rnd), -huge(rnd)});
    std::vector<PathSegment> segments;
    segments.reserve(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double a = values[i], b = values[(i + 1) % values.size()];
        const double c = values[(i + 5) % values.size()];
        segments.push_back(arc({a, b, c}, {b, c, a}, {c, a, b}));
    }
    expect_same_text(segments);
}

// The long numbers' digits (9 to 17 of them, the last 16 made in one piece): every digit at
// every place of the digits, with the point after the first, the middle or the last but one,
// both signs.
TEST(JsonNumbers, EveryDigitAtEveryPlaceOfALongNumberIsWrittenAsStdToChars) {
    std::mt19937_64 rnd(20261126);
    std::uniform_int_distribution<int> digit(0, 9), nonzero(1, 9);
    std::vector<double> values;
    for (int count = 9; count <= 17; ++count)
        for (int place = 0; place < count; ++place)
            for (int d = 0; d <= 9; ++d)
                for (const int whole : {1, count / 2, count - 1}) {
                    std::string text = (place + d) % 2 == 0 ? "-" : "";
                    for (int i = 0; i < count; ++i) {
                        if (i == whole) text += '.';
                        const bool edge = i == 0 || i == count - 1;
                        const int v = i == place ? d : edge ? nonzero(rnd) : digit(rnd);
                        text += static_cast<char>('0' + (edge && v == 0 ? 1 : v));
                    }
                    values.push_back(std::strtod(text.c_str(), nullptr));
                }
    std::vector<PathSegment> segments;
    for (std::size_t i = 0; i + 2 < values.size(); i += 3)
        segments.push_back(arc({values[i], values[i + 1], values[i + 2]},
                               {values[i + 2], values[i], values[i + 1]},
                               {values[i + 1], values[i + 2], values[i]}));
    expect_same_text(segments);
}

// A start is written again from the end before only when it has the same bits: 0 after -0
// (equal as numbers) is written "0", and a start elsewhere is written anew.
TEST(JsonNumbers, AStartAfterAnEndWithOtherBitsIsWrittenAnew) {
    std::vector<PathSegment> segments{
        arc({1.5, 2.25, 0.0}, {-0.0, 3.125, 7.0}, {0.0, 0.0, 0.0}),
        arc({0.0, 3.125, 7.0}, {4.0, 5.0, 6.0}, {1.0, 1.0, 1.0}),
        arc({4.0, 5.0, 6.0}, {0.1, 0.2, 0.30000000000000004}, {1.0, 1.0, 1.0}),
        arc({0.1, 0.2, 0.3}, {0.1, 0.2, 0.3}, {1.0, 1.0, 1.0}),
        arc({0.1, 0.2, 0.3}, {-0.0, -0.0, -0.0}, {1.0, 1.0, 1.0}),
        arc({-0.0, -0.0, -0.0}, {1.0, 1.0, 1.0}, {1.0, 1.0, 1.0})};
    expect_same_text(segments);
}

// The third coordinate is written from the last one's text only when it has the same bits: 0
// (the first, from the writer's start) and -0 alternating, equal values of other bits, NaN and
// infinities, repeated and not, in starts, ends and centres.
TEST(JsonNumbers, AThirdCoordinateIsCopiedFromTheLastOnlyWithTheSameBits) {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<double> zs{
        0.0,  -0.0,  -0.0,  0.0,    0.0,     nan,  nan,
        -nan, inf,   -inf,  -inf,   -0.7,    -0.7, std::nextafter(-0.7, 0.0),
        -0.7, 1e300, 1e300, 5e-324, -5e-324, 1e-4, 1e-4,
        12.5, 12.5,  3.0,   3.0,    -3.0,    0.0,  -0.0};
    std::vector<PathSegment> segments;
    for (std::size_t i = 0; i + 2 < zs.size(); ++i) {
        // Starts where the segment before ended (its text again) and elsewhere.
        const double start_z = i % 3 == 0 ? zs[i + 1] : zs[i];
        segments.push_back(arc({1.5, 2.0, start_z}, {2.5, 1.0, zs[i + 1]}, {1.0, 1.0, zs[i + 2]}));
    }
    expect_same_text(segments);
}

// Every shape of record, with block and line numbers and whole coordinates at each digit-count
// boundary (10^k - 1, 10^k, 10^k + 1) and at the ends of the 64-bit range: the text of
// std::to_chars for the integers, the record as the writer wrote it piece by piece before it
// wrote records in place.
TEST(JsonNumbers, IntegersAtEveryDigitCountAndEveryRecordShapeAreWrittenAsBefore) {
    std::vector<std::int64_t> integers{0,
                                       1,
                                       -1,
                                       std::numeric_limits<std::int64_t>::max(),
                                       std::numeric_limits<std::int64_t>::min(),
                                       std::numeric_limits<std::int64_t>::min() + 1};
    for (std::int64_t p = 10; p <= std::numeric_limits<std::int64_t>::max() / 10; p *= 10)
        for (const std::int64_t v : {p - 1, p, p + 1, -(p - 1), -p, -(p + 1)})
            integers.push_back(v);
    const auto text = [](std::int64_t v) { return std::to_string(v); };
    const apci::run::SegmentKind kinds[] = {apci::run::SegmentKind::kRapid,
                                            apci::run::SegmentKind::kLine,
                                            apci::run::SegmentKind::kArc};
    const apci::run::Role roles[] = {apci::run::Role::kContour, apci::run::Role::kTransition,
                                     apci::run::Role::kApproach, apci::run::Role::kDeparture,
                                     apci::run::Role::kUncompensated};
    MemoryFile f;
    std::string expected = "{\"segments\":[";
    {
        JsonRunWriter w(f.get());
        for (std::size_t i = 0; i < integers.size(); ++i) {
            PathSegment s;
            const std::int64_t n = integers[i];
            // A block without a number (-1) names its line: here the integer's magnitude.
            const bool numbered = i % 3 != 0;
            s.block.number = numbered ? n : apci::run::kNoBlock;
            s.block.line = static_cast<std::uint64_t>(n < 0 ? -(n + 1) : n) + 1;
            s.kind = kinds[i % 3];
            s.role = roles[i % 5];
            // Whole coordinates below 1e15 are written as integers.
            const double whole = static_cast<double>(n % 1000000000000000);
            s.start = {whole, -whole, 0.0};
            s.end = {whole / 2 == std::trunc(whole / 2) ? whole / 2 : whole, 1.0, -7.0};
            s.center = {3.0, whole, 0.5};
            s.ccw = i % 2 == 0;
            s.plane = 17 + static_cast<int>(i % 3);
            w.segment(s);
            expected += i == 0 ? "\n{" : ",\n{";
            expected += "\"block\":" + text(s.block.number);
            if (s.block.number == apci::run::kNoBlock)
                expected += ",\"line\":" + text(static_cast<std::int64_t>(s.block.line));
            expected += ",\"kind\":\"" + std::string(apci::run::kind_name(s.kind)) +
                        "\",\"role\":\"" + std::string(apci::run::role_name(s.role)) +
                        "\",\"start\":" + reference_point(s.start) +
                        ",\"end\":" + reference_point(s.end);
            if (s.kind == apci::run::SegmentKind::kArc)
                expected += ",\"center\":" + reference_point(s.center) +
                            (s.ccw ? ",\"ccw\":true" : ",\"ccw\":false") +
                            ",\"plane\":" + text(s.plane);
            expected += "}";
        }
        ASSERT_TRUE(w.finish({}, {}));
    }
    expected += "],\n";
    const std::string got = f.text();
    ASSERT_GE(got.size(), expected.size());
    EXPECT_EQ(got.substr(0, expected.size()), expected);
}

}  // namespace

namespace {

// A kind or role that is no enumerator (a corrupt value) is written with the names kind_name
// and role_name give it, as every other record: not from the table of the enumerators' texts.
TEST(JsonNumbers, AKindOrRoleOutsideTheEnumeratorsIsWrittenWithItsNames) {
    const std::pair<int, int> pairs[] = {{3, 0}, {0, 5}, {255, 255}, {1, 4}, {7, 1}};
    MemoryFile f;
    std::string expected = "{\"segments\":[";
    {
        JsonRunWriter w(f.get());
        bool first = true;
        for (const auto& [kind, role] : pairs) {
            PathSegment s;
            s.block.number = 5;
            s.kind = static_cast<apci::run::SegmentKind>(kind);
            s.role = static_cast<apci::run::Role>(role);
            s.start = {1.0, 2.0, 3.0};
            s.end = {4.0, 5.0, 6.0};
            w.segment(s);
            expected += first ? "\n{" : ",\n{";
            first = false;
            expected += "\"block\":5,\"kind\":\"" + std::string(apci::run::kind_name(s.kind)) +
                        "\",\"role\":\"" + std::string(apci::run::role_name(s.role)) +
                        "\",\"start\":[1,2,3],\"end\":[4,5,6]}";
        }
        ASSERT_TRUE(w.finish({}, {}));
    }
    expected += "],\n";
    const std::string got = f.text();
    ASSERT_GE(got.size(), expected.size());
    EXPECT_EQ(got.substr(0, expected.size()), expected);
}

}  // namespace

namespace {

// Block numbers as a program's segments bring them: the same again (a transition of its
// block), one more (counted up in the last text, across every digit count: 9, 99, ... and up
// to the largest), jumps up and down, 0, and blocks without a number (-1, with their line) or
// a negative one between them.
TEST(JsonNumbers, BlockNumbersAgainOneMoreOrAnyAreWrittenAsStdToChars) {
    std::vector<std::int64_t> numbers;
    for (std::int64_t n = 0; n <= 1200; ++n) numbers.insert(numbers.end(), {n, n});
    for (std::int64_t p = 10; p <= std::numeric_limits<std::int64_t>::max() / 10; p *= 10)
        numbers.insert(numbers.end(), {p - 2, p - 1, p - 1, p, p + 1, 7, p + 1, apci::run::kNoBlock,
                                       p + 2, -p, p + 3, p + 2, 0, 1});
    const std::int64_t max = std::numeric_limits<std::int64_t>::max();
    numbers.insert(numbers.end(), {max - 2, max - 1, max, max, 5, max - 1, max});
    MemoryFile f;
    std::string expected = "{\"segments\":[";
    {
        JsonRunWriter w(f.get());
        for (std::size_t i = 0; i < numbers.size(); ++i) {
            PathSegment s;
            s.block.number = numbers[i];
            s.block.line = i + 1;
            s.kind = apci::run::SegmentKind::kLine;
            s.role = apci::run::Role::kContour;
            s.start = {1.0, 2.0, 3.0};
            s.end = {4.0, 5.0, 6.0};
            w.segment(s);
            expected += i == 0 ? "\n{" : ",\n{";
            expected += "\"block\":" + std::to_string(s.block.number);
            if (s.block.number == apci::run::kNoBlock)
                expected += ",\"line\":" + std::to_string(s.block.line);
            expected +=
                ",\"kind\":\"line\",\"role\":\"contour\",\"start\":[1,2,3],\"end\":[4,5,6]}";
        }
        ASSERT_TRUE(w.finish({}, {}));
    }
    expected += "],\n";
    const std::string got = f.text();
    ASSERT_GE(got.size(), expected.size());
    std::size_t at = 0, line = 0;  // line by line: a difference names its segment
    while (at < expected.size()) {
        const std::size_t stop = std::min(expected.find('\n', at), expected.size() - 1) + 1;
        ASSERT_EQ(got.substr(at, stop - at), expected.substr(at, stop - at)) << "line " << line;
        at = stop;
        ++line;
    }
}

}  // namespace
