// SPDX-License-Identifier: MIT
// `apcictl run --json`: one JSON object (docs/design.md section 7), written as the run goes. The
// "segments" array is streamed, one segment a line, so a run of any length is written in
// constant memory; "errors", "registers" and "variables" follow at the end:
//
//   {"segments":[
//   {"block":70,"kind":"line","role":"contour","start":[2,-30,0],"end":[102,-30,0]},
//   {"block":80,"kind":"arc","role":"transition","start":[..],"end":[..],"center":[..],"ccw":true,"plane":17},
//   ...],
//   "errors":[{"block":80,"code":"KorrError","message":"..."}],
//   "registers":{"1":{"ERROR":0,"ERROR_bits":[],"STATUS":0,"STATUS_bits":[]},"2":...,"3":...},
//   "variables":{}}
//
// A block without an N number is "block": -1 with its source "line" added.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <utility>

#include "apci/run/path.h"
#include "apci/run/text_sink.h"

namespace apci::run {

class JsonRunWriter {
  public:
    // Writes to `out` (not owned; open until finish() returned).
    explicit JsonRunWriter(std::FILE* out);

    // Appends one executed segment.
    void segment(const PathSegment& s);
    // Closes "segments" and writes the rest of the object. True when every byte was written.
    bool finish(std::span<const RunError> errors, std::span<const GroupRegisters> registers);
    // The same with the readable NC variables ("variables": {"V.G.OTC_ACTIVE": 0, ...}) and the
    // notices ("notices": [{"block":85,"code":"NotEmulated","message":...}], written only when
    // there are any).
    bool finish(std::span<const RunError> errors, std::span<const GroupRegisters> registers,
                std::span<const std::pair<std::string, double>> variables,
                std::span<const RunError> notices,
                std::span<const RunError> warnings = {});

    std::uint64_t segments_written() const noexcept { return count_; }

  private:
    void begin_segments();
    void block(const BlockRef& b);
    void error_list(std::span<const RunError> errors);

    TextSink sink_;
    std::uint64_t count_ = 0;
    bool begun_ = false;
    // The last segment's end and its text: the next segment's start is mostly the same point,
    // written again from here rather than formatted anew.
    Point last_end_ = Point::Zero();
    std::array<char, 112> last_end_text_{};
    std::size_t last_end_size_ = 0;
    // "[x,y,z]" of p; returns its end.
    char* point_text(char* out, const Point& p);
    // The last third coordinate written and its text (kept by its bits: -0 and 0 differ): it
    // mostly stays (a pass at one depth, an arc's centre at the depth of its end), and its text
    // is copied rather than formatted anew. (The other axes change from point to point: a
    // check there costs more than it saves.)
    struct AxisText {
        std::uint64_t bits = 0;  // +0, written "0"
        std::array<char, 32> text{'0'};
        std::size_t size = 1;
    };
    AxisText last_z_;
    // The last segment's N number (>= 0) and its text: the next segment's is mostly the same
    // (a transition of its block) or one more (counted up in the text); size 0: none yet.
    std::int64_t last_block_ = 0;
    std::array<char, 32> last_block_text_{};
    std::size_t last_block_size_ = 0;
    // "block":N of a segment (N >= 0) at out, from last_block_text_; returns its end.
    char* segment_block_text(char* out, std::int64_t number);
    // ,"kind":"arc","role":"contour","start": for every kind and role (by their values), each
    // padded to the same size: one copy of fixed size writes them.
    struct KindRoleText {
        std::array<char, 64> text{};
        std::size_t size = 0;
    };
    static constexpr std::size_t kKinds = 3, kRoles = 5;
    std::array<KindRoleText, kKinds * kRoles> kind_role_texts_{};
};

}  // namespace apci::run
