// SPDX-License-Identifier: MIT
// The self-approach check (self_approach.h) as a sink of its own: it stands in the chain of
// sinks between the executor and the next sink, hands every call on unchanged, and runs a
// SelfApproachCheck on the run's facts as they pass:
//
//   stretch_begin   the check begins a compensated stretch (radius, plane, side); the stretch's
//                   plane and a turning tool's cutting edge offset are kept for the executed
//                   segments (the check measures the nose centre, nose_centre_path);
//   programmed      a move programmed while a stretch is open is an element of the contour;
//                   the moves given after the run stopped (the rest of the program, drawn) are
//                   not run and not checked;
//   executed        every executed segment is a path the check measures; where the next sink
//                   measures the segments (measures_executed()), this one measures each
//                   (measure()) and hands it on measured, so that both take the same sweep;
//   stretch_end     the stretch ends;
//   walls           CDON / CDOF (docs/compensation.md, "What is a wall").
//
// A finding is, with SelfApproachMode::kWarn, a warning "SelfApproach" given to the next sink
// where it was found (warning()) and kept for the outcome (results()); with kError, the run's
// error: take_stop() hands it to the executor, which records it and stops the run there.
//
// Where it stands (program_run.h): with kError on the executor's thread (before the output
// pipeline), so the run stops at the segment that cut; with kWarn after the pipeline's ring,
// on the writer thread, where the segments go anyway.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "apci/run/executor.h"
#include "apci/run/self_approach.h"

namespace apci::run {

// What the run does where the compensated path comes near the contour away from its corners
// (self_approach.h): a warning (the default), the run's error, or nothing checked.
enum class SelfApproachMode { kWarn, kError, kOff };

class SelfApproachSink final : public RunSink {
  public:
    // `next` must outlive this. `mode` is kWarn or kError (kOff: no check, no sink); `schedule`
    // as SelfApproachCheck's (the same findings either way: kAtOnce is the tests' reference).
    SelfApproachSink(RunSink& next, SelfApproachMode mode,
                     SelfApproachCheck::Schedule schedule = SelfApproachCheck::Schedule::kHoldApart);

    void programmed(const PathSegment& s) override;
    bool wants_programmed() const override { return next_.wants_programmed(); }
    void executed(const PathSegment& s) override;
    bool measures_executed() const override { return next_.measures_executed(); }
    void measured_lengths(double& path, double& rapid) override {
        next_.measured_lengths(path, rapid);
    }
    void axes(std::span<const std::string> names) override { next_.axes(names); }
    void axis_numbers(const std::array<int, 3>& xyz) override { next_.axis_numbers(xyz); }
    bool wants_samples() const override { return next_.wants_samples(); }
    void sample(std::uint64_t cycle, double time_s, std::span<const double> axes) override {
        next_.sample(cycle, time_s, axes);
    }
    void error(const RunError& e, const Point& where) override;
    void warning(const RunError& w, const Point& where) override { next_.warning(w, where); }
    void stretch_begin(const CompensatedStretch& s) override;
    void stretch_end() override;
    void walls(bool on) override;
    std::optional<RunError> take_stop() override;
    void progress(std::uint64_t blocks, std::uint64_t offset) override {
        next_.progress(blocks, offset);
    }

    // Appends to the outcome what the check found: the findings (out.self_approach), with
    // kWarn their warnings (out.warnings), and a notice where the check left something out
    // (SelfApproachTruncated, SelfApproachCapped). Once, after the last call.
    void results(RunOutcome& out) const;

  private:
    void found();  // the check's new findings out: warnings, or the stop

    RunSink& next_;
    SelfApproachMode mode_;
    SelfApproachCheck check_;
    // The next sink measures the executed segments (measures_executed(), asked once): this one
    // measures them for it, into measured_, before the check takes them.
    bool next_measures_;
    PathSegment measured_;
    // The plane and cutting edge offset of the stretch under way or last run.
    int plane_ = 17;
    Eigen::Vector2d edge_ = Eigen::Vector2d::Zero();
    bool open_ = false;     // a stretch is open
    bool stopped_ = false;  // the run recorded an error: what is programmed now is not run
    std::vector<SelfApproachFinding> new_;       // the check's, not yet taken
    std::vector<SelfApproachFinding> findings_;  // every one taken, in order
    std::vector<RunError> warnings_;             // kWarn: behind findings_
    std::optional<RunError> stop_;               // kError: for take_stop()
};

}  // namespace apci::run
