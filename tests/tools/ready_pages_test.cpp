// SPDX-License-Identifier: MIT
// Memory made ready before it is written (tools/runlib/src/ready_pages.h) and its users: the
// held calls' chunks, the hold's zones, the output pipeline's batches, the read-ahead's ring.
// Which pages are present is read with mincore(2); the page faults a thread took with
// getrusage(RUSAGE_THREAD) (pages a populating madvise brings in are not counted as faults).
#include "ready_pages.h"

#include <gtest/gtest.h>
#include <linux/perf_event.h>
#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "apci/nc/program.h"
#include "apci/run/pipeline.h"
#include "apci/run/read_ahead.h"
#include "apci/run/slab.h"
#include "apci/run/spsc_ring.h"
#include "chunked_array.h"
#include "held_calls.h"

namespace {

using apci::run::detail::make_ready;
using apci::run::detail::ReadyAhead;

std::size_t page_size() {
    return static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

// Anonymous memory nothing has touched yet (the run library's own mapping, map_block()),
// unmapped at the end.
struct Untouched {
    explicit Untouched(std::size_t pages)
        : bytes(pages * page_size()),
          block(apci::run::detail::map_block(bytes)),
          base(block.get()) {}
    // Which of its pages are present, one character each: '1' present, '.' not.
    std::string present() const {
        std::vector<unsigned char> v(bytes / page_size());
        if (::mincore(base, bytes, v.data()) != 0) return "mincore failed";
        std::string s;
        for (unsigned char c : v) s += (c & 1) != 0 ? '1' : '.';
        return s;
    }
    std::size_t bytes;
    apci::run::detail::MappedBlock block;
    std::byte* base;
};

// Whether this kernel populates on request (MADV_POPULATE_WRITE, Linux 5.14): where it does not,
// make_ready() does nothing by design and the pages fault in as they are written.
// Asked of the kernel itself, not through make_ready(), which it is to test.
bool kernel_populates() {
#ifdef MADV_POPULATE_WRITE
    Untouched probe(1);
    return probe.base != nullptr && ::madvise(probe.base, page_size(), MADV_POPULATE_WRITE) == 0 &&
           probe.present() == "1";
#else
    return false;
#endif
}

#define REQUIRE_POPULATE()                                                                \
    do {                                                                                  \
        if (!kernel_populates()) GTEST_SKIP() << "no MADV_POPULATE_WRITE on this kernel"; \
    } while (0)

// The page faults the calling thread takes while it lives, as perf counts them: the pages a
// populating madvise brings in are not among them (getrusage's counts include them).
class ThreadFaults {
  public:
    // with_new_threads: the threads this thread makes from now on are counted too, each once it
    // has ended (joined).
    explicit ThreadFaults(bool with_new_threads = false) {
        perf_event_attr attr{};
        attr.size = sizeof attr;
        attr.type = PERF_TYPE_SOFTWARE;
        attr.config = PERF_COUNT_SW_PAGE_FAULTS;
        attr.exclude_hv = 1;
        attr.inherit = with_new_threads ? 1 : 0;
        fd_ = static_cast<int>(::syscall(SYS_perf_event_open, &attr, 0, -1, -1, 0));
    }
    ~ThreadFaults() {
        if (fd_ >= 0) ::close(fd_);
    }
    ThreadFaults(const ThreadFaults&) = delete;
    ThreadFaults& operator=(const ThreadFaults&) = delete;
    bool counting() const noexcept { return fd_ >= 0; }
    long now() const {
        std::uint64_t n = 0;
        return ::read(fd_, &n, sizeof n) == static_cast<ssize_t>(sizeof n) ? static_cast<long>(n)
                                                                           : -1;
    }

  private:
    int fd_ = -1;
};

#define REQUIRE_COUNTING(faults)                                                       \
    do {                                                                               \
        if (!(faults).counting())                                                      \
            GTEST_SKIP() << "perf_event_open: " << std::strerror(errno)                \
                         << " (page faults are counted with perf's software counter)"; \
    } while (0)

// Page faults are a release build's figure: a sanitizer's shadow memory faults beside every
// page the program writes.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SKIP_UNDER_SANITIZER() GTEST_SKIP() << "page faults are counted without sanitizers"
#else
#define SKIP_UNDER_SANITIZER() (void)0
#endif
// The address space is a release build's figure too: a sanitizer's runtime maps memory of its
// own as the test runs (its allocator's regions, its shadow).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SKIP_ADDRESS_SPACE_UNDER_SANITIZER() \
    GTEST_SKIP() << "the address space is measured without sanitizers"
#else
#define SKIP_ADDRESS_SPACE_UNDER_SANITIZER() (void)0
#endif

// First in the file: run as one program (not one test per process, as ctest runs them), the
// tests after it free memory the C library keeps, present, for the ring to be made in.
// The caller makes none of the ring (it sets up its run meanwhile): the reader makes each batch's
// items the first time it fills the batch, carved from pages made ready. Counted over the caller
// and the reader (a counter the reader's thread inherits) while a program fills every batch.
TEST(ReadAheadReady, TheReaderMakesTheRingWithFewPageFaults) {
    REQUIRE_POPULATE();
    SKIP_UNDER_SANITIZER();
    using apci::run::ReadAhead;
    constexpr std::size_t kLines = ReadAhead::kBatches * ReadAhead::kBatchEvents + 100;
    std::string text = "G1 F600\n";
    for (std::size_t i = 0; i < kLines; ++i) text += "G1 X" + std::to_string(i % 97) + "\n";
    text += "M2\n";
    apci::nc::EventStream stream = apci::nc::EventStream::from_text(text, "ready.nc");
    const ThreadFaults counter(/*with_new_threads=*/true);
    REQUIRE_COUNTING(counter);
    const long before = counter.now();
    std::size_t events = 0;
    {
        ReadAhead ahead(stream);
        EXPECT_LT(counter.now() - before, 8);  // the constructor makes no batch
        const apci::nc::Event* e = nullptr;
        apci::nc::EventStream::Next n;
        while ((n = ahead.next(e)) == apci::nc::EventStream::Next::kEvent) ++events;
        EXPECT_EQ(n, apci::nc::EventStream::Next::kEnd) << ahead.error().message;
    }  // the reader ended at the end, and was joined
    EXPECT_GE(events, kLines);
    const long faults = counter.now() - before;
    const auto pages = static_cast<long>(ReadAhead::ring_bytes() / page_size());
    // The slab's block is made ready as carved (slab.h): on a huge page a few faults in all
    // (7 or 8, the reader's stack and heap among them); on pages of 4 KiB each batch's items
    // take a fault or two where their array starts and ends within a page. Faulted one page at
    // a time: every page.
    EXPECT_LT(faults, pages / 4) << pages << " pages in the ring";
}

TEST(MakeReady, MakesTheWholePagesOfTheRangePresentAndNoOther) {
    REQUIRE_POPULATE();
    const std::size_t page = page_size();
    Untouched m(8);
    ASSERT_NE(m.base, nullptr);
    ASSERT_EQ(m.present(), "........");
    // From 100 bytes into page 0 to 100 bytes into page 5: pages 1 to 4 are whole in it.
    make_ready(m.base + 100, 5 * page);
    EXPECT_EQ(m.present(), ".1111...");
}

TEST(MakeReady, ARangeOnPageBoundariesTakesItsFirstAndLastPage) {
    REQUIRE_POPULATE();
    const std::size_t page = page_size();
    Untouched m(6);
    ASSERT_NE(m.base, nullptr);
    make_ready(m.base + page, 3 * page);
    EXPECT_EQ(m.present(), ".111..");
    // One byte less: the last page is no longer whole.
    Untouched n(6);
    make_ready(n.base + page, 3 * page - 1);
    EXPECT_EQ(n.present(), ".11...");
}

TEST(MakeReady, ARangeWithinOnePageOrEmptyMakesNothingReady) {
    REQUIRE_POPULATE();
    const std::size_t page = page_size();
    Untouched m(3);
    ASSERT_NE(m.base, nullptr);
    make_ready(m.base + 1, page);  // ends one byte into page 1: no page whole
    make_ready(m.base + page, 0);
    make_ready(nullptr, page);
    EXPECT_EQ(m.present(), "...");
}

TEST(MakeReady, ARangeOfOneWholePageMakesThatPageReady) {
    REQUIRE_POPULATE();
    const std::size_t page = page_size();
    Untouched m(3);
    ASSERT_NE(m.base, nullptr);
    make_ready(m.base + page, page);
    EXPECT_EQ(m.present(), ".1.");
}

TEST(MakeReady, PagesMadeReadyAreWrittenWithoutAFault) {
    REQUIRE_POPULATE();
    SKIP_UNDER_SANITIZER();
    const ThreadFaults counter;
    REQUIRE_COUNTING(counter);
    const std::size_t page = page_size();
    Untouched m(32);
    ASSERT_NE(m.base, nullptr);
    make_ready(m.base, m.bytes);
    const long before = counter.now();
    for (std::size_t i = 0; i < m.bytes; i += page) m.base[i] = std::byte{1};
    // Present for reading only (the zero page, as a read would map it), each write would
    // fault: made ready means writable.
    EXPECT_EQ(counter.now() - before, 0);
}

TEST(MakeReady, WhatIsWrittenStaysAsItIs) {
    const std::size_t page = page_size();
    Untouched m(4);
    ASSERT_NE(m.base, nullptr);
    for (std::size_t i = 0; i < m.bytes; i += 97) m.base[i] = std::byte(i % 251);
    make_ready(m.base, m.bytes);
    for (std::size_t i = 0; i < m.bytes; i += 97) ASSERT_EQ(m.base[i], std::byte(i % 251)) << i;
    (void)page;
}

TEST(ReadyAhead, MakesReadyAStepAheadOfTheWriterAndNoMore) {
    REQUIRE_POPULATE();
    const std::size_t page = page_size();
    const std::size_t step_pages = ReadyAhead::kStep / page;
    Untouched m(3 * step_pages);
    ASSERT_NE(m.base, nullptr);
    ReadyAhead ahead;
    // The first write: its bytes and a step beyond them (the page partly covered stays).
    ahead.before_write(m.base, 0, 100, m.bytes);
    const std::string first = std::string(step_pages, '1') + std::string(2 * step_pages, '.');
    EXPECT_EQ(m.present(), first);
    // Writes within what is ready make nothing more ready.
    ahead.before_write(m.base, ReadyAhead::kStep - 200, 100, m.bytes);
    EXPECT_EQ(m.present(), first);
    // A write that ends where the ready bytes end asks for nothing more.
    ahead.before_write(m.base, ReadyAhead::kStep, 100, m.bytes);
    EXPECT_EQ(m.present(), first);
    // One byte past them: the next step, from the page where the last one ended (the page it
    // only partly covered is made ready now).
    ahead.before_write(m.base, ReadyAhead::kStep, 101, m.bytes);
    EXPECT_EQ(m.present(), std::string(2 * step_pages, '1') + std::string(step_pages, '.'));
}

TEST(ReadyAhead, StopsAtTheBlocksEnd) {
    REQUIRE_POPULATE();
    const std::size_t page = page_size();
    Untouched m(8);
    ASSERT_NE(m.base, nullptr);
    ReadyAhead ahead;
    // A block of 3 pages in a mapping of 8: nothing beyond its end is made ready.
    ahead.before_write(m.base, 0, 10, 3 * page);
    EXPECT_EQ(m.present(), "111.....");
    ahead.before_write(m.base, 3 * page - 10, 10, 3 * page);
    EXPECT_EQ(m.present(), "111.....");
}

// A segment whose numbers the held calls cannot leave out (random ends and centre).
apci::run::PathSegment random_arc(std::mt19937_64& rng, std::int64_t n) {
    std::uniform_real_distribution<double> d(-100.0, 100.0);
    apci::run::PathSegment s;
    s.block = apci::run::BlockRef{n * 7, static_cast<std::uint64_t>(n * 3)};
    s.kind = apci::run::SegmentKind::kArc;
    s.role = apci::run::Role::kContour;
    s.start = apci::run::Point(d(rng), d(rng), d(rng));
    s.end = apci::run::Point(d(rng), d(rng), d(rng));
    s.center = apci::run::Point(d(rng), d(rng), d(rng));
    s.sweep = d(rng);
    return s;
}

std::vector<apci::run::PathSegment> random_arcs(std::uint64_t seed, int n) {
    std::mt19937_64 rng(seed);
    std::vector<apci::run::PathSegment> segments;
    for (int i = 0; i < n; ++i) segments.push_back(random_arc(rng, i));
    return segments;
}

// The page faults the calling thread takes holding `segments` (executed) in `calls`.
long faults_holding(apci::run::detail::HeldCalls& calls,
                    const std::vector<apci::run::PathSegment>& segments,
                    const ThreadFaults& counter) {
    const long before = counter.now();
    for (const auto& s : segments) calls.segment(apci::run::detail::HeldCall::Kind::kExecuted, s);
    return counter.now() - before;
}

TEST(HeldCallsReady, WritingAChunkTakesFewPageFaults) {
    REQUIRE_POPULATE();
    SKIP_UNDER_SANITIZER();
    using apci::run::detail::HeldCall;
    apci::run::detail::HeldCalls calls;
    const auto segments = random_arcs(7, 16'000);
    const ThreadFaults counter;
    REQUIRE_COUNTING(counter);
    const long faults = faults_holding(calls, segments, counter);
    const auto pages = static_cast<long>(calls.bytes() / page_size());
    ASSERT_GT(pages, 256);  // more than a step, within one chunk
    ASSERT_LT(calls.bytes(), apci::run::detail::HeldCalls::kChunkBytes);
    EXPECT_LT(faults, pages / 8) << pages << " pages written";
    std::size_t n = 0;
    calls.for_each([&](const HeldCall& c) {
        ASSERT_LT(n, segments.size());
        EXPECT_EQ(c.segment.end, segments[n].end);
        ++n;
    });
    EXPECT_EQ(n, segments.size());
}

TEST(HeldCallsReady, EveryChunkIsMadeReadyAsItFills) {
    REQUIRE_POPULATE();
    SKIP_UNDER_SANITIZER();
    // Chunks of 512 KiB: 16,000 arcs fill three of them.
    apci::run::detail::HeldCalls calls(std::size_t{512} << 10);
    const auto segments = random_arcs(5, 16'000);
    const ThreadFaults counter;
    REQUIRE_COUNTING(counter);
    const long faults = faults_holding(calls, segments, counter);
    const auto pages = static_cast<long>(calls.bytes() / page_size());
    ASSERT_GT(calls.bytes(), std::size_t{2} * (std::size_t{512} << 10));
    EXPECT_LT(faults, pages / 8) << pages << " pages written";
    // Emptied, the chunks are written again: their pages are there already.
    calls.clear();
    EXPECT_LT(faults_holding(calls, segments, counter), pages / 8);
}

// The process's mapped memory (VmSize), in KiB.
long mapped_kib() {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (f == nullptr) return -1;
    char line[256];
    long kib = -1;
    while (std::fgets(line, sizeof line, f) != nullptr)
        if (std::sscanf(line, "VmSize: %ld kB", &kib) == 1) break;
    std::fclose(f);
    return kib;
}

TEST(HeldCallsReady, AChunksMappingGoesWithIt) {
    using apci::run::detail::HeldCall;
    std::mt19937_64 rng(3);
    const apci::run::PathSegment s = random_arc(rng, 1);
    {  // the C library's and the test's own first allocations, before the count
        apci::run::detail::HeldCalls calls;
        calls.segment(HeldCall::Kind::kExecuted, s);
    }
    const long before = mapped_kib();
    ASSERT_GT(before, 0);
    for (int i = 0; i < 64; ++i) {  // 64 chunks of 2 MiB, one after the other
        apci::run::detail::HeldCalls calls;
        calls.segment(HeldCall::Kind::kExecuted, s);
    }
    EXPECT_LT(mapped_kib() - before, 16 * 1024) << "KiB still mapped after 64 holds ended";
}

// Where no chunk can be had (the address space limited, in a child process), the call that
// needed one throws std::bad_alloc and changes nothing: the calls written before read back,
// and the holder takes calls again once memory is there. Both ways of getting chunks: mapped
// on their own, and carved from a slab.
TEST(HeldCallsReady, NoChunkToBeHadChangesNothing) {
    SKIP_UNDER_SANITIZER();
    using apci::run::detail::HeldCall;
    using apci::run::detail::HeldCalls;
    for (const bool carved : {false, true}) {
        SCOPED_TRACE(carved);
        std::mt19937_64 rng(17);
        std::vector<apci::run::PathSegment> segments;
        for (int i = 0; i < 400'000; ++i) segments.push_back(random_arc(rng, i));
        std::fflush(nullptr);
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            apci::run::detail::Slab memory;
            HeldCalls calls = carved ? HeldCalls(memory) : HeldCalls();
            // The soft limit only: the hard one, lowered, could not be raised again.
            const long kib = mapped_kib();
            rlimit was{};
            if (kib <= 0 || ::getrlimit(RLIMIT_AS, &was) != 0) ::_exit(3);
            const rlimit limit{static_cast<rlim_t>(kib + 12 * 1024) * 1024, was.rlim_max};
            if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(3);
            std::size_t written = 0;
            bool refused = false;
            for (; written < segments.size(); ++written) {
                try {
                    calls.segment(HeldCall::Kind::kExecuted, segments[written]);
                } catch (const std::bad_alloc&) {
                    refused = true;
                    break;
                }
            }
            if (!refused) ::_exit(4);  // the limit was never reached: nothing shown
            if (calls.size() != written) ::_exit(5);
            std::size_t n = 0;
            bool same = true;
            calls.for_each([&](const HeldCall& c) {
                same = same && n < written && c.segment.end == segments[n].end;
                ++n;
            });
            if (!same || n != written) ::_exit(6);
            if (::setrlimit(RLIMIT_AS, &was) != 0) ::_exit(3);
            calls.segment(HeldCall::Kind::kExecuted, segments[written]);
            n = 0;
            calls.for_each([&](const HeldCall& c) {
                same = same && c.segment.end == segments[n].end;
                ++n;
            });
            ::_exit(same && n == written + 1 ? 0 : 7);
        }
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ASSERT_TRUE(WIFEXITED(status)) << status;
        EXPECT_EQ(WEXITSTATUS(status), 0);
    }
}

TEST(HeldCallsReady, AChunkUsedInPartIsMadeReadyAStepAheadOnly) {
    REQUIRE_POPULATE();
    SKIP_UNDER_SANITIZER();
    // A short program's hold: its chunk's first step is ready, not the whole chunk. Read from
    // the process's resident memory: a chunk made ready whole would add 2 MiB. The chunks are
    // a page short of a huge page: of ordinary pages (a chunk of a huge page's size is
    // advised to be one, which the kernel then makes ready whole: MapBlock's tests).
    using apci::run::detail::HeldCall;
    using apci::run::detail::HeldCalls;
    auto resident = [] {
        rusage u{};
        ::getrusage(RUSAGE_SELF, &u);
        return u.ru_maxrss;  // KiB, the peak: grows by what becomes resident
    };
    std::mt19937_64 rng(11);
    const long before = resident();
    std::vector<HeldCalls> holds;
    for (int i = 0; i < 8; ++i) holds.emplace_back(HeldCalls::kChunkBytes - page_size());
    for (auto& calls : holds)
        for (int i = 0; i < 10; ++i) calls.segment(HeldCall::Kind::kExecuted, random_arc(rng, i));
    const long grown = resident() - before;
    // Eight holds of a step (256 KiB) each: 2 MiB, against 16 MiB were each chunk made whole.
    EXPECT_LT(grown, 4 * 1024) << grown << " KiB";
}

TEST(ChunkedArrayReady, KeepingItemsTakesFewPageFaults) {
    REQUIRE_POPULATE();
    SKIP_UNDER_SANITIZER();
    struct Item {
        double v[8];
    };
    apci::run::detail::ChunkedArray<Item> items;
    const ThreadFaults counter;
    REQUIRE_COUNTING(counter);
    const long before = counter.now();
    constexpr int kItems = 16'000;  // 1 MiB
    for (int i = 0; i < kItems; ++i) items.emplace_back().v[0] = i;
    const long faults = counter.now() - before;
    const auto pages = static_cast<long>(kItems * sizeof(Item) / page_size());
    EXPECT_LT(faults, pages / 8) << pages << " pages written";
    for (int i = 0; i < kItems; i += 999) EXPECT_EQ(items[i].v[0], i);
}

TEST(ChunkedArrayReady, EachChunkIsMadeReadyAStepAheadOfItsItems) {
    REQUIRE_POPULATE();
    struct Item {
        double v[8];
    };
    // Chunks of ordinary pages (64 KiB short of a huge page; see HeldCallsReady above).
    using Array = apci::run::detail::ChunkedArray<Item, apci::run::detail::kHugePage -
                                                            (std::size_t{64} << 10)>;
    const std::size_t page = page_size();
    Array items;
    // The first chunk full, one item in the second.
    for (std::size_t i = 0; i <= Array::kPerChunk; ++i) items.emplace_back().v[0] = 1.0;
    auto* second = reinterpret_cast<std::byte*>(&items[Array::kPerChunk]);
    const std::size_t chunk = Array::kPerChunk * sizeof(Item);
    // From the second chunk's first whole page to its end, one character a page.
    const auto skip = (page - reinterpret_cast<std::uintptr_t>(second) % page) % page;
    std::byte* first_page = second + skip;
    const std::size_t pages = (chunk - skip) / page;
    std::vector<unsigned char> v(pages);
    ASSERT_EQ(::mincore(first_page, pages * page, v.data()), 0) << std::strerror(errno);
    std::string present;
    for (unsigned char c : v) present += (c & 1) != 0 ? '1' : '.';
    // Its first step ready (the page the step ends in partly, so one less), nothing after it.
    const std::size_t step_pages = ReadyAhead::kStep / page;
    EXPECT_EQ(present.substr(0, step_pages - 1), std::string(step_pages - 1, '1'));
    EXPECT_EQ(present.substr(step_pages + 1), std::string(pages - step_pages - 1, '.'));
}

// An inner sink that takes everything and does nothing with it.
class Nothing final : public apci::run::RunSink {
  public:
    void executed(const apci::run::PathSegment&) override {}
};

// A pipeline into Nothing, and a line segment to give it.
struct LinePipeline {
    Nothing inner;
    apci::run::PipelinedSink pipe{inner};
    apci::run::PathSegment s = [] {
        apci::run::PathSegment line;
        line.kind = apci::run::SegmentKind::kLine;
        return line;
    }();
};

TEST(PipelineReady, FillingEveryBatchOnceTakesFewPageFaults) {
    REQUIRE_POPULATE();
    SKIP_UNDER_SANITIZER();
    using apci::run::PipelinedSink;
    LinePipeline p;
    PipelinedSink& pipe = p.pipe;
    apci::run::PathSegment& s = p.s;
    pipe.executed(s);  // the writer thread started: its start is not the batches'
    const ThreadFaults counter;
    REQUIRE_COUNTING(counter);
    const long before = counter.now();
    const std::size_t events = PipelinedSink::kBatches * PipelinedSink::kBatchEvents;
    for (std::size_t i = 0; i < events; ++i) {
        s.end.x() = static_cast<double>(i);
        pipe.executed(s);
    }
    const long faults = counter.now() - before;
    pipe.finish();
    const auto pages = static_cast<long>(events * sizeof(apci::run::PathSegment) / page_size());
    EXPECT_LT(faults, pages / 8) << pages << " pages of segments";
}

// ---- Huge pages: map_block's blocks of a whole number of them, the slab carved from them.

using apci::run::detail::kHugePage;
using apci::run::detail::map_block;
using apci::run::detail::Slab;
using apci::run::detail::SlabAllocator;

// The mapping (/proc/self/smaps) that holds p: its range and its flags as listed after
// "VmFlags:" ("hg": advised to be backed by huge pages, MADV_HUGEPAGE).
struct Mapping {
    std::uintptr_t lo = 0, hi = 0;
    std::string flags;
    bool advised_huge() const { return (flags + " ").find(" hg ") != std::string::npos; }
};
Mapping mapping_of(const void* p) {
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    Mapping m;
    bool in = false;
    while (std::getline(smaps, line)) {
        unsigned long lo = 0, hi = 0;
        if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2) {
            in = lo <= at && at < hi;
            if (in) m.lo = lo, m.hi = hi;
        } else if (in && line.rfind("VmFlags:", 0) == 0) {
            m.flags = line.substr(8);
            return m;
        }
    }
    return m;
}

// The process's address space in KiB (VmSize, /proc/self/status).
long address_space_kib() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmSize:", 0) == 0) return std::stol(line.substr(7));
    return -1;
}

// Aligned, so that a system whose policy backs all anonymous memory with huge pages backs the
// block whole; not advised (docs/performance.md, "Ordinary pages again").
TEST(MapBlock, AWholeNumberOfHugePagesIsAlignedToOneAndNotAdvisedHuge) {
    for (const std::size_t pages : {1u, 2u, 3u}) {
        SCOPED_TRACE(pages);
        const std::size_t bytes = pages * kHugePage;
        const auto block = map_block(bytes);
        const auto at = reinterpret_cast<std::uintptr_t>(block.get());
        EXPECT_EQ(at % kHugePage, 0u);
        const Mapping m = mapping_of(block.get());
        EXPECT_FALSE(m.advised_huge()) << m.flags;
        EXPECT_LE(m.lo, at);
        EXPECT_GE(m.hi, at + bytes);
        // Written through to its last byte.
        block[bytes - 1] = std::byte{7};
        EXPECT_EQ(block[bytes - 1], std::byte{7});
    }
}

TEST(MapBlock, OtherSizesAreOrdinaryPages) {
    for (const std::size_t bytes :
         {kHugePage - page_size(), kHugePage + page_size(), page_size()}) {
        SCOPED_TRACE(bytes);
        const auto block = map_block(bytes);
        const Mapping m = mapping_of(block.get());
        EXPECT_FALSE(m.flags.empty()) << "no mapping holds the block";
        EXPECT_FALSE(m.advised_huge()) << m.flags;
    }
}

// A block takes its own size of the address space (of a huge block, the huge page's more that
// aligns it is given back), and all of it goes with it.
TEST(MapBlock, ABlockTakesItsOwnSizeOfTheAddressSpaceAndGivesItBack) {
    SKIP_ADDRESS_SPACE_UNDER_SANITIZER();
    for (const std::size_t bytes : {3 * page_size(), 2 * kHugePage}) {
        SCOPED_TRACE(bytes);
        const long before = address_space_kib();
        ASSERT_GT(before, 0);
        {
            const auto block = map_block(bytes);
            EXPECT_EQ(address_space_kib() - before, static_cast<long>(bytes / 1024));
        }
        EXPECT_EQ(address_space_kib(), before);
    }
}

TEST(Slab, CarvesAlignedPiecesInOrderFromOneBlock) {
    Slab slab;
    EXPECT_EQ(slab.blocks(), 0u);
    auto* a = static_cast<std::byte*>(slab.take(1));
    auto* b = static_cast<std::byte*>(slab.take(100));
    auto* c = static_cast<std::byte*>(slab.take(Slab::kAlign));
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a) % kHugePage, 0u);  // a block's start
    EXPECT_EQ(b, a + Slab::kAlign);                                  // 1 byte rounded up to a line
    EXPECT_EQ(c, b + 2 * Slab::kAlign);                              // 100 bytes to two
    EXPECT_EQ(slab.blocks(), 1u);
    for (auto* p : {a, b, c}) EXPECT_TRUE(slab.holds(p));
}

TEST(Slab, NothingOrTooMuchIsNotCarved) {
    Slab slab;
    EXPECT_EQ(slab.take(0), nullptr);
    EXPECT_EQ(slab.take(Slab::kMostTaken + 1), nullptr);
    EXPECT_EQ(slab.blocks(), 0u);
    EXPECT_NE(slab.take(Slab::kMostTaken), nullptr);
    EXPECT_EQ(slab.blocks(), 1u);
}

TEST(Slab, CarvedIsTheSizeRoundedUpToALine) {
    static_assert(Slab::carved(0) == 0);
    static_assert(Slab::carved(1) == Slab::kAlign);
    static_assert(Slab::carved(Slab::kAlign) == Slab::kAlign);
    static_assert(Slab::carved(Slab::kAlign + 1) == 2 * Slab::kAlign);
    // What take() carves: the next piece starts carved(bytes) on.
    Slab slab;
    auto* a = static_cast<std::byte*>(slab.take(Slab::kAlign + 1));
    auto* b = static_cast<std::byte*>(slab.take(1));
    EXPECT_EQ(b, a + Slab::carved(Slab::kAlign + 1));
}

TEST(Chunks, CarvedFromASlabInOrderAndNoneTooLarge) {
    using apci::run::detail::Chunks;
    Slab slab;
    Chunks chunks(slab);
    EXPECT_TRUE(chunks.carved());
    std::byte* const first = chunks.add(Slab::kMostTaken);
    std::byte* const second = chunks.add(Slab::kAlign);
    EXPECT_EQ(chunks.size(), 2u);
    EXPECT_EQ(chunks[0], first);
    EXPECT_EQ(chunks.back(), second);
    EXPECT_EQ(second, first + Slab::kMostTaken);
    EXPECT_TRUE(slab.holds(first) && slab.holds(second));
    // More than a slab carves: std::bad_alloc, and nothing changes.
    EXPECT_THROW(chunks.add(Slab::kMostTaken + 1), std::bad_alloc);
    EXPECT_EQ(chunks.size(), 2u);
    EXPECT_EQ(chunks.back(), second);
    EXPECT_EQ(slab.blocks(), 1u);
}

TEST(Chunks, MappedOnTheirOwnAndSwappedWithTheirMappings) {
    using apci::run::detail::Chunks;
    Slab slab;
    Chunks carved(slab);
    carved.add(Slab::kAlign);
    {
        Chunks mapped;
        EXPECT_FALSE(mapped.carved());
        std::byte* const a = mapped.add(kHugePage);
        std::byte* const b = mapped.add(kHugePage);
        EXPECT_NE(a, b);
        EXPECT_FALSE(slab.holds(a) || slab.holds(b));
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a) % kHugePage, 0u);
        a[0] = std::byte{1};
        b[kHugePage - 1] = std::byte{2};
        mapped.swap(carved);
        EXPECT_TRUE(mapped.carved());
        EXPECT_FALSE(carved.carved());
        ASSERT_EQ(carved.size(), 2u);
        EXPECT_EQ(carved[0], a);
        EXPECT_EQ(carved.back(), b);
        EXPECT_EQ(mapped.size(), 1u);
    }  // the swapped-out holder ends: the mappings stay with `carved`
    EXPECT_EQ(carved[0][0], std::byte{1});
    EXPECT_EQ(carved[1][kHugePage - 1], std::byte{2});
    carved[1][0] = std::byte{3};
    EXPECT_EQ(carved[1][0], std::byte{3});
    std::byte* const c = carved.add(kHugePage);  // mapped too, after the swap
    EXPECT_EQ(carved.back(), c);
    EXPECT_EQ(carved.size(), 3u);
    EXPECT_FALSE(slab.holds(c));
}

TEST(Slab, ABlockFilledExactlyThenTheNextPieceStartsANewOne) {
    Slab slab;
    auto* first = static_cast<std::byte*>(slab.take(Slab::kMostTaken));
    slab.take(Slab::kMostTaken);
    slab.take(Slab::kMostTaken);
    auto* last = static_cast<std::byte*>(slab.take(Slab::kMostTaken - Slab::kAlign));
    auto* line = static_cast<std::byte*>(slab.take(Slab::kAlign));
    EXPECT_EQ(slab.blocks(), 1u) << "the block's last line is carved from it";
    EXPECT_EQ(last, first + 3 * Slab::kMostTaken);
    EXPECT_EQ(line, first + Slab::kBlockBytes - Slab::kAlign);
    auto* next = static_cast<std::byte*>(slab.take(1));
    EXPECT_EQ(slab.blocks(), 2u);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(next) % kHugePage, 0u);
    // Its blocks and nothing else.
    EXPECT_TRUE(slab.holds(first + Slab::kBlockBytes - 1));
    EXPECT_TRUE(slab.holds(next + Slab::kBlockBytes - 1));
    int elsewhere = 0;
    EXPECT_FALSE(slab.holds(&elsewhere));
    const auto heap = std::make_unique<int>(1);
    EXPECT_FALSE(slab.holds(heap.get()));
    // Just outside each block (where the other block is not mapped right there).
    if (next != first + Slab::kBlockBytes) {
        EXPECT_FALSE(slab.holds(first + Slab::kBlockBytes));
    }
    if (first != next + Slab::kBlockBytes) {
        EXPECT_FALSE(slab.holds(next + Slab::kBlockBytes));
        EXPECT_FALSE(slab.holds(first - 1));
    }
}

TEST(Slab, WhatItCarvesIsMadeReady) {
    REQUIRE_POPULATE();
    Slab slab;
    const std::size_t page = page_size();
    auto* p = static_cast<std::byte*>(slab.take(8 * page));
    std::vector<unsigned char> v(8);
    ASSERT_EQ(::mincore(p, 8 * page, v.data()), 0) << std::strerror(errno);
    for (std::size_t i = 0; i < v.size(); ++i) EXPECT_EQ(v[i] & 1, 1) << "page " << i;
}

TEST(SlabAllocator, AVectorsArrayIsCarvedFromTheSlabUpToTheMostItTakes) {
    Slab slab;
    using Alloc = SlabAllocator<double>;
    std::vector<double, Alloc> small{Alloc(&slab)};
    small.reserve(Slab::kMostTaken / sizeof(double));  // at the edge: carved
    EXPECT_TRUE(slab.holds(small.data()));
    std::vector<double, Alloc> large{Alloc(&slab)};
    large.reserve(Slab::kMostTaken / sizeof(double) + 1);  // one more: from the heap
    EXPECT_FALSE(slab.holds(large.data()));
    large.assign(Slab::kMostTaken / sizeof(double) + 1, 2.5);
    EXPECT_EQ(large.back(), 2.5);
    std::vector<double, Alloc> none;  // no slab: the heap
    none.reserve(16);
    EXPECT_FALSE(slab.holds(none.data()));
}

// An array of the slab given back is not handed to the heap (where it would be a bad free: an
// abort, or AddressSanitizer's report), nor carved again: it stays the slab's until it goes.
TEST(SlabAllocator, ArraysOfTheSlabAreNotFreedToTheHeapNorCarvedAgain) {
    Slab slab;
    using Alloc = SlabAllocator<int>;
    Alloc alloc(&slab);
    int* const first = alloc.allocate(1000);
    alloc.deallocate(first, 1000);
    int* const second = alloc.allocate(1000);
    EXPECT_TRUE(slab.holds(first));
    EXPECT_TRUE(slab.holds(second));
    EXPECT_NE(second, first);
    alloc.deallocate(second, 1000);
    {
        std::vector<int, Alloc> v{Alloc(&slab)};
        v.assign(1000, 42);
        v.assign(100000, 1);  // grown: the first array given back, the second from the slab
        EXPECT_TRUE(slab.holds(v.data()));
        EXPECT_EQ(v[99999], 1);
    }
    EXPECT_EQ(slab.blocks(), 1u);
}

TEST(SlabAllocator, AssignedOrSwappedTheAllocatorGoesWithTheArray) {
    Slab one, two;
    using Alloc = SlabAllocator<int>;
    EXPECT_TRUE(Alloc(&one) == Alloc(&one));
    EXPECT_FALSE(Alloc(&one) == Alloc(&two));
    EXPECT_TRUE(Alloc() == Alloc());
    std::vector<int, Alloc> v;
    v = std::vector<int, Alloc>(Alloc(&one));  // as a batch takes its slab's allocator
    EXPECT_EQ(v.get_allocator().slab(), &one);
    v.reserve(64);
    EXPECT_TRUE(one.holds(v.data()));
    std::vector<int, Alloc> w{Alloc(&two)};
    w.reserve(8);
    v.swap(w);
    EXPECT_EQ(v.get_allocator().slab(), &two);
    EXPECT_EQ(w.get_allocator().slab(), &one);
    EXPECT_TRUE(two.holds(v.data()));
    EXPECT_TRUE(one.holds(w.data()));
    const SlabAllocator<double> rebound(v.get_allocator());
    EXPECT_EQ(rebound.slab(), &two);
}

// The slab's blocks go with it: the address space it took is given back.
TEST(Slab, ItsBlocksAreUnmappedWhenItGoes) {
    SKIP_ADDRESS_SPACE_UNDER_SANITIZER();
    const long before = address_space_kib();
    ASSERT_GT(before, 0);
    {
        Slab slab;
        slab.take(Slab::kMostTaken);
        slab.take(Slab::kMostTaken);
        slab.take(Slab::kMostTaken);
        slab.take(Slab::kMostTaken);
        slab.take(1);  // a second block
        ASSERT_EQ(slab.blocks(), 2u);
        EXPECT_EQ(address_space_kib() - before, static_cast<long>(2 * Slab::kBlockBytes / 1024));
    }
    EXPECT_EQ(address_space_kib(), before);
}

// The C library's count of the bytes it has given out (its heap's and its own mappings').
std::size_t heap_in_use() {
    const struct mallinfo2 m = ::mallinfo2();
    return m.uordblks + m.hblkhd;
}

// An array the slab does not carve comes from the heap, and goes back to it.
TEST(SlabAllocator, AnArrayFromTheHeapGoesBackToIt) {
    SKIP_ADDRESS_SPACE_UNDER_SANITIZER();
    Slab slab;
    using Alloc = SlabAllocator<std::byte>;
    Alloc alloc(&slab);
    const std::size_t before = heap_in_use();
    for (int i = 0; i < 4; ++i) {
        std::byte* p = alloc.allocate(Slab::kMostTaken + 1);
        EXPECT_FALSE(slab.holds(p));
        p[Slab::kMostTaken] = std::byte{1};
        alloc.deallocate(p, Slab::kMostTaken + 1);
    }
    EXPECT_LT(heap_in_use(), before + Slab::kMostTaken) << "an array kept from the heap";
    EXPECT_EQ(slab.blocks(), 0u);
}

// A chunk of items whose size does not divide a huge page is still mapped whole (a huge page's
// size, aligned to one, not advised): the hold's zones are 72 bytes.
TEST(ChunkedArrayReady, AChunkIsAWholeHugePageWhateverTheItemsSize) {
    struct Item {
        double v[9];  // 72 bytes: 29,127 to a chunk, 56 bytes over
    };
    apci::run::detail::ChunkedArray<Item> items;
    items.emplace_back().v[0] = 1.0;
    const auto* first = reinterpret_cast<const std::byte*>(&items[0]);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(first) % kHugePage, 0u);
    EXPECT_FALSE(mapping_of(first).advised_huge()) << mapping_of(first).flags;
    EXPECT_GE(mapping_of(first).hi, reinterpret_cast<std::uintptr_t>(first) + kHugePage);
}

// The pipeline carves its batches' arrays once, the first time round: a run that fills every
// batch many times takes no more of the address space than one that fills each once.
TEST(PipelineReady, TheBatchesArraysAreCarvedOnceNotEachTimeRound) {
    SKIP_ADDRESS_SPACE_UNDER_SANITIZER();
    using apci::run::PipelinedSink;
    LinePipeline p;
    PipelinedSink& pipe = p.pipe;
    apci::run::PathSegment& s = p.s;
    const std::size_t round = PipelinedSink::kBatches * PipelinedSink::kBatchEvents;
    for (std::size_t i = 0; i < round; ++i) pipe.executed(s);
    const long once = address_space_kib();
    for (std::size_t i = 0; i < 6 * round; ++i) pipe.executed(s);
    const long later = address_space_kib();
    pipe.finish();
    // Six rounds more carved anew would map about 12 MiB more (a round's arrays: 2 MiB).
    EXPECT_LT(later - once, static_cast<long>(Slab::kBlockBytes / 1024)) << once << " KiB before";
}

}  // namespace
