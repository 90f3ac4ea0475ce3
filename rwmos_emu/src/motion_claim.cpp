// SPDX-License-Identifier: MIT
#include "rwmos/motion_claim.h"

#include <chrono>

namespace rwmos {

using objif::ClaimAction;
using objif::Status;

namespace {
std::uint64_t now_ms() {
    const auto since_epoch = std::chrono::system_clock::now().time_since_epoch();
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::milliseconds>(since_epoch).count());
}
}  // namespace

void MotionClaim::forget_dead_holder() {
    if (holder_ && holder_->by_pid && alive_ != nullptr && !alive_(*holder_)) holder_.reset();
}

const std::optional<Host>& MotionClaim::holder() {
    forget_dead_holder();
    return holder_;
}

objif::ClaimReply MotionClaim::reply_for(const Host& host, Status status) const {
    objif::ClaimReply reply;
    reply.status = status;
    if (holder_) {
        reply.held = true;
        reply.yours = holder_->key == host.key;
        reply.pid = holder_->pid;
        reply.name = holder_->name.substr(0, objif::kMaxHolderName);
        reply.since_ms = since_ms_;
    }
    return reply;
}

objif::ClaimReply MotionClaim::serve(const Host& host, const objif::ClaimRequest& request) {
    forget_dead_holder();
    const bool mine = holder_ && holder_->key == host.key;
    switch (request.action) {
        case ClaimAction::kClaim:
            if (mine) return reply_for(host, Status::kWrongDeviceState);
            if (holder_) return reply_for(host, Status::kMotionClaimed);
            holder_ = host;
            since_ms_ = now_ms();
            return reply_for(host, Status::kOk);
        case ClaimAction::kRelease:
            if (!mine) return reply_for(host, Status::kWrongDeviceState);
            holder_.reset();
            since_ms_ = 0;
            return reply_for(host, Status::kOk);
        case ClaimAction::kQuery:
            break;
    }
    return reply_for(host, Status::kOk);
}

bool MotionClaim::allows(const Host& host) {
    forget_dead_holder();
    return !holder_ || holder_->key == host.key;
}

std::string MotionClaim::held_text() const {
    if (!holder_) return {};
    return "the board's motion is held by " + objif::claim_holder_text(reply_for(Host{}, Status::kOk));
}

bool MotionClaim::drop(std::uint64_t key) {
    if (!holder_ || holder_->key != key) return false;
    holder_.reset();
    since_ms_ = 0;
    return true;
}

}  // namespace rwmos
