// SPDX-License-Identifier: MIT
// Seed names of the TC register bits: APCI-8001 TC document, Table 4 (ERROR)
// and Table 5 (STATUS).
#include <array>

#include "apci/apci.h"

namespace {

constexpr std::array<const char*, 5> kErrorBits{
    "InitError", "KorrError", "CalcError", "PlaneError", "CenterError"};
constexpr std::array<const char*, 2> kStatusBits{"Run", "ProfMarked"};

static_assert(APCI_TC_ERROR_INIT == 1u << 0 && APCI_TC_ERROR_KORR == 1u << 1 &&
              APCI_TC_ERROR_CALC == 1u << 2 && APCI_TC_ERROR_PLANE == 1u << 3 &&
              APCI_TC_ERROR_CENTER == 1u << 4);
static_assert(APCI_TC_STATUS_RUN == 1u << 0 && APCI_TC_STATUS_PROF_MARKED == 1u << 1);

template <std::size_t N>
const char* bit_name(const std::array<const char*, N>& names, int bit) noexcept {
    if (bit < 0 || static_cast<std::size_t>(bit) >= N) return nullptr;
    return names[static_cast<std::size_t>(bit)];
}

}  // namespace

extern "C" {

const char* apci_tc_error_bit_name(int bit) noexcept {
    return bit_name(kErrorBits, bit);
}

const char* apci_tc_status_bit_name(int bit) noexcept {
    return bit_name(kStatusBits, bit);
}

}  // extern "C"
