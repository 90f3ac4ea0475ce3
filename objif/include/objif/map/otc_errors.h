// SPDX-License-Identifier: MIT
// The errors of the online tool compensation, one table: [ISG-OTC]'s P-ERR-21391 and our own
// (design numbers from 21900, named after the rule they enforce). The OTC module's LastError
// object reads the number; the NC front end and apcictl print the name and message. Part of the
// object contract between a host and a board, so it lives in objif (docs/design.md section 2,
// "Shared declarations"); the emulator's OTC module includes it as rwmos/otc/errors.h.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace objif::map::otc {

enum class Error : std::int32_t {
    kNone = 0,
    // [ISG-OTC] section 1 "Eigenschaften": "Die Verschleißkompensation kann nur mit dem
    // Werkzeugtyp 2 (Schleifwerkzeug) aktiviert werden. Wird ein anderer Werkzeugtyp verwendet,
    // so wird die Fehlermeldung P-ERR-21391 ausgegeben."
    kToolNotGrinding = 21391,
    // [ISG-OTC] section 2.2 "Hinweis": "Bei der Abwahl muss zwingend die Sequenz G40 vor
    // #OTC OFF eingehalten werden."
    kOffBeforeG40 = 21901,
    // [ISG-OTC] section 2.1: "Die Parametrierung kann vorab oder zusammen mit #OTC ON erfolgen":
    // type, mode and ACC_WEIGHT are not changed while OTC is on.
    kChangeWhileActive = 21902,
    // The current tool (its data and its wear) is not changed while OTC is on.
    kToolChangeWhileActive = 21903,
    // [ISG-OTC] section 2.6: "Wenn grinding_max_infeed nicht gesetzt wird, kann kein diskreter
    // Versatz beauftragt werden"; section 2.7: range [-P-TOOL-00031, P-TOOL-00031].
    kInfeedBeyondLimit = 21904,
};

struct ErrorInfo {
    Error error;
    std::string_view name;     // "P-ERR-21391", "OTC_OFF_BEFORE_G40", ...
    std::string_view message;  // one line
};

// One table; header-only, so host tools name the errors without the emulator.
inline constexpr std::array<ErrorInfo, 6> kErrors{{
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

// The table row of `e` (kNone for unknown numbers).
constexpr const ErrorInfo& error_info(Error e) noexcept {
    for (const ErrorInfo& i : kErrors)
        if (i.error == e) return i;
    return kErrors[0];
}
inline std::string_view error_name(Error e) noexcept {
    return error_info(e).name;
}
inline std::string_view error_message(Error e) noexcept {
    return error_info(e).message;
}

}  // namespace objif::map::otc
