// SPDX-License-Identifier: MIT
#include "rwmos/frame_stream.h"

namespace rwmos {

FrameStream::Result FrameStream::feed(std::span<const std::uint8_t> bytes, FrameServer& server,
                                      std::vector<std::uint8_t>& replies) {
    append(bytes);
    return serve(server, replies, Turn{});
}

void FrameStream::append(std::span<const std::uint8_t> bytes) {
    buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

FrameStream::Result FrameStream::serve(FrameServer& server, std::vector<std::uint8_t>& replies,
                                       const Turn& turn) {
    Result result;
    const std::size_t replies_before = replies.size();
    const bool timed = turn.until != std::chrono::steady_clock::time_point::max();
    while (start_ < buffer_.size()) {
        if (result.frames != 0 && ((timed && std::chrono::steady_clock::now() >= turn.until) ||
                                   replies.size() - replies_before >= turn.reply_bytes)) {
            result.more = true;  // the turn is over; the rest waits for the next
            break;
        }
        const std::span<const std::uint8_t> rest(buffer_.data() + start_, buffer_.size() - start_);
        std::size_t consumed = 0;
        bool need_more = false;
        const objif::FrameError e = objif::decode_frame(rest, frame_, consumed, need_more);
        if (e == objif::FrameError::kNone) {
            // A frame whose payload does not decode, or whose opcode is not
            // served, is answered with an Error reply too: counted.
            if (server.handle(frame_, host_, replies) != objif::FrameError::kNone) ++result.rejected;
        } else if (need_more) {
            break;
        } else if (consumed == 0) {
            result.keep = false;
            result.garbage = e;
            result.more = false;
            clear();
            return result;
        } else {
            FrameServer::reject(frame_.sequence, e, replies);
            ++result.rejected;
        }
        ++result.frames;
        start_ += consumed;
    }
    // Keep only the unconsumed tail, at the front of the buffer.
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
    return result;
}

}  // namespace rwmos
