// SPDX-License-Identifier: MIT
// Bottleneck avoidance as SINUMERIK's collision detection (CDON) does it ([SIN-CD]): the tool
// paths (equidistants) of the compensated moves are compared over a number of blocks ahead
// (MD 20240 CUTCOM_MAXNUM_CHECK_BLOCKS); where the paths of two moves that do not follow each
// other cross, the moves programmed between them are left out in the plane, and the tool goes
// from the one path to the other at the crossing. `apcictl run --avoid-bottlenecks N`
// (docs/apcictl.md, docs/compensation.md "Avoidance").
//
// The avoider sits between the NC program's events and the executor: it holds the compensated
// moves of a stretch up to N blocks back and gives them on as they fall out of its view. Where
// the path of a move j crosses that of a move i two to N moves before it (the farthest back
// first; on j, the crossing X nearest j's start), move i ends at the point of its contour whose
// offset is X, move j starts at the point of its contour whose offset is X, and between them
// goes an arc about X of the tool's radius, on the tool's side: its offset is the point X, so
// the board's compensation runs the path of i to X and on from X along the path of j, as the
// corner rule of the board joins them (tangentially). What else the left-out moves did (their
// move on the third axis, events of their blocks) is done at X, in their order. The arc is no
// wall for the gouge check (CDOF around it).
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "apci/nc/events.h"
#include "apci/run/path.h"

namespace apci::run::detail {

// What was left out: the first and last block, the blocks whose paths cross, and where.
struct Bottleneck {
    nc::BlockOrigin first, last;  // of the left-out moves
    nc::BlockOrigin before, after;  // the moves whose paths cross (i and j)
    Point where = Point::Zero();
};

class BottleneckAvoider {
  public:
    static constexpr int kMinBlocks = 2;
    static constexpr int kMaxBlocks = 64;

    // `blocks`: how many moves back a move's path is compared with (2..64; MD 20240).
    explicit BottleneckAvoider(int blocks) : blocks_(blocks) {}

    // The next event of the program. `radius` is the tool's radius and `plane` the plane in
    // force (the executor's: events before G41/G42 reached it already). Events to execute now
    // are appended to `out`, each bottleneck avoided to `found`.
    void take(const nc::Event& ev, double radius, int plane, std::vector<nc::Event>& out,
              std::vector<Bottleneck>& found);
    // The end of the program (or of the stream): every event held goes out.
    void flush(std::vector<nc::Event>& out);

  private:
    // A held compensated move in the plane, its event's position in held_, its path.
    struct Move {
        std::size_t event = 0;
        bool arc = false;
        // The path in the plane: a line from a to b, or an arc about c of radius rho from
        // angle phi0 turning by sweep.
        Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
        Eigen::Vector2d c = Eigen::Vector2d::Zero();
        double rho = 0.0, phi0 = 0.0, sweep = 0.0;
        bool usable = true;  // a path to compare (a tool larger than a concave arc has none)
    };
    void hold(const nc::Event& ev, double radius, int plane, std::vector<Bottleneck>& found);
    void release(std::size_t count, std::vector<nc::Event>& out);
    void avoid(double radius, int plane, std::vector<Bottleneck>& found);

    int blocks_;
    int side_ = 0;             // +1 G41, -1 G42, 0 off
    bool first_ = false;       // the next move is the stretch's approach (not compared)
    bool walls_ = true;        // CDON (the program's), restored after a bridge
    std::deque<nc::Event> held_;
    std::deque<Move> moves_;   // of the events held, in order
};

}  // namespace apci::run::detail
