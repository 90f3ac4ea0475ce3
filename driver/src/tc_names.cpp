// SPDX-License-Identifier: MIT
// The names of the TC register bits in [APCI-TC] Table 4 (ERROR)
// and Table 5 (STATUS).
#include "apci/apci.h"
#include "rwmos/object_map.h"
#include "rwmos/tc_bits.h"

namespace {

// The names come from the emulator's table, next to the registers they name.
template <std::size_t N>
const char* bit_name(const std::array<rwmos::tc::BitName, N>& bits, int bit) noexcept {
    if (bit < 0 || bit > 30) return nullptr;
    for (const auto& b : bits)
        if (b.mask == (std::int32_t{1} << bit)) return b.name.data();  // literals: NUL-terminated
    return nullptr;
}

}  // namespace

extern "C" {

const char* apci_tc_error_bit_name(int bit) noexcept {
    return bit_name(rwmos::tc::kErrorBits, bit);
}

const char* apci_tc_status_bit_name(int bit) noexcept {
    return bit_name(rwmos::tc::kStatusBits, bit);
}

}  // extern "C"

// apci.h repeats the emulator's object map for C programs; keep them equal.
static_assert(APCI_TC_BUS == rwmos::tc::kBus);
static_assert(APCI_TC_DEVICE_INIT == rwmos::tc::kDevInit);
static_assert(APCI_TC_DEVICE_GROUP == rwmos::tc::kDevGroups);
static_assert(APCI_TC_CLEAN == rwmos::tc::kIdxClean);
static_assert(APCI_TC_AXIS_NR == rwmos::tc::kIdxAxisNr);
static_assert(APCI_TC_PLANE == rwmos::tc::kIdxTcPlane);
static_assert(APCI_TC_REINIT == rwmos::tc::kIdxReInit);
static_assert(APCI_TC_RESET == rwmos::tc::kIdxReset);
static_assert(APCI_TC_ROT_ANGLE == rwmos::tc::kIdxRotAngle);
static_assert(APCI_TC_ROT_CENTER_X == rwmos::tc::kIdxRotCenterX);
static_assert(APCI_TC_ROT_CENTER_Y == rwmos::tc::kIdxRotCenterY);
static_assert(APCI_TC_ERROR == rwmos::tc::kSubError);
static_assert(APCI_TC_GROUP_RESET == rwmos::tc::kSubReset);
static_assert(APCI_TC_STATUS == rwmos::tc::kSubStatus);
static_assert(APCI_TC_XAXIS == rwmos::tc::kSubXAxis);
static_assert(APCI_TC_YAXIS == rwmos::tc::kSubYAxis);
static_assert(APCI_TC_RADIUS == rwmos::tc::kSubRadius);
static_assert(APCI_TC_WKZINDEX == rwmos::tc::kSubWkzIndex);
static_assert(APCI_TC_LEFT == rwmos::tc::kSubLeft);
static_assert(APCI_TC_RIGHT == rwmos::tc::kSubRight);
static_assert(APCI_TC_ZAXIS == rwmos::tc::kSubZAxis);
static_assert(APCI_TC_WKZLEN == rwmos::tc::kSubWkzLen);
static_assert(APCI_TC_ERROR_INIT == rwmos::tc::kInitError);
static_assert(APCI_TC_ERROR_KORR == rwmos::tc::kKorrError);
static_assert(APCI_TC_ERROR_CALC == rwmos::tc::kCalcError);
static_assert(APCI_TC_ERROR_PLANE == rwmos::tc::kPlaneError);
static_assert(APCI_TC_ERROR_CENTER == rwmos::tc::kCenterError);
static_assert(APCI_TC_STATUS_RUN == rwmos::tc::kRun);
static_assert(APCI_TC_STATUS_PROF_MARKED == rwmos::tc::kProfMarked);
