// SPDX-License-Identifier: MIT
#include "usb_emulator.h"

#include <fmt/format.h>
#include <linux/ioctl.h>
#include <linux/usbdevice_fs.h>
#include <umockdev.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <vector>

#include "objif/usb_layout.h"
#include "rwmos/board.h"
#include "rwmos/frame_server.h"
#include "rwmos/frame_stream.h"

namespace apci_test {

namespace {

// Descriptors as the kernel shows them in sysfs ("descriptors"): device,
// configuration, the vendor interface and its two bulk endpoints (512-byte
// packets, high speed).
std::string descriptors_hex(const UsbBoard::Options& o) {
    return fmt::format(
        "12010002000000{:02x}{:02x}{:02x}{:02x}{:02x}000101020301"  // device
        "0902200001010080fa"       // configuration, 32 bytes in all
        "09040000 02{:02x}000000"  // interface 0
        "0705{:02x}02000200"       // bulk OUT
        "0705{:02x}02000200",      // bulk IN
        0x40, o.vendor & 0xFF, o.vendor >> 8, o.product & 0xFF, o.product >> 8, o.interface_class,
        objif::usb::kEndpointOut, objif::usb::kEndpointIn);
}

std::string without_spaces(std::string s) {
    std::erase(s, ' ');
    return s;
}

constexpr const char* kSysPath = "/sys/devices/usb1/1-2";

}  // namespace

struct UsbBoard::Impl {
    Options options;
    UMockdevTestbed* testbed = nullptr;
    UMockdevIoctlBase* handler = nullptr;

    mutable std::mutex mutex;  // everything below: the handler runs on umockdev's thread
    int address = 5;
    bool plugged = false;
    std::unique_ptr<rwmos::EmulatedBoard> board;
    std::unique_ptr<rwmos::FrameServer> server;
    rwmos::FrameStream stream;
    std::deque<std::uint8_t> replies;           // reply bytes not yet sent on bulk IN
    std::deque<UMockdevIoctlData*> waiting_in;  // bulk IN URBs waiting for bytes
    std::deque<UMockdevIoctlData*> done;        // URBs to reap
    std::vector<std::uint8_t> scratch;
    std::uint64_t served = 0;
    std::string problem;

    std::string devnode() const { return fmt::format("/dev/bus/usb/001/{:03d}", address); }

    void fresh_board() {
        rwmos::BoardConfig config;
        config.option_tc = options.option_tc;
        board = std::make_unique<rwmos::EmulatedBoard>(config);
        server = std::make_unique<rwmos::FrameServer>(*board);
        stream.clear();
        replies.clear();
    }

    void drop_urbs() {
        for (auto* d : waiting_in) umockdev_ioctl_data_unref(d);
        for (auto* d : done) umockdev_ioctl_data_unref(d);
        waiting_in.clear();
        done.clear();
    }

    void plug_in() {
        umockdev_testbed_attach_ioctl(testbed, devnode().c_str(), handler, nullptr);
        const std::string description = fmt::format(
            "P: /devices/usb1/1-2\n"
            "N: bus/usb/001/{0:03d}\n"
            "E: SUBSYSTEM=usb\n"
            "E: DEVTYPE=usb_device\n"
            "E: BUSNUM=001\n"
            "E: DEVNUM={0:03d}\n"
            "E: DEVNAME=/dev/bus/usb/001/{0:03d}\n"
            "A: busnum=1\\n\n"
            "A: devnum={0}\\n\n"
            "A: bConfigurationValue=1\\n\n"
            "A: speed=480\\n\n"
            "H: descriptors={1}\n",
            address, without_spaces(descriptors_hex(options)));
        GError* error = nullptr;
        if (!umockdev_testbed_add_from_string(testbed, description.c_str(), &error)) {
            const std::lock_guard lock(mutex);
            problem = fmt::format("umockdev: {}",
                                  error != nullptr ? error->message : "add_from_string failed");
            if (error != nullptr) g_error_free(error);
        }
    }

    // Moves reply bytes into waiting bulk IN URBs (each gets what fits).
    void fill_in_urbs() {
        while (!replies.empty() && !waiting_in.empty()) {
            UMockdevIoctlData* urb_data = waiting_in.front();
            waiting_in.pop_front();
            auto* urb = reinterpret_cast<usbdevfs_urb*>(urb_data->data);
            const std::size_t n =
                std::min<std::size_t>(replies.size(), static_cast<std::size_t>(urb->buffer_length));
            // The test shares the address space with libusb: the buffer
            // pointer is libusb's own (libusb/tests/umockdev.c does the same).
            std::copy_n(replies.begin(), n, static_cast<std::uint8_t*>(urb->buffer));
            replies.erase(replies.begin(), replies.begin() + static_cast<std::ptrdiff_t>(n));
            urb->actual_length = static_cast<int>(n);
            urb->status = 0;
            done.push_back(urb_data);
        }
    }

    gboolean submit(UMockdevIoctlClient* client, UMockdevIoctlData* arg) {
        UMockdevIoctlData* urb_data =
            umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), nullptr);
        auto* urb = reinterpret_cast<usbdevfs_urb*>(urb_data->data);
        if (urb->type != USBDEVFS_URB_TYPE_BULK || (urb->endpoint != objif::usb::kEndpointOut &&
                                                    urb->endpoint != objif::usb::kEndpointIn)) {
            umockdev_ioctl_data_unref(urb_data);
            umockdev_ioctl_client_complete(client, -1, EINVAL);
            return TRUE;
        }
        if (urb->endpoint == objif::usb::kEndpointIn) {
            waiting_in.push_back(urb_data);
        } else {
            UMockdevIoctlData* buffer = umockdev_ioctl_data_resolve(
                urb_data, offsetof(usbdevfs_urb, buffer), urb->buffer_length, nullptr);
            scratch.clear();
            const auto before = scratch.size();
            const auto result = stream.feed(
                {buffer->data, static_cast<std::size_t>(urb->buffer_length)}, *server, scratch);
            served += result.frames;
            if (options.answers)
                replies.insert(replies.end(), scratch.begin() + static_cast<std::ptrdiff_t>(before),
                               scratch.end());
            if (!result.keep)
                stream.clear();  // garbage: the board resynchronises on the next frame
            umockdev_ioctl_data_unref(buffer);
            urb->actual_length = urb->buffer_length;
            urb->status = 0;
            done.push_back(urb_data);
        }
        fill_in_urbs();
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
    }

    gboolean reap(UMockdevIoctlClient* client, UMockdevIoctlData* arg) {
        if (done.empty()) {
            umockdev_ioctl_client_complete(client, -1, EAGAIN);
            return TRUE;
        }
        UMockdevIoctlData* urb_data = done.front();
        done.pop_front();
        UMockdevIoctlData* slot = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpointer), nullptr);
        umockdev_ioctl_data_set_ptr(slot, 0, urb_data);
        umockdev_ioctl_data_unref(slot);
        umockdev_ioctl_data_unref(urb_data);  // set_ptr holds its own reference
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
    }

    gboolean discard(UMockdevIoctlClient* client, UMockdevIoctlData* arg) {
        const auto address = reinterpret_cast<gulong>(*reinterpret_cast<void**>(arg->data));
        for (auto it = waiting_in.begin(); it != waiting_in.end(); ++it) {
            if ((*it)->client_addr != address) continue;
            auto* urb = reinterpret_cast<usbdevfs_urb*>((*it)->data);
            urb->status = -ENOENT;
            urb->actual_length = 0;
            done.push_back(*it);
            waiting_in.erase(it);
            umockdev_ioctl_client_complete(client, 0, 0);
            return TRUE;
        }
        umockdev_ioctl_client_complete(client, -1, EINVAL);
        return TRUE;
    }

    gboolean handle(UMockdevIoctlClient* client) {
        const std::lock_guard lock(mutex);
        const gulong request = umockdev_ioctl_client_get_request(client);
        UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
        if (!plugged || devnode() != umockdev_ioctl_client_get_devnode(client)) {
            umockdev_ioctl_client_complete(client, -1, ENODEV);
            return TRUE;
        }
        switch (request) {
            case USBDEVFS_GET_CAPABILITIES: {
                UMockdevIoctlData* d =
                    umockdev_ioctl_data_resolve(arg, 0, sizeof(guint32), nullptr);
                *reinterpret_cast<guint32*>(d->data) =
                    USBDEVFS_CAP_BULK_SCATTER_GATHER | USBDEVFS_CAP_BULK_CONTINUATION |
                    USBDEVFS_CAP_NO_PACKET_SIZE_LIM | USBDEVFS_CAP_REAP_AFTER_DISCONNECT |
                    USBDEVFS_CAP_ZERO_PACKET;
                umockdev_ioctl_data_unref(d);
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            }
            case USBDEVFS_CLAIMINTERFACE:
            case USBDEVFS_RELEASEINTERFACE:
            case USBDEVFS_CLEAR_HALT:
            case USBDEVFS_RESET:
            case USBDEVFS_RESETEP:
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            case USBDEVFS_GETDRIVER:  // no kernel driver holds the interface,
            case USBDEVFS_IOCTL:      // so there is none to disconnect (what the kernel answers)
                umockdev_ioctl_client_complete(client, -1, ENODATA);
                return TRUE;
            case USBDEVFS_SUBMITURB:
                return submit(client, arg);
            case USBDEVFS_REAPURB:
            case USBDEVFS_REAPURBNDELAY:
                return reap(client, arg);
            case USBDEVFS_DISCARDURB:
                return discard(client, arg);
            default:
                umockdev_ioctl_client_complete(client, -1, ENOTTY);
                return TRUE;
        }
    }
};

namespace {
gboolean on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer impl) {
    return static_cast<UsbBoard::Impl*>(impl)->handle(client);
}
}  // namespace

bool UsbBoard::available() {
    // umockdev_in_mock_environment() only answers true once a testbed
    // exists (it looks at /sys), and caches its first answer: ask the
    // environment instead.
    const char* preload = std::getenv("LD_PRELOAD");
    return preload != nullptr && std::strstr(preload, "libumockdev-preload") != nullptr;
}

UsbBoard::UsbBoard(const Options& options) : impl_(std::make_unique<Impl>()) {
    impl_->options = options;
    impl_->testbed = umockdev_testbed_new();
    impl_->handler = umockdev_ioctl_base_new();
    g_signal_connect_after(impl_->handler, "handle-ioctl", G_CALLBACK(on_ioctl), impl_.get());
    {
        const std::lock_guard lock(impl_->mutex);
        impl_->fresh_board();
        impl_->plugged = true;
    }
    impl_->plug_in();
}

UsbBoard::~UsbBoard() {
    g_clear_object(&impl_->handler);
    g_clear_object(&impl_->testbed);  // removes the testbed's directory
    const std::lock_guard lock(impl_->mutex);
    impl_->drop_urbs();
}

std::string UsbBoard::uri() const {
    return fmt::format("usb:{}:{}", bus(), address());
}
int UsbBoard::bus() const {
    return 1;
}
int UsbBoard::address() const {
    const std::lock_guard lock(impl_->mutex);
    return impl_->address;
}

void UsbBoard::unplug() {
    {
        const std::lock_guard lock(impl_->mutex);
        impl_->plugged = false;
        impl_->drop_urbs();
    }
    umockdev_testbed_remove_device(impl_->testbed, kSysPath);
}

void UsbBoard::replug() {
    {
        const std::lock_guard lock(impl_->mutex);
        ++impl_->address;  // a re-plugged device gets a new address, on the same port
        impl_->fresh_board();
        impl_->plugged = true;
    }
    impl_->plug_in();
}

std::string UsbBoard::problem() const {
    const std::lock_guard lock(impl_->mutex);
    return impl_->problem;
}

std::uint64_t UsbBoard::served() const {
    const std::lock_guard lock(impl_->mutex);
    return impl_->served;
}

}  // namespace apci_test
