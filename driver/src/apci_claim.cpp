// SPDX-License-Identifier: MIT
// The C API of the motion claim (apci.h "Exclusive use of the board's motion";
// docs/motion-claim.md): the handle's side of it (whether this handle holds the claim, so a
// second claim or a release without one is refused before anything is sent) and the words
// that name a holder. The board keeps the claim itself, per link (Transport::claim).
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "apci/apci.h"
#include "c_api.h"
#include "objif/frame.h"

namespace {

using apci::fail;
using objif::ClaimAction;
using objif::Status;

static_assert(sizeof(apci_motion_claim::name) > objif::kMaxHolderName,
              "the holder's name and its NUL fit");

std::string describe(std::string_view op, Status s, std::string_view detail) {
    std::string text =
        fmt::format("{}: {} ({})", op, objif::status_name(s), objif::status_message(s));
    if (!detail.empty()) text += fmt::format(": {}", detail);
    return text;
}

apci_status claim_call(apci_board* board, ClaimAction action, objif::ClaimReply& rep) noexcept {
    return apci::to_c(board->transport->claim(objif::ClaimRequest{action}, rep));
}

}  // namespace

namespace apci {

std::string failure_words(apci_board* board, Status s) {
    if (s != Status::kMotionClaimed) return std::string(board->transport->failure_detail());
    objif::ClaimReply rep;
    if (board->transport->claim(objif::ClaimRequest{ClaimAction::kQuery}, rep) != Status::kOk ||
        !rep.held)
        return "another handle held the board's motion";
    return "the board's motion is held by " + objif::claim_holder_text(rep);
}

void drop_motion_claim(apci_board* board) noexcept {
    if (board == nullptr || !board->holds_motion) return;
    board->holds_motion = false;
    objif::ClaimReply rep;
    (void)claim_call(board, ClaimAction::kRelease, rep);
}

}  // namespace apci

extern "C" {

apci_status apci_claim_motion(apci_board* board) noexcept {
    if (board == nullptr)
        return fail(nullptr, Status::kInvalidArgument,
                    [] { return std::string("apci_claim_motion: board is NULL"); });
    if (board->holds_motion)
        return fail(board, Status::kWrongDeviceState, [] {
            return std::string(
                "apci_claim_motion: this handle holds the board's motion already (a claim is "
                "not counted: release it once)");
        });
    objif::ClaimReply rep;
    const Status s = board->transport->claim(objif::ClaimRequest{ClaimAction::kClaim}, rep);
    if (objif::ok(s)) {
        board->holds_motion = true;
        board->last_error.clear();
        board->board_message.clear();
        return APCI_OK;
    }
    if (s == Status::kMotionClaimed || s == Status::kWrongDeviceState) {
        // WrongDeviceState from the board: it knows this handle's host as the holder, which on
        // a link where the board knows hosts by process (shm:) means another handle of this
        // process holds it. Either way another handle does.
        return fail(board, Status::kMotionClaimed, [&] {
            std::string holder = objif::claim_holder_text(rep);
            if (s == Status::kWrongDeviceState) holder += ", another handle of this process";
            return describe("claim motion", Status::kMotionClaimed,
                            "the board's motion is held by " + holder);
        });
    }
    return fail(board, s, [&] {
        return describe("claim motion", s, board->transport->failure_detail());
    });
}

apci_status apci_release_motion(apci_board* board) noexcept {
    if (board == nullptr)
        return fail(nullptr, Status::kInvalidArgument,
                    [] { return std::string("apci_release_motion: board is NULL"); });
    if (!board->holds_motion)
        return fail(board, Status::kWrongDeviceState, [] {
            return std::string("apci_release_motion: this handle holds no claim on the board's "
                               "motion (apci_claim_motion)");
        });
    board->holds_motion = false;
    objif::ClaimReply rep;
    const Status s = board->transport->claim(objif::ClaimRequest{ClaimAction::kRelease}, rep);
    if (!objif::ok(s))
        return fail(board, s, [&] {
            return describe("release motion", s,
                            s == Status::kWrongDeviceState
                                ? std::string_view("the board no longer knew this handle as the "
                                                   "holder (its link was lost meanwhile)")
                                : board->transport->failure_detail());
        });
    board->last_error.clear();
    board->board_message.clear();
    return APCI_OK;
}

apci_status apci_motion_claim_get(apci_board* board, apci_motion_claim* claim) noexcept {
    if (board == nullptr || claim == nullptr)
        return fail(board, Status::kInvalidArgument, [&] {
            return fmt::format("apci_motion_claim_get: {} is NULL",
                               board == nullptr ? "board" : "claim");
        });
    objif::ClaimReply rep;
    const Status s = board->transport->claim(objif::ClaimRequest{ClaimAction::kQuery}, rep);
    if (!objif::ok(s))
        return fail(board, s, [&] {
            return describe("query motion claim", s, board->transport->failure_detail());
        });
    apci_motion_claim out{};
    out.held = rep.held ? 1 : 0;
    out.yours = rep.yours ? 1 : 0;
    out.pid = rep.pid;
    out.since_ms = rep.since_ms;
    const std::size_t n = std::min(rep.name.size(), sizeof out.name - 1);
    std::memcpy(out.name, rep.name.data(), n);
    *claim = out;
    board->last_error.clear();
    board->board_message.clear();
    return APCI_OK;
}

size_t apci_motion_claim_holder(const apci_motion_claim* claim, char* text, size_t size) noexcept {
    return apci::give_words(text, size, [&] {
        if (claim == nullptr || claim->held == 0) return std::string();
        objif::ClaimReply rep;
        rep.held = true;
        rep.yours = claim->yours != 0;
        rep.pid = claim->pid;
        rep.since_ms = claim->since_ms;
        rep.name.assign(claim->name, ::strnlen(claim->name, sizeof claim->name));
        return objif::claim_holder_text(rep);
    });
}

}  // extern "C"
