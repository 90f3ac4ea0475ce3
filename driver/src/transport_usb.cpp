// SPDX-License-Identifier: MIT
// The USB transport ("usb:" or "usb:BUS:ADDR"): libusb bulk transfers on the
// board's vendor interface (objif/usb_layout.h, docs/usb.md): the request
// frame goes out on bulk OUT 0x01, the reply frame comes back on bulk IN
// 0x81, reassembled from the header's length.
// Options: pid=0xNNNN (repeatable: only these product IDs), timeout=MS.
// $APCI_USB_PRODUCT_IDS="0xNNNN,0xMMMM" narrows the match the same way.
// Unplug: a transfer that answers LIBUSB_ERROR_NO_DEVICE marks the link lost;
// every call then answers TransportError ("unplugged") until reconnect()
// finds the board again on the same port (or, for "usb:", any board).
// Blocking: each transfer blocks in libusb for at most the remaining
// timeout. Threading: one caller at a time; each link has its own libusb
// context, so distinct boards are independent. libusb codes become a status
// in status_of_libusb() and nowhere else.
#include <fmt/format.h>
#include <libusb.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#include "frame_transport.h"
#include "objif/usb_layout.h"
#include "guarded.h"

namespace apci {
namespace {

namespace usb = objif::usb;
using objif::Status;
using SteadyClock = std::chrono::steady_clock;

// The one place where this backend turns a libusb code into a status.
Status status_of_libusb(int rc) noexcept {
    switch (rc) {
        case LIBUSB_SUCCESS:
            return Status::kOk;
        case LIBUSB_ERROR_TIMEOUT:
            return Status::kTimeout;
        case LIBUSB_ERROR_NO_MEM:
            return Status::kNoMemory;
        case LIBUSB_ERROR_INVALID_PARAM:
            return Status::kInvalidArgument;
        case LIBUSB_ERROR_NOT_SUPPORTED:
            return Status::kNotSupported;
        case LIBUSB_ERROR_BUSY:  // interface claimed by another program
        case LIBUSB_ERROR_ACCESS:
        case LIBUSB_ERROR_NO_DEVICE:
        case LIBUSB_ERROR_NOT_FOUND:
        case LIBUSB_ERROR_PIPE:
        case LIBUSB_ERROR_OVERFLOW:
        case LIBUSB_ERROR_IO:
        default:
            return Status::kTransportError;
    }
}

std::string libusb_text(std::string_view what, int rc) {
    std::string text = fmt::format("{}: {} ({})", what, libusb_strerror(rc), libusb_error_name(rc));
    if (rc == LIBUSB_ERROR_ACCESS)
        text += "; install udev/60-apci8001.rules and re-plug the board, or join group plugdev";
    return text;
}

// A bulk IN buffer must be a whole number of packets, or the last one may overflow.
constexpr std::size_t kReadChunk = (kMaxFrameSize + 511) / 512 * 512;

struct UsbTarget {
    bool any = true;  // "usb:": the first board found
    std::uint8_t bus = 0, address = 0;
    std::vector<std::uint16_t> products;  // empty: any product of the vendors
};

bool parse_product_list(std::string_view text, std::vector<std::uint16_t>& out) {
    while (!text.empty()) {
        const auto comma = text.find(',');
        std::uint32_t v = 0;
        if (!parse_unsigned(text.substr(0, comma), 0xFFFF, v)) return false;
        out.push_back(static_cast<std::uint16_t>(v));
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    return true;
}

Status parse_target(const DeviceUri& uri, const std::vector<std::string>& options, UsbTarget& t,
                    std::string& why) {
    if (!uri.target.empty()) {
        const auto colon = uri.target.find(':');
        std::uint32_t bus = 0, address = 0;
        if (colon == std::string::npos ||
            !parse_unsigned(std::string_view(uri.target).substr(0, colon), 255, bus) ||
            !parse_unsigned(std::string_view(uri.target).substr(colon + 1), 127, address) ||
            bus == 0 || address == 0) {
            why = fmt::format(
                "usb:{}: expected usb: (first board) or usb:BUS:ADDR with decimal bus "
                "1..255 and address 1..127, as apcictl list prints them",
                uri.target);
            return Status::kInvalidArgument;
        }
        t.any = false;
        t.bus = static_cast<std::uint8_t>(bus);
        t.address = static_cast<std::uint8_t>(address);
    }
    for (const auto& o : options) {
        if (!o.starts_with("pid=") ||
            !parse_product_list(std::string_view(o).substr(4), t.products)) {
            why = fmt::format("usb: option '{}' is not pid=0xNNNN or timeout=MS", o);
            return Status::kInvalidArgument;
        }
    }
    if (const char* env = std::getenv("APCI_USB_PRODUCT_IDS"); env != nullptr && *env != '\0') {
        if (!parse_product_list(env, t.products)) {
            why = fmt::format(
                "APCI_USB_PRODUCT_IDS='{}' is not a comma-separated list of product IDs", env);
            return Status::kInvalidArgument;
        }
    }
    return Status::kOk;
}

using Context = std::unique_ptr<libusb_context, void (*)(libusb_context*)>;

Status make_context(Context& out, std::string& why) {
    libusb_context* ctx = nullptr;
    const int rc = libusb_init(&ctx);
    if (rc != LIBUSB_SUCCESS) {
        why = libusb_text("libusb_init", rc);
        return status_of_libusb(rc);
    }
    out = Context(ctx, libusb_exit);
    return Status::kOk;
}

// Whether the device is an ADDI-DATA board with the frame interface.
bool is_board(libusb_device* dev, const std::vector<std::uint16_t>& products) {
    libusb_device_descriptor desc{};
    if (libusb_get_device_descriptor(dev, &desc) != LIBUSB_SUCCESS) return false;
    if (std::find(usb::kVendorIds.begin(), usb::kVendorIds.end(), desc.idVendor) ==
        usb::kVendorIds.end())
        return false;
    if (!products.empty() &&
        std::find(products.begin(), products.end(), desc.idProduct) == products.end())
        return false;
    libusb_config_descriptor* config = nullptr;
    if (libusb_get_active_config_descriptor(dev, &config) != LIBUSB_SUCCESS &&
        libusb_get_config_descriptor(dev, 0, &config) != LIBUSB_SUCCESS)
        return false;
    bool in = false, out = false;
    for (int i = 0; i < config->bNumInterfaces; ++i) {
        for (int a = 0; a < config->interface[i].num_altsetting; ++a) {
            const libusb_interface_descriptor& alt = config->interface[i].altsetting[a];
            if (alt.bInterfaceNumber != usb::kInterfaceNumber ||
                alt.bInterfaceClass != usb::kInterfaceClass)
                continue;
            for (int e = 0; e < alt.bNumEndpoints; ++e) {
                const auto& ep = alt.endpoint[e];
                const bool bulk = (ep.bmAttributes & 0x3) == LIBUSB_TRANSFER_TYPE_BULK;
                in = in || (bulk && ep.bEndpointAddress == usb::kEndpointIn);
                out = out || (bulk && ep.bEndpointAddress == usb::kEndpointOut);
            }
        }
    }
    libusb_free_config_descriptor(config);
    return in && out;
}

struct PortPath {
    std::uint8_t bus = 0;
    std::vector<std::uint8_t> ports;
    bool operator==(const PortPath&) const = default;
};

PortPath port_path_of(libusb_device* dev) {
    PortPath p;
    p.bus = libusb_get_bus_number(dev);
    std::array<std::uint8_t, 8> ports{};
    const int n = libusb_get_port_numbers(dev, ports.data(), static_cast<int>(ports.size()));
    if (n > 0) p.ports.assign(ports.begin(), ports.begin() + n);
    return p;
}

std::string port_text(const PortPath& p) {
    std::string s = fmt::format("{}", p.bus);
    for (std::size_t i = 0; i < p.ports.size(); ++i)
        s += fmt::format("{}{}", i == 0 ? '-' : '.', p.ports[i]);
    return s;
}

class UsbLink final : public FrameLink {
  public:
    explicit UsbLink(UsbTarget target) : target_(std::move(target)) {}
    ~UsbLink() override { close_handle(); }
    UsbLink(const UsbLink&) = delete;
    UsbLink& operator=(const UsbLink&) = delete;

    Status open(std::string& why) noexcept {
        try {
            close_handle();
            if (!context_) {
                const Status s = make_context(context_, why);
                if (s != Status::kOk) return s;
            }
            libusb_device** list = nullptr;
            const ssize_t n = libusb_get_device_list(context_.get(), &list);
            if (n < 0) {
                why = libusb_text("libusb_get_device_list", static_cast<int>(n));
                return status_of_libusb(static_cast<int>(n));
            }
            libusb_device* chosen = nullptr;
            for (ssize_t i = 0; i < n && chosen == nullptr; ++i) {
                if (matches(list[i])) chosen = list[i];
            }
            Status s = Status::kOk;
            if (chosen == nullptr) {
                why = not_found_text();
                s = Status::kTransportError;
            } else {
                s = open_device(chosen, why);
            }
            libusb_free_device_list(list, 1);
            return s;
        } catch (const std::bad_alloc&) {
            return Status::kNoMemory;
        } catch (...) {
            return Status::kGeneralError;
        }
    }

    Status exchange(std::span<const std::uint8_t> request, std::uint32_t sequence,
                    std::vector<std::uint8_t>& reply, Millis timeout,
                    std::string& why) noexcept override {
        if (handle_ == nullptr) {
            why = still_lost_words(lost_);
            return Status::kTransportError;
        }
        const auto deadline = SteadyClock::now() + timeout;
        std::size_t sent = 0;
        while (sent < request.size()) {
            int done = 0;
            const int rc = libusb_bulk_transfer(
                handle_, usb::kEndpointOut, const_cast<std::uint8_t*>(request.data() + sent),
                static_cast<int>(request.size() - sent), &done, remaining_ms(deadline));
            sent += static_cast<std::size_t>(std::max(done, 0));
            if (rc != LIBUSB_SUCCESS) return failed(rc, "bulk OUT (request)", why);
        }
        return receive_reply(
            pending_, sequence, reply, deadline,
            [this](std::vector<std::uint8_t>& buffer, SteadyClock::time_point until,
                   std::string& text) { return read_some(buffer, until, text); },
            why);
    }

    Status reconnect(std::string& why) noexcept override { return open(why); }
    bool connected() const noexcept override { return handle_ != nullptr; }
    std::string lost_reason() const override { return handle_ ? std::string() : lost_; }
    // Interface 0 is claimed at open (libusb_claim_interface): a second program, or a second
    // handle, cannot open the board while this one has it.
    bool exclusive() const noexcept override { return true; }

  private:
    static unsigned remaining_ms(SteadyClock::time_point deadline) {
        const auto left = std::chrono::ceil<Millis>(deadline - SteadyClock::now()).count();
        return static_cast<unsigned>(
            std::clamp<long long>(left, 1, 1 << 30));  // 0 would be "forever"
    }

    bool matches(libusb_device* dev) const {
        if (!is_board(dev, target_.products)) return false;
        if (target_.any) return true;
        if (port_.bus != 0) return port_path_of(dev) == port_;  // reconnect: the same port
        return libusb_get_bus_number(dev) == target_.bus &&
               libusb_get_device_address(dev) == target_.address;
    }

    std::string not_found_text() const {
        if (port_.bus != 0)
            return fmt::format("no APCI board on USB port {} (still unplugged?)", port_text(port_));
        if (target_.any)
            return "no ADDI-DATA USB board found (vendor 0x15b8 or 0x10e8 with a bulk frame "
                   "interface)";
        return fmt::format(
            "no ADDI-DATA USB board at bus {} address {} (apcictl list names the boards found)",
            target_.bus, target_.address);
    }

    Status open_device(libusb_device* dev, std::string& why) {
        libusb_device_handle* h = nullptr;
        int rc = libusb_open(dev, &h);
        if (rc == LIBUSB_ERROR_NO_DEVICE) {  // gone since the enumeration (being unplugged)
            why = not_found_text();
            return Status::kTransportError;
        }
        if (rc != LIBUSB_SUCCESS) {
            why = libusb_text(fmt::format("open USB device {}:{}", libusb_get_bus_number(dev),
                                          libusb_get_device_address(dev)),
                              rc);
            return status_of_libusb(rc);
        }
        libusb_set_auto_detach_kernel_driver(
            h, 1);  // NOT_SUPPORTED where there is no kernel driver: fine
        rc = libusb_claim_interface(h, usb::kInterfaceNumber);
        if (rc != LIBUSB_SUCCESS) {
            libusb_close(h);
            why = rc == LIBUSB_ERROR_NO_DEVICE ? not_found_text()
                                               : libusb_text("claim interface 0", rc);
            return status_of_libusb(rc);
        }
        handle_ = h;
        port_ = port_path_of(dev);
        name_ =
            fmt::format("usb:{}:{}", libusb_get_bus_number(dev), libusb_get_device_address(dev));
        pending_.clear();
        lost_.clear();
        return Status::kOk;
    }

    Status read_some(std::vector<std::uint8_t>& buffer, SteadyClock::time_point deadline,
                     std::string& why) {
        const std::size_t old = buffer.size();
        buffer.resize(old + kReadChunk);
        int done = 0;
        const int rc =
            libusb_bulk_transfer(handle_, usb::kEndpointIn, buffer.data() + old,
                                 static_cast<int>(kReadChunk), &done, remaining_ms(deadline));
        buffer.resize(old + static_cast<std::size_t>(std::max(done, 0)));
        if (rc == LIBUSB_SUCCESS && done > 0) return Status::kOk;
        if (rc == LIBUSB_SUCCESS) return read_some(buffer, deadline, why);  // zero-length packet
        return failed(rc, "bulk IN (reply)", why);
    }

    Status failed(int rc, std::string_view what, std::string& why) {
        if (rc == LIBUSB_ERROR_NO_DEVICE) {
            lost_ = fmt::format("{} was unplugged (port {})", name_, port_text(port_));
            close_handle();
            why = lost_link_words(lost_, /*once_back=*/true);
            return Status::kTransportError;
        }
        if (rc == LIBUSB_ERROR_TIMEOUT) {
            why = fmt::format("{}: no {} within the timeout", name_, what);
            return Status::kTimeout;
        }
        why = libusb_text(fmt::format("{} {}", name_, what), rc);
        return status_of_libusb(rc);
    }

    void close_handle() noexcept {
        if (handle_ != nullptr) {
            libusb_release_interface(handle_, usb::kInterfaceNumber);
            libusb_close(handle_);
        }
        handle_ = nullptr;
        pending_.clear();
    }

    UsbTarget target_;
    Context context_{nullptr, libusb_exit};
    libusb_device_handle* handle_ = nullptr;
    PortPath port_;  // where the board was found: reconnect looks there
    std::string name_;
    std::vector<std::uint8_t> pending_;
    std::string lost_;
};

}  // namespace

Status open_usb(const DeviceUri& uri, std::unique_ptr<Transport>& out, std::string& why) noexcept {
    return open_with_options(uri, why, [&](const LinkOptions& options) {
        UsbTarget target;
        if (Status s = parse_target(uri, options.rest, target, why); s != Status::kOk) return s;
        return open_framed(std::make_unique<UsbLink>(std::move(target)), "usb:" + uri.target,
                           options.timeout, out, why);
    });
}

Status list_usb(std::vector<FoundDevice>& out, std::string& why) noexcept {
    return guarded([&] {
        UsbTarget any;
        if (Status s = parse_target(DeviceUri{}, {}, any, why); s != Status::kOk) return s;
        Context context{nullptr, libusb_exit};
        if (Status s = make_context(context, why); s != Status::kOk) return s;
        libusb_device** list = nullptr;
        const ssize_t n = libusb_get_device_list(context.get(), &list);
        if (n < 0) {
            why = libusb_text("libusb_get_device_list", static_cast<int>(n));
            return status_of_libusb(static_cast<int>(n));
        }
        for (ssize_t i = 0; i < n; ++i) {
            if (!is_board(list[i], any.products)) continue;
            libusb_device_descriptor desc{};
            libusb_get_device_descriptor(list[i], &desc);
            out.push_back({fmt::format("usb:{}:{}", libusb_get_bus_number(list[i]),
                                       libusb_get_device_address(list[i])),
                           fmt::format("ADDI-DATA USB board {:04x}:{:04x}, port {}", desc.idVendor,
                                       desc.idProduct, port_text(port_path_of(list[i])))});
        }
        libusb_free_device_list(list, 1);
        return Status::kOk;
    });
}

}  // namespace apci
