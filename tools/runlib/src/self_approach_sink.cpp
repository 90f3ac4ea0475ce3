// SPDX-License-Identifier: MIT
#include "apci/run/self_approach_sink.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

namespace apci::run {

SelfApproachSink::SelfApproachSink(RunSink& next, SelfApproachMode mode,
                                   SelfApproachCheck::Schedule schedule)
    : next_(next),
      mode_(mode),
      check_(SelfApproachCheck::kWindow, SelfApproachCheck::kEntryBudget,
             SelfApproachCheck::Candidates::kGrid, schedule),
      next_measures_(next.measures_executed()) {}

void SelfApproachSink::programmed(const PathSegment& s) {
    next_.programmed(s);
    if (!open_ || stopped_) return;
    check_.programmed(s, new_);
    found();
}

void SelfApproachSink::executed(const PathSegment& s) {
    // Where the next sink would measure the segment (a pipeline's writers), it is measured here
    // instead and handed on measured: the check's shape takes its sweep (shape_of), and the
    // writers take it as it comes (the same values, on whichever thread).
    const PathSegment* at = &s;
    if (next_measures_ && std::isnan(s.length)) {
        measured_ = s;
        measure(measured_);
        at = &measured_;
    }
    next_.executed(*at);
    if (edge_.isZero(0.0))
        check_.executed(*at, new_);
    else
        check_.executed(nose_centre_path(*at, edge_, plane_), new_);
    found();
}

void SelfApproachSink::error(const RunError& e, const Point& where) {
    next_.error(e, where);
    stopped_ = true;
}

void SelfApproachSink::stretch_begin(const CompensatedStretch& s) {
    next_.stretch_begin(s);
    check_.begin(s.radius, s.plane, s.side);
    plane_ = s.plane;
    edge_ = s.edge;
    open_ = true;
}

void SelfApproachSink::stretch_end() {
    next_.stretch_end();
    open_ = false;
    check_.end(new_);
    found();
}

void SelfApproachSink::walls(bool on) {
    next_.walls(on);
    check_.set_walls(on);
}

std::optional<RunError> SelfApproachSink::take_stop() {
    std::optional<RunError> stop = std::move(stop_);
    stop_.reset();
    return stop;
}

void SelfApproachSink::found() {
    if (new_.empty()) return;
    if (mode_ == SelfApproachMode::kError) {
        // The first is the run's error; the run stops there and the rest are not looked at,
        // nor what the axes still run of the move under way once the run stopped (the run has
        // its error: one).
        if (stopped_) {
            new_.clear();
            return;
        }
        const SelfApproachFinding& f = new_.front();
        findings_.push_back(f);
        stop_ = RunError{f.path_block, "SelfApproach", describe(f)};
        new_.clear();
        return;
    }
    for (const SelfApproachFinding& f : new_) {
        findings_.push_back(f);
        warnings_.push_back(RunError{f.path_block, "SelfApproach", describe(f)});
        next_.warning(warnings_.back(), f.where);
    }
    new_.clear();
}

void SelfApproachSink::results(RunOutcome& out) const {
    out.self_approach.insert(out.self_approach.end(), findings_.begin(), findings_.end());
    out.warnings.insert(out.warnings.end(), warnings_.begin(), warnings_.end());
    const SelfApproachLimits limits = check_.limits();
    if (limits.truncated)
        out.notices.push_back(RunError{
            limits.truncated_at, "SelfApproachTruncated",
            fmt::format("from here on the self-approach check compared each compensated element "
                        "in G{} only with the {} distinct elements before it (fewer where they "
                        "are long): where the path comes back near the contour further back than "
                        "that, it was not checked",
                        limits.truncated_plane, SelfApproachCheck::kWindow)});
    if (limits.capped)
        out.notices.push_back(RunError{
            {},
            "SelfApproachCapped",
            fmt::format("more than {0} pairs of blocks come near each other: the first {0} are "
                        "reported, and the self-approach check stopped looking there",
                        SelfApproachCheck::kMaxFindings)});
}

}  // namespace apci::run
