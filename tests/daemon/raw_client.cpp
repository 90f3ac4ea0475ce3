// SPDX-License-Identifier: MIT
#include "raw_client.h"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace daemon_test {

bool is_greeting(const objif::Frame& frame) {
    objif::Notice notice;
    return frame.opcode ==
               (static_cast<std::uint16_t>(objif::Opcode::kNotice) | objif::kReplyFlag) &&
           objif::decode(frame.payload, notice) == objif::FrameError::kNone &&
           notice.status == objif::Status::kOk;
}

RawClient::RawClient(const std::string& socket_path) {
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, socket_path.c_str(), sizeof addr.sun_path - 1);
    fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd_ >= 0 && ::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) close();
}

RawClient::~RawClient() {
    close();
}

void RawClient::close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

void RawClient::shutdown() {
    if (fd_ >= 0) ::shutdown(fd_, SHUT_RDWR);
}

bool RawClient::send(std::span<const std::uint8_t> bytes) {
    std::size_t sent = 0;
    while (fd_ >= 0 && sent < bytes.size()) {
        const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        sent += static_cast<std::size_t>(n);
    }
    return fd_ >= 0;
}

bool RawClient::receive(objif::Frame& frame, std::chrono::milliseconds timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            until - std::chrono::steady_clock::now());
        if (!receive_any(frame, std::max(left, std::chrono::milliseconds(0)))) return false;
        if (!is_greeting(frame)) return true;
    }
}

bool RawClient::receive_any(objif::Frame& frame, std::chrono::milliseconds timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    for (;;) {
        std::size_t consumed = 0;
        bool need_more = false;
        const auto e = objif::decode_frame(pending_, frame, consumed, need_more);
        if (e == objif::FrameError::kNone) {
            pending_.erase(pending_.begin(),
                           pending_.begin() + static_cast<std::ptrdiff_t>(consumed));
            return true;
        }
        if (!need_more && !pending_.empty()) return false;
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            until - std::chrono::steady_clock::now());
        if (fd_ < 0 || left.count() <= 0) return false;
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
        std::uint8_t buffer[4096];
        const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
        if (n <= 0) return false;
        pending_.insert(pending_.end(), buffer, buffer + n);
    }
}

bool RawClient::closed_by_peer(std::chrono::milliseconds timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (fd_ >= 0) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            until - std::chrono::steady_clock::now());
        if (left.count() <= 0) return false;
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
        std::uint8_t buffer[4096];
        const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
        if (n == 0 || (n < 0 && errno == ECONNRESET)) return true;
        if (n < 0) return false;
    }
    return false;
}

std::vector<std::uint8_t> frame_bytes(objif::Opcode op, std::uint32_t sequence,
                                      std::span<const std::uint8_t> payload) {
    std::vector<std::uint8_t> out;
    objif::encode_frame(static_cast<std::uint16_t>(op), sequence, payload, out);
    return out;
}

std::vector<std::uint8_t> write_double_frame(std::uint32_t sequence, objif::Address a, double v) {
    std::vector<std::uint8_t> payload;
    objif::encode(
        objif::WriteRequest{objif::Descriptor{a, objif::kNoHandle}, objif::Value::of_double(v)},
        payload);
    return frame_bytes(objif::Opcode::kObjectWrite, sequence, payload);
}

}  // namespace daemon_test
