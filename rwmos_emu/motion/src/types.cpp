// SPDX-License-Identifier: MIT
#include "rwmos/motion/types.h"

#include "objif/enum_names.h"

namespace rwmos::motion {
namespace {

constexpr auto kProfileKindNames = objif::enum_names<ProfileKind::kRapid, ProfileKind::kTraverse>(
    {"G00", "G01", "G02", "G03", "G00 (traverse)"}, "unknown");
constexpr auto kDirectCodeNames =
    objif::enum_names<DirectCode::kJA, DirectCode::kJS>({"JA", "JS"}, "unknown");
constexpr auto kSegmentRoleNames = objif::enum_names<SegmentRole::kContour, SegmentRole::kRapid>(
    {"contour", "transition", "approach", "departure", "uncompensated", "rapid"}, "unknown");
constexpr auto kSegmentKindNames =
    objif::enum_names<SegmentKind::kLine, SegmentKind::kArc>({"line", "arc"}, "unknown");

}  // namespace

std::string_view profile_kind_name(ProfileKind k) noexcept {
    return kProfileKindNames(k);
}

std::string_view direct_code_name(DirectCode c) noexcept {
    return kDirectCodeNames(c);
}

std::string_view segment_role_name(SegmentRole r) noexcept {
    return kSegmentRoleNames(r);
}

std::string_view segment_kind_name(SegmentKind k) noexcept {
    return kSegmentKindNames(k);
}

}  // namespace rwmos::motion
