// SPDX-License-Identifier: MIT
#include "apci/run/read_ahead.h"

#include <stdexcept>
#include <utility>

#include "quiet_thread.h"

namespace apci::run {

using Next = nc::EventStream::Next;

// The ring's batches get their items from the reader (open_batch), the first time it fills
// each: carved from the slab (made ready there: slab.h) rather than faulted in a page at a time,
// and not on the caller's thread.
ReadAhead::ReadAhead(nc::EventStream& stream, const CpuPlacement* cpus, HelperCpu where,
                     const RingFill* follows)
    : stream_(stream), cpus_(cpus), follows_(follows), where_(where) {}

ReadAhead::~ReadAhead() {
    stop();
}

void ReadAhead::set_variable_source(nc::VariableSource* source) {
    // The reader reads the stream's source on its own thread.
    if (started_ && !ended_)
        throw std::logic_error("ReadAhead: the variable source set while the reader runs");
    source_ = source;
    // While the reader may run, its reads come to the caller through `requests_`.
    stream_.set_variable_source(source != nullptr && !ended_ ? &requests_ : source);
}

void ReadAhead::start() {
    started_ = true;
    reader_ = exec::quiet_thread("apci-reader", [this] { read_loop(); });
}

void ReadAhead::begin() {
    if (!started_ && !ended_) start();
}

// ---- the reader thread

ReadAhead::Batch* ReadAhead::open_batch() {
    if (filling_ != nullptr) return filling_;
    if (follows_ != nullptr && ++opened_ % kFollowEvery == 0) {
        const HelperCpu want = follow_backlog(follows_->backlog(), follows_->capacity(), placed_);
        if (want != placed_) {
            placed_ = want;
            if (cpus_ != nullptr) cpus_->place_helper(want);
        }
    }
    filling_ = ring_.acquire();  // nullptr: stopped
    if (filling_ != nullptr) {
        if (filling_->items.empty()) {
            // The slot's first time round: its items carved from the slab, on this thread
            // (made ready and written here, not on the caller's while it sets up the run).
            filling_->items =
                decltype(filling_->items)(decltype(filling_->items)::allocator_type(&slab_));
            filling_->items.resize(kBatchEvents);
        }
        filling_->size = 0;
        filling_->tail = Tail::kMore;
    }
    return filling_;
}

void ReadAhead::commit() {
    if (filling_ == nullptr) return;
    filling_ = nullptr;
    ring_.commit();
}

void ReadAhead::read_loop() noexcept {
    placed_ = where_;
    if (cpus_ != nullptr) cpus_->place_helper(where_);
    try {
        nc::Event ev;
        for (;;) {
            if (stopping_.load(std::memory_order_relaxed)) break;
            // A variable read inside next() hands over the batch being filled: the event goes
            // into the batch open after it.
            const Next n = stream_.next(ev);
            Batch* b = open_batch();
            if (b == nullptr || stopping_.load(std::memory_order_relaxed)) break;
            if (n == Next::kEvent) {
                Item& item = b->items[b->size++];
                item.event = ev;
                item.blocks = stream_.blocks_read();
                item.offset = stream_.offset();
                item.dialect = stream_.dialect();
                if (b->size == kBatchEvents) commit();
                continue;
            }
            b->tail = n == Next::kEnd ? Tail::kEnd : Tail::kError;
            commit();
            break;
        }
    } catch (...) {
        failure_ = std::current_exception();
        commit();  // the events before it; then the ring ends without an end: next() rethrows
    }
    ring_.close();
}

bool ReadAhead::Requests::read(const nc::VariableRef& v, double& out, std::string& why) {
    ReadAhead& o = owner_;
    Batch* b = withdrawn_ ? nullptr : o.open_batch();
    if (b == nullptr) {
        withdrawn_ = true;
        return false;
    }
    b->tail = Tail::kRequest;
    b->request = v;
    o.commit();
    o.ring_.flush();  // the caller may sleep until half the ring is ready: it must see this now
    std::unique_lock<std::mutex> lock(o.answer_mutex_);
    o.answered_cv_.wait(lock, [&] { return o.answered_ || o.stopping_.load(); });
    if (!o.answered_) {
        withdrawn_ = true;
        return false;
    }
    o.answered_ = false;
    out = o.answer_;
    why = o.answer_why_;
    return o.answer_ok_;
}

// ---- the caller's thread

Next ReadAhead::next(nc::Event& out) {
    const nc::Event* event = nullptr;
    const Next n = next(event);
    if (n == Next::kEvent && event != nullptr) out = *event;  // kEvent always sets it
    return n;
}

Next ReadAhead::next(const nc::Event*& out) {
    for (;;) {
        if (reading_ != nullptr) {
            if (pos_ < reading_->size) {
                const Item& item = reading_->items[pos_++];
                out = &item.event;
                blocks_ = item.blocks;
                offset_ = item.offset;
                dialect_ = item.dialect;
                return Next::kEvent;
            }
            const Tail tail = reading_->tail;
            const nc::VariableRef request = reading_->request;
            reading_ = nullptr;
            ring_.pop();
            if (tail == Tail::kRequest) {
                // Every event before the read was taken and executed: the board is as the
                // program expects to see it.
                serve(request);
            } else if (tail != Tail::kMore) {
                join();  // the reader ends after its last batch
                last_ = tail == Tail::kEnd ? Next::kEnd : Next::kError;
                return last_;
            }
        }
        if (ended_) return last_;
        if (!started_) start();
        reading_ = ring_.front();
        pos_ = 0;
        if (reading_ == nullptr) {  // the reader ended without an end: it failed
            join();
            if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
            return last_;
        }
    }
}

void ReadAhead::serve(const nc::VariableRef& v) {
    double value = 0.0;
    std::string why = "no variable source";
    bool ok = false;
    if (source_ != nullptr) {
        why.clear();
        ok = source_->read(v, value, why);
    }
    {
        const std::lock_guard<std::mutex> lock(answer_mutex_);
        answered_ = true;
        answer_ok_ = ok;
        answer_ = value;
        answer_why_ = std::move(why);
    }
    answered_cv_.notify_one();
}

void ReadAhead::join() noexcept {
    if (reader_.joinable()) reader_.join();
    ended_ = true;
}

void ReadAhead::stop() noexcept {
    if (ended_) return;
    if (started_) {
        {
            const std::lock_guard<std::mutex> lock(answer_mutex_);
            stopping_.store(true);
        }
        answered_cv_.notify_all();
        ring_.cancel();  // a reader waiting for room is released
    }
    join();
    reading_ = nullptr;
    last_ = Next::kEnd;
}

}  // namespace apci::run
