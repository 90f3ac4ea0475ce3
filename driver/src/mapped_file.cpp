// SPDX-License-Identifier: MIT
#include "mapped_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include "objif/mapping_guard.h"

namespace apci {
namespace {

// A whole mapping, unmapped when destroyed.
struct Mapping {
    void* map;
    std::size_t size;
    Mapping(void* m, std::size_t n) noexcept : map(m), size(n) {}
    ~Mapping() { ::munmap(map, size); }
    Mapping(const Mapping&) = delete;
    Mapping& operator=(const Mapping&) = delete;
};

// The mapping is guarded (objif/mapping_guard.h): a file shrunk under it by
// another process (truncate) becomes this window's error, not a SIGBUS.
class MappedFile final : public objif::mailbox::MappedWindow {
  public:
    MappedFile(void* map, std::size_t map_size, std::size_t skip, std::size_t size, bool can_sleep,
               std::string path)
        : MappedWindow(static_cast<std::uint8_t*>(map) + skip, size, can_sleep),
          mapping_(map, map_size),
          guard_(map, map_size),
          path_(std::move(path)) {}

    objif::Status error() const noexcept override {
        return guard_.lost() ? objif::Status::kTransportError : objif::Status::kOk;
    }
    std::string error_text() const override {
        if (!guard_.lost()) return {};
        return fmt::format(
            "{} was shrunk (truncated) by another process while mapped: the mailbox in it is gone",
            path_);
    }

  private:
    Mapping mapping_;
    objif::MappingGuard guard_;  // after mapping_: unguarded before it is unmapped
    std::string path_;
};

}  // namespace

int map_file(const MapRequest& request, std::unique_ptr<objif::mailbox::Window>& out,
             std::string& what) {
    const int fd = ::open(request.path.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        const int err = errno;
        what = fmt::format("open {}", request.path);
        return err;
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        const int err = errno;
        ::close(fd);
        what = fmt::format("stat {}", request.path);
        return err;
    }
    if (request.check_size && S_ISREG(st.st_mode) &&
        static_cast<std::size_t>(st.st_size) < request.offset + request.size) {
        ::close(fd);
        what = fmt::format("{} holds {} bytes, a mailbox window needs {}", request.path, st.st_size,
                           request.offset + request.size);
        return EINVAL;
    }
    // Map from the page that holds `offset`.
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    const std::size_t start = request.offset / page * page;
    const std::size_t skip = request.offset - start;
    const std::size_t length = skip + request.size;
    void* map =
        ::mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_SHARED, fd, static_cast<off_t>(start));
    const int err = errno;
    ::close(fd);  // the mapping keeps the file
    if (map == MAP_FAILED) {
        what = fmt::format("mmap {}", request.path);
        return err;
    }
    out = std::make_unique<MappedFile>(map, length, skip, request.size, request.can_sleep,
                                       request.path);
    return 0;
}

objif::Status status_of_file_errno(int err) noexcept {
    switch (err) {
        case ENOMEM:
            return objif::Status::kNoMemory;
        case ENAMETOOLONG:
            return objif::Status::kInvalidArgument;
        default:
            return objif::Status::kTransportError;
    }
}

}  // namespace apci
