// SPDX-License-Identifier: MIT
#include "mapped_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

namespace apci {
namespace {

class MappedFile final : public objif::mailbox::MappedWindow {
  public:
    MappedFile(void* map, std::size_t map_size, std::size_t skip, std::size_t size, bool can_sleep)
        : MappedWindow(static_cast<std::uint8_t*>(map) + skip, size, can_sleep),
          map_(map),
          map_size_(map_size) {}
    ~MappedFile() override { ::munmap(map_, map_size_); }
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

  private:
    void* map_;
    std::size_t map_size_;
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
    out = std::make_unique<MappedFile>(map, length, skip, request.size, request.can_sleep);
    return 0;
}

}  // namespace apci
