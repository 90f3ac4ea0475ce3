// SPDX-License-Identifier: MIT
// The motion requests at the request level, in the wire payload structs of
// objif/frame.h: the FrameServer (every framed transport) and the driver's
// in-process transport both serve them through these functions, so a board
// answers the same on every transport. docs/motion.md "Wire payloads".
#pragma once

#include "objif/frame.h"
#include "rwmos/board.h"

namespace rwmos {

objif::MotionReply serve_spool(EmulatedBoard& board, const objif::SpoolRequest& req);
// The same reply written into `rep` (the in-process transport: none built and moved per call).
void serve_spool(EmulatedBoard& board, const objif::SpoolRequest& req, objif::MotionReply& rep);
objif::MotionReply serve_direct(EmulatedBoard& board, const objif::DirectRequest& req);
objif::MotionReply serve_ssf(EmulatedBoard& board, const objif::SsfRequest& req);
objif::ClockReply serve_clock(EmulatedBoard& board, const objif::ClockRequest& req);
// Reads at most req.max items, and at most one reply frame's worth.
objif::TraceReply serve_trace(EmulatedBoard& board, const objif::TraceRequest& req);

}  // namespace rwmos
