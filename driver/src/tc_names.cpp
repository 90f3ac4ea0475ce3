// SPDX-License-Identifier: MIT
// The names of the TC register bits in [APCI-TC] Table 4 (ERROR)
// and Table 5 (STATUS).
#include "apci/apci.h"
#include "objif/map/object_map.h"
#include "objif/map/tc_bits.h"

namespace {

// The names come from the emulator's table, next to the registers they name.
template <std::size_t N>
const char* bit_name(const std::array<objif::map::tc::BitName, N>& bits, int bit) noexcept {
    if (bit < 0 || bit > 30) return nullptr;
    for (const auto& b : bits)
        if (b.mask == (std::int32_t{1} << bit)) return b.name.data();  // literals: NUL-terminated
    return nullptr;
}

}  // namespace

extern "C" {

const char* apci_tc_error_bit_name(int bit) noexcept {
    return bit_name(objif::map::tc::kErrorBits, bit);
}

const char* apci_tc_status_bit_name(int bit) noexcept {
    return bit_name(objif::map::tc::kStatusBits, bit);
}

}  // extern "C"

// apci.h repeats the emulator's object map for C programs; keep them equal.
static_assert(APCI_TC_BUS == objif::map::tc::kBus);
static_assert(APCI_TC_DEVICE_INIT == objif::map::tc::kDevInit);
static_assert(APCI_TC_DEVICE_GROUP == objif::map::tc::kDevGroups);
static_assert(APCI_TC_CLEAN == objif::map::tc::kIdxClean);
static_assert(APCI_TC_AXIS_NR == objif::map::tc::kIdxAxisNr);
static_assert(APCI_TC_PLANE == objif::map::tc::kIdxTcPlane);
static_assert(APCI_TC_REINIT == objif::map::tc::kIdxReInit);
static_assert(APCI_TC_RESET == objif::map::tc::kIdxReset);
static_assert(APCI_TC_ROT_ANGLE == objif::map::tc::kIdxRotAngle);
static_assert(APCI_TC_ROT_CENTER_X == objif::map::tc::kIdxRotCenterX);
static_assert(APCI_TC_ROT_CENTER_Y == objif::map::tc::kIdxRotCenterY);
static_assert(APCI_TC_ERROR == objif::map::tc::kSubError);
static_assert(APCI_TC_GROUP_RESET == objif::map::tc::kSubReset);
static_assert(APCI_TC_STATUS == objif::map::tc::kSubStatus);
static_assert(APCI_TC_XAXIS == objif::map::tc::kSubXAxis);
static_assert(APCI_TC_YAXIS == objif::map::tc::kSubYAxis);
static_assert(APCI_TC_RADIUS == objif::map::tc::kSubRadius);
static_assert(APCI_TC_WKZINDEX == objif::map::tc::kSubWkzIndex);
static_assert(APCI_TC_LEFT == objif::map::tc::kSubLeft);
static_assert(APCI_TC_RIGHT == objif::map::tc::kSubRight);
static_assert(APCI_TC_ZAXIS == objif::map::tc::kSubZAxis);
static_assert(APCI_TC_WKZLEN == objif::map::tc::kSubWkzLen);
static_assert(APCI_TC_ERROR_INIT == objif::map::tc::kInitError);
static_assert(APCI_TC_ERROR_KORR == objif::map::tc::kKorrError);
static_assert(APCI_TC_ERROR_CALC == objif::map::tc::kCalcError);
static_assert(APCI_TC_ERROR_PLANE == objif::map::tc::kPlaneError);
static_assert(APCI_TC_ERROR_CENTER == objif::map::tc::kCenterError);
static_assert(APCI_TC_STATUS_RUN == objif::map::tc::kRun);
static_assert(APCI_TC_STATUS_PROF_MARKED == objif::map::tc::kProfMarked);
