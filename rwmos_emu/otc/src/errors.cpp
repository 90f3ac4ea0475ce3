// SPDX-License-Identifier: MIT
#include "rwmos/otc/errors.h"

#include <array>

namespace rwmos::otc {

namespace {
constexpr std::array<ErrorInfo, 6> kErrors{{
    {Error::kNone, "none", "no error"},
    {Error::kToolNotGrinding, "P-ERR-21391",
     "OTC needs a grinding tool (tool type 2, P-TOOL-00001); OTC stays off"},
    {Error::kOffBeforeG40, "OTC_OFF_BEFORE_G40",
     "#OTC OFF while tool radius compensation is on: program G40 before #OTC OFF"},
    {Error::kChangeWhileActive, "OTC_CHANGE_WHILE_ACTIVE",
     "processing type, mode and ACC_WEIGHT are set before or with #OTC ON, not while OTC is on"},
    {Error::kToolChangeWhileActive, "OTC_TOOL_CHANGE_WHILE_ACTIVE",
     "the tool is not changed while OTC is on: program #OTC OFF first"},
    {Error::kInfeedBeyondLimit, "OTC_INFEED_BEYOND_LIMIT",
     "discrete offset beyond grinding_max_infeed (P-TOOL-00031) of the current tool"},
}};
}  // namespace

const ErrorInfo& error_info(Error e) noexcept {
    for (const ErrorInfo& i : kErrors)
        if (i.error == e) return i;
    return kErrors[0];
}

}  // namespace rwmos::otc
