// SPDX-License-Identifier: MIT
#include "rwmos/motion/types.h"

namespace rwmos::motion {

std::string_view profile_kind_name(ProfileKind k) noexcept {
    switch (k) {
        case ProfileKind::kRapid:
            return "G00";
        case ProfileKind::kLine:
            return "G01";
        case ProfileKind::kArcCw:
            return "G02";
        case ProfileKind::kArcCcw:
            return "G03";
        case ProfileKind::kTraverse:
            return "G00 (traverse)";
    }
    return "unknown";
}

std::string_view direct_code_name(DirectCode c) noexcept {
    switch (c) {
        case DirectCode::kJA:
            return "JA";
        case DirectCode::kJS:
            return "JS";
    }
    return "unknown";
}

std::string_view segment_role_name(SegmentRole r) noexcept {
    switch (r) {
        case SegmentRole::kContour:
            return "contour";
        case SegmentRole::kTransition:
            return "transition";
        case SegmentRole::kApproach:
            return "approach";
        case SegmentRole::kDeparture:
            return "departure";
        case SegmentRole::kUncompensated:
            return "uncompensated";
        case SegmentRole::kRapid:
            return "rapid";
    }
    return "unknown";
}

std::string_view segment_kind_name(SegmentKind k) noexcept {
    switch (k) {
        case SegmentKind::kLine:
            return "line";
        case SegmentKind::kArc:
            return "arc";
    }
    return "unknown";
}

}  // namespace rwmos::motion
