// SPDX-License-Identifier: MIT
#include "apci/run/pipeline.h"

#include <algorithm>
#include <cmath>

#include "quiet_thread.h"

namespace apci::run {

void PipelinedSink::Batch::clear() noexcept {
    order.clear();
    segments.clear();
    samples.clear();
    notes.clear();
    names.clear();
    stretches.clear();
}

PipelinedSink::PipelinedSink(RunSink& inner, const CpuPlacement* cpus, HelperCpu where,
                             std::size_t writer_wakes_after)
    : inner_(inner),
      cpus_(cpus),
      where_(where),
      ring_(kBatches, kProducerWakesAfter, writer_wakes_after) {
    // Every batch's arrays, full, carved from one block of the slab.
    using detail::Slab;
    static_assert(kBatches *
                      (Slab::carved(kBatchEvents * sizeof(decltype(Batch::order)::value_type)) +
                       Slab::carved(kBatchEvents * sizeof(PathSegment))) <=
                  Slab::kBlockBytes);
}

PipelinedSink::~PipelinedSink() {
    stop();
}

void PipelinedSink::start() {
    started_ = true;
    inner_measures_ = inner_.measures_executed();  // before the writer reads it
    writer_ = exec::quiet_thread("apci-pipeline", [this] { write_loop(); });
}

PipelinedSink::Batch* PipelinedSink::open_batch() {
    if (filling_ != nullptr) return filling_;
    if (finished_) return nullptr;
    if (!started_) start();
    filling_ = ring_.acquire();  // nullptr: the writer stopped
    if (filling_ == nullptr) return nullptr;
    filling_->clear();
    if (filling_->order.capacity() == 0) {
        // Its first time round: the arrays every full batch takes, carved from the slab at
        // once (made ready there: slab.h) rather than
        // grown and faulted in a page at a time as they fill.
        filling_->order =
            decltype(filling_->order)(decltype(filling_->order)::allocator_type(&slab_));
        filling_->segments =
            decltype(filling_->segments)(decltype(filling_->segments)::allocator_type(&slab_));
        filling_->order.reserve(kBatchEvents);
        filling_->segments.reserve(kBatchEvents);
    }
    return filling_;
}

void PipelinedSink::add(Kind kind, std::uint32_t index) {
    filling_->order.emplace_back(kind, index);
    if (filling_->order.size() >= kBatchEvents) commit();
}

void PipelinedSink::commit() {
    if (filling_ == nullptr) return;
    filling_ = nullptr;
    ring_.commit();
}

void PipelinedSink::programmed(const PathSegment& s) {
    if (!inner_.takes_programmed()) return;  // not copied for nothing
    Batch* b = open_batch();
    if (b == nullptr) return;
    b->segments.push_back(s);
    add(Kind::kProgrammed, static_cast<std::uint32_t>(b->segments.size() - 1));
}

void PipelinedSink::executed(const PathSegment& s) {
    Batch* b = open_batch();
    if (b == nullptr) return;
    b->segments.push_back(s);
    add(Kind::kExecuted, static_cast<std::uint32_t>(b->segments.size() - 1));
}

void PipelinedSink::axes(std::span<const std::string> names) {
    Batch* b = open_batch();
    if (b == nullptr) return;
    const auto first = static_cast<std::uint32_t>(b->names.size());
    b->names.insert(b->names.end(), names.begin(), names.end());
    // The names of this event: from `first` up to the next event's (or the end).
    b->names.emplace_back();  // an empty name closes the list (no axis is unnamed)
    add(Kind::kAxes, first);
}

void PipelinedSink::axis_numbers(const std::array<int, 3>& xyz) {
    Batch* b = open_batch();
    if (b == nullptr) return;
    b->xyz = xyz;
    // The numbers are kept once a batch: a second change in one batch starts the next.
    add(Kind::kAxisNumbers, 0);
    commit();
}

void PipelinedSink::sample(std::uint64_t cycle, double time_s, std::span<const double> axes) {
    Batch* b = open_batch();
    if (b == nullptr) return;
    Sample s;
    s.cycle = cycle;
    s.time_s = time_s;
    s.count = static_cast<std::uint32_t>(std::min(axes.size(), s.axes.size()));
    std::copy_n(axes.begin(), s.count, s.axes.begin());
    b->samples.push_back(s);
    add(Kind::kSample, static_cast<std::uint32_t>(b->samples.size() - 1));
}

void PipelinedSink::error(const RunError& e, const Point& where) {
    Batch* b = open_batch();
    if (b == nullptr) return;
    b->notes.push_back(Note{e, where});
    add(Kind::kError, static_cast<std::uint32_t>(b->notes.size() - 1));
}

void PipelinedSink::warning(const RunError& w, const Point& where) {
    Batch* b = open_batch();
    if (b == nullptr) return;
    b->notes.push_back(Note{w, where});
    add(Kind::kWarning, static_cast<std::uint32_t>(b->notes.size() - 1));
}

void PipelinedSink::deliver(Batch& b) {
    for (const auto& [kind, i] : b.order) {
        switch (kind) {
            case Kind::kProgrammed:
                inner_.programmed(b.segments[i]);
                break;
            case Kind::kExecuted: {
                PathSegment& s = b.segments[i];
                // Unmeasured from the executor, and measured here unless the inner sink
                // measures them (then they go on as they came); one that comes measured is
                // not measured again.
                if (!inner_measures_) {
                    if (std::isnan(s.length)) measure(s);
                    count_segment(measured_, s);
                }
                inner_.executed(s);
                break;
            }
            case Kind::kSample: {
                const Sample& s = b.samples[i];
                inner_.sample(s.cycle, s.time_s, std::span<const double>(s.axes.data(), s.count));
                break;
            }
            case Kind::kError:
                inner_.error(b.notes[i].what, b.notes[i].where);
                break;
            case Kind::kWarning:
                inner_.warning(b.notes[i].what, b.notes[i].where);
                break;
            case Kind::kAxes: {
                const auto first = b.names.begin() + i;
                inner_.axes(std::span<const std::string>(
                    &*first, static_cast<std::size_t>(
                                 std::find(first, b.names.end(), std::string()) - first)));
                break;
            }
            case Kind::kAxisNumbers:
                inner_.axis_numbers(b.xyz);
                break;
            case Kind::kBarrier:
                writer_reached(true);
                break;
            case Kind::kStretchBegin:
                inner_.stretch_begin(b.stretches[i]);
                break;
            case Kind::kStretchEnd:
                inner_.stretch_end();
                break;
            case Kind::kWalls:
                inner_.walls(i != 0);
                break;
        }
    }
}

void PipelinedSink::write_loop() noexcept {
    if (cpus_ != nullptr) cpus_->place_helper(where_);
    try {
        while (Batch* b = ring_.front()) {
            if (ring_.cancelled()) break;  // the caller left without finish()
            deliver(*b);
            ring_.pop();
        }
    } catch (...) {
        failure_ = std::current_exception();
        ring_.cancel();  // the producer waits no more; what it sends is dropped
    }
    writer_reached(false);
}

void PipelinedSink::writer_reached(bool barrier) noexcept {
    {
        const std::lock_guard<std::mutex> lock(sync_mutex_);
        if (barrier) {
            ++barriers_passed_;
        } else {
            writer_ended_ = true;
        }
    }
    synced_.notify_all();
}

void PipelinedSink::sync() {
    if (!started_) return;
    const std::uint64_t barrier = ++barriers_sent_;
    if (open_batch() != nullptr) {
        add(Kind::kBarrier, 0);
        commit();
        ring_.flush();  // the writer may sleep until half the ring is ready
    }
    std::unique_lock<std::mutex> lock(sync_mutex_);
    synced_.wait(lock, [&] { return barriers_passed_ >= barrier || writer_ended_; });
}

void PipelinedSink::measured_lengths(double& path, double& rapid) {
    sync();
    // Every segment is the inner sink's now: its sums. The writer thread waits for the next
    // batch (sync() ordered what it did before this), so the caller's thread may call the
    // inner sink (a second pipeline's measured_lengths() hands over its barrier from here).
    if (inner_measures_) {
        inner_.measured_lengths(path, rapid);
        return;
    }
    path = measured_.path_length;
    rapid = measured_.rapid_length;
}

// ---- the compensated stretches, in their place among the calls

void PipelinedSink::add_only(Kind kind, std::uint32_t index) {
    if (open_batch() != nullptr) add(kind, index);
}

void PipelinedSink::stretch_begin(const CompensatedStretch& s) {
    Batch* b = open_batch();
    if (b == nullptr) return;
    b->stretches.push_back(s);
    add(Kind::kStretchBegin, static_cast<std::uint32_t>(b->stretches.size() - 1));
}

void PipelinedSink::stretch_end() {
    add_only(Kind::kStretchEnd);
}

void PipelinedSink::walls(bool on) {
    add_only(Kind::kWalls, on ? 1 : 0);
}

void PipelinedSink::finish() {
    if (finished_) return;
    commit();
    finished_ = true;
    ring_.close();
    if (writer_.joinable()) writer_.join();
    if (failure_) std::rethrow_exception(failure_);
}

// On a path out without finish() (an exception on the caller's thread): the writer takes no
// more, and the thread is joined.
void PipelinedSink::stop() noexcept {
    if (finished_) return;
    finished_ = true;
    filling_ = nullptr;
    ring_.cancel();
    ring_.close();
    if (writer_.joinable()) writer_.join();
}

}  // namespace apci::run
