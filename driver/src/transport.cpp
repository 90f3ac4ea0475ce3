// SPDX-License-Identifier: MIT
// Device URI parsing and the scheme table: one row per backend.
#include "transport.h"
#include "guarded.h"

#include <array>
#include <new>

#include <fmt/format.h>

namespace apci {
namespace {

using OpenFn = objif::Status (*)(const DeviceUri&, std::unique_ptr<Transport>&,
                                 std::string&) noexcept;
using ListFn = objif::Status (*)(std::vector<FoundDevice>&, std::string&) noexcept;

struct Scheme {
    std::string_view name;
    OpenFn open;  // nullptr: known scheme, backend not built
    ListFn list;  // nullptr: nothing to enumerate (emu:)
    std::string_view form;
};

#if defined(APCI_HAVE_LIBUSB)
constexpr OpenFn kOpenUsb = open_usb;
constexpr ListFn kListUsb = list_usb;
#else
constexpr OpenFn kOpenUsb = nullptr;  // built without libusb-1.0
constexpr ListFn kListUsb = nullptr;
#endif

// docs/design.md section 6. One row per backend; list_devices() walks the rows in
// this order, so boards come before emulators.
constexpr std::array kSchemes{
    Scheme{"usb", kOpenUsb, kListUsb, "usb:[BUS:ADDR]"},
    Scheme{"pci", open_pci, list_pci, "pci:DOMAIN:BUS:DEV.FN"},
    Scheme{"unix", open_unix, list_unix, "unix:PATH"},
    Scheme{"shm", open_shm, list_shm, "shm:PATH"},
    Scheme{"emu", open_inproc, nullptr, "emu:[?no-option-tc]"},
};

constexpr bool scheme_char(char c) noexcept {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.';
}

std::string known_schemes() {
    std::string s;
    for (const auto& row : kSchemes) {
        if (!s.empty()) s += ", ";
        s += row.form;
    }
    return s;
}

}  // namespace

objif::Status parse_device_uri(std::string_view text, DeviceUri& out, std::string& why) noexcept {
    return guarded([&] {
        DeviceUri uri;
        if (text.empty()) text = "emu:";
        const auto colon = text.find(':');
        if (colon == std::string_view::npos || colon == 0) {
            why = fmt::format("device URI '{}' has no scheme (expected one of: {})", text,
                              known_schemes());
            return objif::Status::kInvalidArgument;
        }
        uri.scheme = std::string(text.substr(0, colon));
        for (char c : uri.scheme) {
            if (!scheme_char(c)) {
                why = fmt::format("device URI '{}': scheme '{}' has an invalid character '{}'",
                                  text, uri.scheme, c);
                return objif::Status::kInvalidArgument;
            }
        }
        std::string_view rest = text.substr(colon + 1);
        const auto q = rest.find('?');
        uri.target = std::string(rest.substr(0, q));
        if (q != std::string_view::npos) {
            std::string_view opts = rest.substr(q + 1);
            while (true) {
                const auto amp = opts.find('&');
                const std::string_view item = opts.substr(0, amp);
                if (item.empty()) {
                    why = fmt::format("device URI '{}' has an empty option", text);
                    return objif::Status::kInvalidArgument;
                }
                uri.options.emplace_back(item);
                if (amp == std::string_view::npos) break;
                opts = opts.substr(amp + 1);
            }
        }
        out = std::move(uri);
        return objif::Status::kOk;
    });
}

objif::Status open_transport(const DeviceUri& uri, std::unique_ptr<Transport>& out,
                             std::string& why) noexcept {
    try {
        for (const auto& row : kSchemes) {
            if (row.name != uri.scheme) continue;
            if (row.open == nullptr) {
                why = fmt::format("transport '{}:' is not available: this libapci was built "
                                  "without its library",
                                  uri.scheme);
                return objif::Status::kNotSupported;
            }
            return row.open(uri, out, why);
        }
        why = fmt::format("unknown device URI scheme '{}:' (expected one of: {})", uri.scheme,
                          known_schemes());
        return objif::Status::kInvalidArgument;
    } catch (const std::bad_alloc&) {
        return objif::Status::kNoMemory;
    } catch (...) {
        return objif::Status::kGeneralError;
    }
}

objif::Status list_devices(std::vector<FoundDevice>& out, std::vector<std::string>& problems) noexcept {
    return guarded([&] {
        for (const auto& row : kSchemes) {
            if (row.list == nullptr) continue;
            std::string why;
            const objif::Status s = row.list(out, why);
            if (!objif::ok(s))
                problems.push_back(fmt::format("{}: {} ({})", row.name, why.empty() ? "enumeration failed" : why,
                                               objif::status_name(s)));
        }
        return objif::Status::kOk;
    });
}

std::string lost_link_words(std::string_view cause, bool once_back) {
    return fmt::format("{}; apci_reconnect() reopens the link{}", cause,
                       once_back ? " once it is back" : "");
}

std::string still_lost_words(std::string_view cause) {
    return lost_link_words(fmt::format("link lost: {}", cause));
}

}  // namespace apci
