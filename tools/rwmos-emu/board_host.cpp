// SPDX-License-Identifier: MIT
#include "board_host.h"

namespace rwmos_emu {

rwmos::FrameStream::Result BoardHost::serve_stream(rwmos::FrameStream& stream,
                                                   std::span<const std::uint8_t> bytes,
                                                   std::vector<std::uint8_t>& replies) {
    const std::lock_guard lock(mutex_);
    const auto result = stream.feed(bytes, server_, replies);
    counts_.frames += result.frames;
    counts_.rejected += result.rejected;
    return result;
}

void BoardHost::serve_frame(std::span<const std::uint8_t> request, std::vector<std::uint8_t>& reply) {
    const std::lock_guard lock(mutex_);
    const objif::FrameError e = server_.serve(request, reply);
    ++counts_.frames;
    if (e != objif::FrameError::kNone) ++counts_.rejected;
}

ServedCounts BoardHost::counts() const {
    const std::lock_guard lock(mutex_);
    return counts_;
}

}  // namespace rwmos_emu
