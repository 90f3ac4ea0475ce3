// SPDX-License-Identifier: MIT
#include "apci/run/pipeline.h"

#include <pthread.h>

#include <algorithm>
#include <csignal>

namespace apci::run {

namespace {

// The signals the writer thread leaves to the caller's thread: every one that ends the process
// and can be sent to it, less those a thread's own write or fault raises in that thread.
sigset_t process_signals() noexcept {
    sigset_t set;
    sigfillset(&set);
    for (const int sig : {SIGPIPE, SIGXFSZ, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGSYS})
        sigdelset(&set, sig);
    return set;
}

}  // namespace

void PipelinedSink::Batch::clear() noexcept {
    order.clear();
    segments.clear();
    samples.clear();
    notes.clear();
    names.clear();
}

PipelinedSink::PipelinedSink(RunSink& inner) : inner_(inner) {}

PipelinedSink::~PipelinedSink() {
    stop();
}

void PipelinedSink::start() {
    started_ = true;
    // The thread inherits the mask in force when it is made: the process's signals blocked.
    const sigset_t block = process_signals();
    sigset_t saved;
    ::pthread_sigmask(SIG_BLOCK, &block, &saved);
    try {
        writer_ = std::thread([this] { write_loop(); });
    } catch (...) {
        ::pthread_sigmask(SIG_SETMASK, &saved, nullptr);
        throw;
    }
    ::pthread_sigmask(SIG_SETMASK, &saved, nullptr);
}

PipelinedSink::Batch* PipelinedSink::open_batch() {
    if (filling_ != nullptr) return filling_;
    if (finished_) return nullptr;
    if (!started_) start();
    filling_ = ring_.acquire();  // nullptr: the writer stopped
    if (filling_ != nullptr) filling_->clear();
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

void PipelinedSink::deliver(const Batch& b) {
    for (const auto& [kind, i] : b.order) {
        switch (kind) {
            case Kind::kProgrammed:
                inner_.programmed(b.segments[i]);
                break;
            case Kind::kExecuted:
                inner_.executed(b.segments[i]);
                break;
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
        }
    }
}

void PipelinedSink::write_loop() noexcept {
    try {
        while (const Batch* b = ring_.front()) {
            if (ring_.cancelled()) break;  // the caller left without finish()
            deliver(*b);
            ring_.pop();
        }
    } catch (...) {
        failure_ = std::current_exception();
        ring_.cancel();  // the producer waits no more; what it sends is dropped
    }
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
