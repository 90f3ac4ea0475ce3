// SPDX-License-Identifier: MIT
// Fuzz target: the dual-port RAM mailbox (objif/mailbox.h) read from a
// mapping whose content anyone who may write the shm file controls. The
// input is the mapping as a host or the board finds it:
//   byte 0         bit 0: a board answers the host's doorbell at once (its
//                  reply sequence follows the request sequence), so the
//                  host goes on to read the reply record from the input;
//   bytes 1..288   the window from offset 0: header, host lock, request
//                  sequence, board sleeping, request length, request frame;
//   the rest       the window from the reply sequence on: reply sequence,
//                  host sleeping, reply length, reply frame.
// Checks: check_layout accepts exactly a header of this layout; a host
// exchange ends within its timeout with a status, a reason when not kOk, the
// lock freed, and on kOk the reply the record holds, never more than a
// record; the board takes exactly a pending request, its frame empty when
// the announced length is out of range.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "objif/mailbox.h"

namespace {

namespace mb = objif::mailbox;

constexpr std::size_t kHeadBytes = 0x120;

// A window on ordinary memory whose board, if told to, answers each request
// the moment the host rings (the reply record is what the input put there).
class FuzzWindow final : public mb::MappedWindow {
  public:
    FuzzWindow(void* base, bool board_answers)
        : MappedWindow(base, mb::kWindowSize, false), board_answers_(board_answers) {}
    void store_fence(std::size_t offset, std::uint32_t value) noexcept override {
        MappedWindow::store_fence(offset, value);
        if (board_answers_ && offset == mb::kOffRequestSequence)
            MappedWindow::store_fence(mb::kOffReplySequence, value);
    }
    // Nothing to sleep on: the fuzzer never waits.
    void wait(std::size_t, std::uint32_t, std::chrono::nanoseconds) noexcept override {}

  private:
    bool board_answers_;
};

void fill(std::vector<std::uint32_t>& words, const std::uint8_t* data, std::size_t size) {
    std::fill(words.begin(), words.end(), 0);
    auto* bytes = reinterpret_cast<std::uint8_t*>(words.data());
    const std::size_t head = std::min(size, kHeadBytes);
    std::memcpy(bytes, data, head);
    const std::size_t tail = std::min(size - head, mb::kWindowSize - mb::kOffReplySequence);
    std::memcpy(bytes + mb::kOffReplySequence, data + head, tail);
}

void check_layout_contract(mb::Window& w) {
    const bool ours = w.load(mb::kOffSignature) == mb::kSignature &&
                      w.load(mb::kOffVersion) == mb::kLayoutVersion &&
                      w.load(mb::kOffWindowSize) == mb::kWindowSize &&
                      w.load(mb::kOffRecordCapacity) == mb::kRecordCapacity;
    FUZZ_CHECK(mb::check_layout(w).empty() == ours,
               "check_layout accepts exactly a header of this layout");
}

void check_host(std::vector<std::uint32_t>& words, bool board_answers) {
    FuzzWindow w(words.data(), board_answers);
    const std::uint32_t lock_before = w.load(mb::kOffHostLock);
    mb::HostOptions options;
    options.token = 0x7fffffff;
    options.spin = std::chrono::nanoseconds(0);
    options.timeout = std::chrono::milliseconds(0);
    const std::vector<std::uint8_t> request(objif::kFrameOverhead, 0x5a);
    std::vector<std::uint8_t> reply{1, 2, 3};
    std::string why;
    const objif::Status s = mb::exchange(w, options, request, reply, why);
    FUZZ_CHECK(s == objif::Status::kOk || !why.empty(), "a failed exchange says why");
    FUZZ_CHECK(w.load(mb::kOffHostLock) == lock_before || lock_before == options.token,
               "the host lock is freed (or left to the host holding it)");
    if (s != objif::Status::kOk) return;
    FUZZ_CHECK(board_answers, "a reply only comes from a board");
    const std::uint32_t length = w.load(mb::kOffReply);
    FUZZ_CHECK(length <= mb::kRecordCapacity && reply.size() == length,
               "the reply is the record's length, at most a record");
    const auto* record = reinterpret_cast<const std::uint8_t*>(words.data()) + mb::kOffReply + 4;
    FUZZ_CHECK(std::equal(reply.begin(), reply.end(), record), "the reply is the record's bytes");
}

void check_board(std::vector<std::uint32_t>& words) {
    FuzzWindow w(words.data(), false);
    const std::uint32_t requested = w.load(mb::kOffRequestSequence);
    const std::uint32_t answered = w.load(mb::kOffReplySequence);
    const std::uint32_t length = w.load(mb::kOffRequest);
    mb::Request request;
    request.frame.assign(3, 0xee);
    const bool got =
        mb::take_request(w, request, std::chrono::nanoseconds(0), std::chrono::nanoseconds(0));
    FUZZ_CHECK(got == (requested != answered), "the board takes exactly a pending request");
    if (!got) return;
    FUZZ_CHECK(request.sequence == requested, "the reply will answer the request's sequence");
    if (length < objif::kFrameOverhead || length > mb::kRecordCapacity) {
        FUZZ_CHECK(request.frame.empty(), "an impossible length gives an empty frame");
        return;
    }
    const auto* record = reinterpret_cast<const std::uint8_t*>(words.data()) + mb::kOffRequest + 4;
    FUZZ_CHECK(request.frame.size() == length &&
                   std::equal(request.frame.begin(), request.frame.end(), record),
               "the frame is the record's bytes");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static std::vector<std::uint32_t> words(mb::kWindowSize / 4);
    const bool board_answers = (data[0] & 1) != 0;
    fill(words, data + 1, size - 1);
    {
        FuzzWindow w(words.data(), false);
        check_layout_contract(w);
    }
    check_host(words, board_answers);
    fill(words, data + 1, size - 1);
    check_board(words);
    return 0;
}
