// SPDX-License-Identifier: MIT
// The PCI transport ("pci:DOMAIN:BUS:DEV.FN"): the board's dual-port RAM
// mailbox (docs/dpram.md) reached through one of its BARs, with the same
// mailbox code as shm: (MailboxLink). The BAR is found through sysfs:
//  - a memory BAR is mapped from .../resourceN;
//  - an I/O BAR is read and written 32 bits at a time with pread/pwrite on
//    .../resourceN (the only access sysfs offers for I/O regions);
//  - with ?uio the BAR is mapped from the UIO device bound to the board
//    (/dev/uioN, map index ?uio-map=M).
// Options: bar=N (default 0), offset=BYTES (window offset inside the BAR,
// default 0), uio, uio-map=M, timeout=MS. $APCI_SYSFS_ROOT and
// $APCI_DEV_ROOT replace /sys and /dev (tests use a fake tree).
// Blocking: as MailboxLink; device memory cannot sleep on a futex, so a
// waiting host polls every 20 us after its spin. Threading: one caller at a
// time. errno becomes a status in status_of_file_errno() (mapped_file.h) and
// nowhere else.
#include <dirent.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <new>
#include <sstream>

#include "mailbox_link.h"
#include "mapped_file.h"
#include "objif/byte_order.h"
#include "objif/usb_layout.h"
#include "guarded.h"

namespace apci {
namespace {

namespace mb = objif::mailbox;
using objif::Status;

// Flags of a sysfs `resource` line (include/linux/ioport.h).
constexpr std::uint64_t kIoResourceIo = 0x100;
constexpr std::uint64_t kIoResourceMem = 0x200;

std::string env_or(const char* name, const char* fallback) {
    const char* v = std::getenv(name);
    return v != nullptr && *v != '\0' ? v : fallback;
}
std::string sysfs_root() {
    return env_or("APCI_SYSFS_ROOT", "/sys");
}
std::string dev_root() {
    return env_or("APCI_DEV_ROOT", "/dev");
}
std::string pci_devices_dir() {
    return sysfs_root() + "/bus/pci/devices";
}

bool read_first_line(const std::string& path, std::string& line) {
    std::ifstream f(path);
    return static_cast<bool>(std::getline(f, line));
}

// "0x15b8" in a sysfs id file.
bool read_id(const std::string& path, std::uint32_t& id) {
    std::string line;
    return read_first_line(path, line) && parse_unsigned(line, 0xFFFF, id);
}

bool addi_data_vendor(std::uint32_t vendor) {
    return std::find(objif::usb::kVendorIds.begin(), objif::usb::kVendorIds.end(), vendor) !=
           objif::usb::kVendorIds.end();
}

// "DDDD:BB:DD.F", hexadecimal, as sysfs names PCI functions.
bool valid_pci_address(std::string_view a) {
    if (a.size() != 12 || a[4] != ':' || a[7] != ':' || a[10] != '.') return false;
    for (std::size_t i : {0u, 1u, 2u, 3u, 5u, 6u, 8u, 9u})
        if (!std::isxdigit(static_cast<unsigned char>(a[i]))) return false;
    return a[11] >= '0' && a[11] <= '7';
}

struct Bar {
    std::uint64_t start = 0, end = 0, flags = 0;
    std::uint64_t size() const { return start == 0 && end == 0 ? 0 : end - start + 1; }
};

bool read_bar(const std::string& device_dir, unsigned index, Bar& bar) {
    std::ifstream f(device_dir + "/resource");
    std::string line;
    for (unsigned i = 0; i <= index; ++i)
        if (!std::getline(f, line)) return false;
    std::istringstream in(line);
    std::string a, b, c;
    if (!(in >> a >> b >> c)) return false;
    bar.start = std::strtoull(a.c_str(), nullptr, 16);
    bar.end = std::strtoull(b.c_str(), nullptr, 16);
    bar.flags = std::strtoull(c.c_str(), nullptr, 16);
    return true;
}

// An I/O BAR through sysfs: 32-bit pread/pwrite at aligned offsets. The host
// lock's compare-and-swap is made atomic among the hosts of this machine
// with a byte-range lock on that word (the board never touches it).
class IoPortWindow final : public mb::Window {
  public:
    IoPortWindow(int fd, std::size_t base, std::string path)
        : fd_(fd), base_(base), path_(std::move(path)) {}
    ~IoPortWindow() override { ::close(fd_); }
    IoPortWindow(const IoPortWindow&) = delete;
    IoPortWindow& operator=(const IoPortWindow&) = delete;

    std::uint32_t load(std::size_t offset) noexcept override {
        std::uint32_t v = 0;
        if (::pread(fd_, &v, 4, static_cast<off_t>(base_ + offset)) != 4)
            note(errno, "read", offset);
        return v;
    }
    void store(std::size_t offset, std::uint32_t value) noexcept override {
        if (::pwrite(fd_, &value, 4, static_cast<off_t>(base_ + offset)) != 4)
            note(errno, "write", offset);
    }
    bool compare_exchange(std::size_t offset, std::uint32_t expected,
                          std::uint32_t desired) noexcept override {
        if (!lock_word(offset, F_WRLCK)) return false;
        const bool equal = load(offset) == expected;
        if (equal) store(offset, desired);
        lock_word(offset, F_UNLCK);
        return equal && error_ == 0;
    }
    // Frame bytes: the kernel gives (and takes) an I/O BAR's word as the value of the
    // little-endian bus word in the host's order (ioread32/iowrite32), so the board's bytes are
    // that value stored little-endian, on any host (docs/transports.md).
    void read(std::size_t offset, std::uint8_t* out, std::size_t size) noexcept override {
        for (std::size_t i = 0; i < size; i += 4) {
            std::uint8_t word[4];
            objif::store_little<std::uint32_t>(word, load(offset + i));
            std::memcpy(out + i, word, std::min<std::size_t>(4, size - i));
        }
    }
    void write(std::size_t offset, const std::uint8_t* in, std::size_t size) noexcept override {
        for (std::size_t i = 0; i < size; i += 4) {
            std::uint8_t word[4] = {0, 0, 0, 0};
            std::memcpy(word, in + i, std::min<std::size_t>(4, size - i));
            store(offset + i, objif::load_little<std::uint32_t>(word));
        }
    }
    Status error() const noexcept override {
        return error_ == 0 ? Status::kOk : status_of_file_errno(error_);
    }
    std::string error_text() const override { return error_text_; }

  private:
    // An open-file-description lock on the word's 4 bytes: excludes the
    // other hosts of this machine, threads included.
    bool lock_word(std::size_t offset, short type) noexcept {
        struct flock l {};
        l.l_type = type;
        l.l_whence = SEEK_SET;
        l.l_start = static_cast<off_t>(base_ + offset);
        l.l_len = 4;
        while (::fcntl(fd_, F_OFD_SETLKW, &l) != 0) {
            if (errno == EINTR) continue;
            note(errno, "lock", offset);
            return false;
        }
        return true;
    }

    void note(int err, std::string_view what, std::size_t offset) noexcept {
        if (error_ != 0) return;  // keep the first
        error_ = err == 0 ? EIO : err;
        try {
            error_text_ = fmt::format("{} {} at offset {:#x}: {}", what, path_, base_ + offset,
                                      std::strerror(error_));
        } catch (...) {
        }
    }

    int fd_;
    std::size_t base_;
    std::string path_;
    int error_ = 0;
    std::string error_text_;
};

struct PciTarget {
    std::string address;  // "0000:03:00.0"
    unsigned bar = 0;
    std::size_t offset = 0;
    bool uio = false;
    unsigned uio_map = 0;
};

Status parse_pci_options(const std::vector<std::string>& options, PciTarget& t, std::string& why) {
    for (const auto& o : options) {
        const auto eq = o.find('=');
        const std::string_view key = std::string_view(o).substr(0, eq);
        const std::string_view value =
            eq == std::string::npos ? std::string_view() : std::string_view(o).substr(eq + 1);
        std::uint32_t v = 0;
        if (key == "uio" && eq == std::string::npos) {
            t.uio = true;
        } else if (key == "bar" && parse_unsigned(value, 5, v)) {
            t.bar = v;
        } else if (key == "offset" && parse_unsigned(value, 0x7FFFFFFF, v) && v % 4 == 0) {
            t.offset = v;
        } else if (key == "uio-map" && parse_unsigned(value, 4, v)) {
            t.uio = true;
            t.uio_map = v;
        } else {
            why = fmt::format(
                "pci: option '{}' is not one of bar=0..5, offset=BYTES (a multiple "
                "of 4), uio, uio-map=0..4, timeout=MS",
                o);
            return Status::kInvalidArgument;
        }
    }
    return Status::kOk;
}

std::string mapped_error(int err, const std::string& what) {
    return err == EINVAL ? what : fmt::format("{}: {}", what, std::strerror(err));
}

// The UIO device bound to the board: .../DEVICE/uio/uioN.
Status find_uio(const std::string& device_dir, std::string& uio, std::string& why) {
    std::unique_ptr<DIR, int (*)(DIR*)> d(::opendir((device_dir + "/uio").c_str()), ::closedir);
    if (d) {
        while (const dirent* e = ::readdir(d.get())) {
            if (std::string_view(e->d_name).starts_with("uio")) {
                uio = e->d_name;
                return Status::kOk;
            }
        }
    }
    why = fmt::format(
        "no UIO device is bound to {} (load uio_pci_generic and bind the board "
        "to it, or drop the uio option)",
        device_dir);
    return Status::kTransportError;
}

Status open_window(const PciTarget& t, std::unique_ptr<mb::Window>& out, std::string& why) {
    const std::string dir = pci_devices_dir() + "/" + t.address;
    std::uint32_t vendor = 0;
    if (!read_id(dir + "/vendor", vendor)) {
        why = fmt::format("no PCI function {} ({} is missing)", t.address, dir + "/vendor");
        return Status::kTransportError;
    }
    if (!addi_data_vendor(vendor)) {
        why = fmt::format("PCI function {} has vendor {:#06x}, not ADDI-DATA (0x15b8, 0x10e8)",
                          t.address, vendor);
        return Status::kInvalidArgument;
    }
    Bar bar;
    if (!read_bar(dir, t.bar, bar) || bar.size() == 0) {
        why = fmt::format("PCI function {} has no BAR {}", t.address, t.bar);
        return Status::kTransportError;
    }
    if (bar.size() < t.offset + mb::kWindowSize) {
        why = fmt::format(
            "BAR {} of {} holds {:#x} bytes; the mailbox window needs {:#x} from offset {:#x}",
            t.bar, t.address, bar.size(), mb::kWindowSize, t.offset);
        return Status::kTransportError;
    }
    std::string what;
    if (t.uio) {
        std::string uio;
        if (Status s = find_uio(dir, uio, why); s != Status::kOk) return s;
        MapRequest request;
        request.path = dev_root() + "/" + uio;
        // UIO selects map M with an mmap offset of M pages.
        request.offset = t.uio_map * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE)) + t.offset;
        request.check_size = false;
        const int err = map_file(request, out, what);
        if (err != 0) why = mapped_error(err, what);
        return err == 0 ? Status::kOk : status_of_file_errno(err);
    }
    const std::string resource = fmt::format("{}/resource{}", dir, t.bar);
    if ((bar.flags & kIoResourceIo) != 0) {
        const int fd = ::open(resource.c_str(), O_RDWR | O_CLOEXEC);
        if (fd < 0) {
            const int err = errno;
            why = fmt::format("open {}: {}", resource, std::strerror(err));
            return status_of_file_errno(err);
        }
        out = std::make_unique<IoPortWindow>(fd, t.offset, resource);
        return Status::kOk;
    }
    if ((bar.flags & kIoResourceMem) == 0) {
        why = fmt::format("BAR {} of {} is neither memory nor I/O (flags {:#x})", t.bar, t.address,
                          bar.flags);
        return Status::kTransportError;
    }
    MapRequest request;
    request.path = resource;
    request.offset = t.offset;
    const int err = map_file(request, out, what);
    if (err != 0) why = mapped_error(err, what);
    return err == 0 ? Status::kOk : status_of_file_errno(err);
}

}  // namespace

Status open_pci(const DeviceUri& uri, std::unique_ptr<Transport>& out, std::string& why) noexcept {
    return open_with_options(uri, why, [&](const LinkOptions& options) {
        PciTarget target;
        target.address = uri.target;
        if (!valid_pci_address(target.address)) {
            why = fmt::format(
                "pci:{}: expected pci:DOMAIN:BUS:DEV.FN in hexadecimal, e.g. "
                "pci:0000:03:00.0 (apcictl list names the boards found)",
                uri.target);
            return Status::kInvalidArgument;
        }
        if (Status s = parse_pci_options(options.rest, target, why); s != Status::kOk) return s;
        const std::string name = "pci:" + target.address;
        OpenWindow open = [target](std::unique_ptr<mb::Window>& window, std::string& text) {
            return open_window(target, window, text);
        };
        return open_framed(std::make_unique<MailboxLink>(std::move(open), name), name,
                           options.timeout, out, why);
    });
}

Status list_pci(std::vector<FoundDevice>& out, std::string& why) noexcept {
    return guarded([&] {
        const std::string root = pci_devices_dir();
        std::unique_ptr<DIR, int (*)(DIR*)> d(::opendir(root.c_str()), ::closedir);
        if (!d) {
            if (errno == ENOENT) return Status::kOk;  // no PCI bus here
            const int err = errno;
            why = fmt::format("{}: {}", root, std::strerror(err));
            return status_of_file_errno(err);
        }
        std::vector<FoundDevice> found;
        while (const dirent* e = ::readdir(d.get())) {
            const std::string address = e->d_name;
            if (!valid_pci_address(address)) continue;
            std::uint32_t vendor = 0, device = 0;
            std::string dir = root;
            dir += '/';
            dir += address;
            if (!read_id(dir + "/vendor", vendor) || !addi_data_vendor(vendor)) continue;
            read_id(dir + "/device", device);
            Bar bar;
            std::string bar_text = "BAR 0 not assigned";
            if (read_bar(dir, 0, bar) && bar.size() != 0)
                bar_text =
                    fmt::format("BAR 0 {} {:#x} bytes",
                                (bar.flags & kIoResourceIo) != 0 ? "I/O" : "memory", bar.size());
            found.push_back({"pci:" + address, fmt::format("ADDI-DATA PCI board {:04x}:{:04x}, {}",
                                                           vendor, device, bar_text)});
        }
        std::sort(found.begin(), found.end(), [](auto& a, auto& b) { return a.uri < b.uri; });
        out.insert(out.end(), found.begin(), found.end());
        return Status::kOk;
    });
}

}  // namespace apci
