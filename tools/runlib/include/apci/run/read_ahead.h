// SPDX-License-Identifier: MIT
// The NC front end of `apcictl run` on a thread of its own: ReadAhead runs an nc::EventStream
// (parsing and interpreting the program) on a reader thread and hands its events in batches
// through a bounded ring (spsc_ring.h) to the executor on the caller's thread, each with what
// the executor reads of the stream at that event: the blocks read, the dialect, the bytes read.
// The executor reads it as it reads the stream itself (ProgramExecutor::set_read_ahead), and
// sees exactly what it would have seen:
//
//   - every event in order, each with the stream's counts as they were when it was handed out;
//   - the end, or the error of a line that does not parse, after every event before it;
//   - the board's variables (V.G., $SC_TOOL_TEMP_COMP; [ISG-OTC] section 2.8): the board is
//     not thread-safe and is touched on the caller's thread only. A variable read in the front
//     end hands over the events read before it and waits; next() answers it on the caller's
//     thread once every one of them was taken, that is executed (the executor asks for the
//     next event only when it is done with the last), exactly where the stream read it
//     without the read-ahead. A program that reads variables is read ahead up to its next read;
//   - bounded: kBatches batches of at most kBatchEvents events; the reader waits while all of
//     them are taken, so memory is flat in the program length;
//   - stop() (or the destructor, on any path out) stops the reader at its next event and joins
//     it; a variable read it waits on is withdrawn (nc::VariableSource::withdrawn: the stream
//     reads it with its own view, as when the caller took the source away at the stop). The
//     stream is then the caller's again, between two events, read ahead of the executor by at
//     most the ring's events and the block under way; a caller that reads on
//     (nc::SinglePass::finish) counts from the stream's start as before. After stop() next()
//     returns kEnd;
//   - no thread outlives it: the reader ends at the end, the error or stop(), and is joined;
//     it blocks the signals sent to the process, as the writer thread does (pipeline.h).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "apci/nc/program.h"
#include "apci/run/cpu_placement.h"
#include "apci/run/slab.h"
#include "apci/run/spsc_ring.h"

namespace apci::run {

class ReadAhead {
  public:
    static constexpr std::size_t kBatchEvents = 128;
    static constexpr std::size_t kBatches = 64;
    // The memory its ring holds: kBatches batches of kBatchEvents events, made once.
    static constexpr std::size_t ring_bytes() noexcept {
        return kBatches * (sizeof(Batch) + kBatchEvents * sizeof(Item));
    }

    // Batches the reader opens between two looks at the ring it follows.
    static constexpr std::size_t kFollowEvery = 8;

    // `stream` must outlive this; the reader thread starts with begin() or the first next(),
    // whichever comes first. With `cpus` (which must outlive this too), the reader runs where
    // it places helpers (cpu_placement.h), first on the CPU `where` says; with `follows` (which
    // must outlive this too) it moves, every kFollowEvery batches it opens, where
    // follow_backlog() says for that ring's fill.
    explicit ReadAhead(nc::EventStream& stream, const CpuPlacement* cpus = nullptr,
                       HelperCpu where = HelperCpu::kOther, const RingFill* follows = nullptr);
    ~ReadAhead();
    ReadAhead(const ReadAhead&) = delete;
    ReadAhead& operator=(const ReadAhead&) = delete;

    // Where the board's variables come from (as EventStream::set_variable_source), read on the
    // caller's thread. Before begin() and the first next(), or after the reader ended; while
    // the reader may run it throws std::logic_error (the reader reads the stream's source).
    void set_variable_source(nc::VariableSource* source);

    // Starts the reader now, so that it reads ahead while the caller sets up its run: after
    // set_variable_source(), if that is called at all. Idempotent; nothing once stopped.
    void begin();

    // As EventStream::next. Serves the variable reads of the front end that are due. Rethrows
    // an exception that ended the reader.
    nc::EventStream::Next next(nc::Event& out);
    // The same without a copy: `out` points at the event in the ring, valid until the next
    // call of next() or stop().
    nc::EventStream::Next next(const nc::Event*& out);
    // The stream's error, after next() returned kError.
    const nc::Diagnostic& error() const noexcept { return stream_.error(); }
    // The stream's counts when it handed out the last event next() returned.
    std::uint64_t blocks_read() const noexcept { return blocks_; }
    nc::Dialect dialect() const noexcept { return dialect_; }
    std::uint64_t offset() const noexcept { return offset_; }

    // Stops the reader and joins it (see above). Idempotent.
    void stop() noexcept;
    // Times a side slept on the ring, and the reader alone (for tests and measurements).
    std::uint64_t waits() const noexcept { return ring_.sleeps(); }
    std::uint64_t reader_waits() const noexcept { return ring_.producer_sleeps(); }
    // Blocks of memory the ring's items were carved from, once the reader ended (for tests:
    // one, however long the program).
    std::size_t item_blocks() const noexcept { return slab_.blocks(); }

  private:
    struct Item {
        nc::Event event;
        std::uint64_t blocks = 0;
        std::uint64_t offset = 0;
        nc::Dialect dialect = nc::Dialect::kUndecided;
    };
    // What follows a batch's events.
    enum class Tail : std::uint8_t { kMore, kRequest, kEnd, kError };
    struct Batch {
        // kBatchEvents, kept from batch to batch: carved from the read-ahead's slab by the
        // reader, the first time it fills the batch.
        std::vector<Item, detail::SlabAllocator<Item>> items;
        std::size_t size = 0;
        Tail tail = Tail::kMore;
        nc::VariableRef request;  // kRequest: the variable the front end waits for
    };
    // The front end's VariableSource, on the reader thread: hands the read to the caller.
    class Requests final : public nc::VariableSource {
      public:
        explicit Requests(ReadAhead& owner) : owner_(owner) {}
        bool read(const nc::VariableRef& v, double& out, std::string& why) override;
        bool withdrawn() const noexcept override { return withdrawn_; }

      private:
        ReadAhead& owner_;
        bool withdrawn_ = false;  // the reader thread's own
    };

    void start();
    void read_loop() noexcept;
    Batch* open_batch();                   // reader: the batch being filled, nullptr once stopped
    void commit();                         // reader
    void serve(const nc::VariableRef& v);  // caller: a variable read, answered
    void join() noexcept;

    // (In the order that packs them.)
    // The batches' items (slab.h): before the ring, which goes first; then what fills the
    // line up to the ring.
    detail::Slab slab_;
    nc::EventStream& stream_;
    const CpuPlacement* cpus_;
    const RingFill* follows_;
    std::size_t opened_ = 0;  // the reader's: batches it opened
    // 64 batches (8,192 events, 4 to 6 ms of the executor's work): the reader shares the CPUs
    // with the check and the writers, and a reader woken for room may wait a few milliseconds
    // for its turn; with 16 batches the executor ran dry 2 to 23 times a run on the CAM program
    // (up to 17 ms in all), now 1 to 4 (docs/performance.md, "A deeper read-ahead"). The reader,
    // asleep on a full ring, is woken for 16 free batches (6,144 events still ahead of the
    // executor); the executor, asleep on an empty one (at the start), for the first batch.
    SpscRing<Batch> ring_{kBatches, 16, 1};
    nc::VariableSource* source_ = nullptr;  // the caller's
    Batch* filling_ = nullptr;              // the reader's
    Batch* reading_ = nullptr;              // the caller's
    std::size_t pos_ = 0;
    std::uint64_t blocks_ = 0;
    std::uint64_t offset_ = 0;
    std::thread reader_;
    std::exception_ptr failure_;  // written by the reader before it ends
    // A variable read handed to the caller, and its answer.
    double answer_ = 0.0;
    Requests requests_{*this};
    std::string answer_why_;
    std::mutex answer_mutex_;
    std::condition_variable answered_cv_;
    nc::EventStream::Next last_ = nc::EventStream::Next::kEnd;
    HelperCpu where_;
    HelperCpu placed_ = HelperCpu::kOther;  // the reader's: where it runs now
    bool started_ = false;
    bool ended_ = false;  // the reader ended and was joined: next() returns `last_`
    nc::Dialect dialect_ = nc::Dialect::kUndecided;
    bool answered_ = false;
    bool answer_ok_ = false;
    std::atomic<bool> stopping_{false};
};

}  // namespace apci::run
