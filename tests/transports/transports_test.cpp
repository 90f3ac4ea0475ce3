// SPDX-License-Identifier: MIT
// The remote transports through the public C API: URI and option errors,
// connection failures, timeouts, late replies, lost links and reconnect, and
// board listing. What the transports have in common with the embedded
// emulator is the conformance suite's (tests/conformance).
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "apci/apci.h"
#include "apci/apci.hpp"
#include "daemon.h"
#include "fake_sysfs.h"
#include "objif/frame.h"
#include "objif/mailbox.h"
#include "text.h"

namespace {

using test_support::contains;
using apci_test::Daemon;
using apci_test::DaemonOptions;
using apci_test::FakePciSysfs;
using apci_test::TempDir;
using namespace std::chrono_literals;

apci_object_descriptor axis_count() {
    return {1000, 0, 3, 0, 0};
}

std::string open_error(const std::string& uri, apci_status expected) {
    apci_board* b = reinterpret_cast<apci_board*>(0x1);
    const apci_status s = apci_open(uri.c_str(), &b);
    EXPECT_EQ(s, expected) << uri << ": " << apci_last_error(nullptr);
    EXPECT_EQ(b, nullptr);
    apci_close(b);
    return apci_last_error(nullptr);
}

// A file of `size` zero bytes.
void make_file(const std::string& path, std::uintmax_t size) {
    { std::ofstream created(path); }
    std::filesystem::resize_file(path, size);
}

// A socket server whose replies the test scripts: it reads each request frame
// and hands it to `answer`, which writes whatever bytes it likes.
class ScriptedServer {
  public:
    using Answer = std::function<void(int fd, const objif::Frame& request, int index)>;

    // `greeting_version`: the frame version its greeting says (another release's daemon).
    explicit ScriptedServer(Answer answer, std::uint16_t greeting_version = objif::kFrameVersion)
        : answer_(std::move(answer)), greeting_version_(greeting_version) {
        listen_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        std::strncpy(addr.sun_path, path().c_str(), sizeof addr.sun_path - 1);
        EXPECT_EQ(::bind(listen_, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
        EXPECT_EQ(::listen(listen_, 4), 0);
        thread_ = std::thread([this] { run(); });
    }
    ~ScriptedServer() {
        stop_ = true;
        ::shutdown(listen_, SHUT_RDWR);
        thread_.join();
        ::close(listen_);
    }
    std::string path() const { return dir_.file("scripted.sock"); }
    std::string uri(const std::string& options = "") const { return "unix:" + path() + options; }

    static void send_frame(int fd, std::uint16_t opcode, std::uint32_t sequence,
                           const std::vector<std::uint8_t>& payload) {
        std::vector<std::uint8_t> out;
        objif::encode_frame(opcode, sequence, payload, out);
        (void)!::send(fd, out.data(), out.size(), MSG_NOSIGNAL);
    }
    static void send_read_reply(int fd, std::uint32_t sequence, std::int32_t value) {
        std::vector<std::uint8_t> payload;
        objif::encode(objif::ReadReply{objif::Status::kOk, 1, objif::Value::of_int(value)},
                      payload);
        send_frame(fd, 0x8001, sequence, payload);
    }

    // What rwmos-emu sends first on every connection (docs/wire-frame.md "Notices").
    // A header of another version is refused before its CRC is looked at.
    static void greet(int fd, std::uint16_t version = objif::kFrameVersion) {
        std::vector<std::uint8_t> payload;
        objif::encode(objif::Notice{objif::Status::kOk, std::string(objif::kDaemonGreeting)},
                      payload);
        std::vector<std::uint8_t> out;
        objif::encode_frame(0xFFFE, 0, payload, out);
        out[4] = static_cast<std::uint8_t>(version & 0xFF);
        out[5] = static_cast<std::uint8_t>(version >> 8);
        (void)!::send(fd, out.data(), out.size(), MSG_NOSIGNAL);
    }

  private:
    void run() {
        while (!stop_) {
            const int fd = ::accept(listen_, nullptr, nullptr);
            if (fd < 0) return;
            greet(fd, greeting_version_);
            std::vector<std::uint8_t> pending;
            int index = 0;
            for (;;) {
                std::uint8_t buf[4096];
                const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
                if (n <= 0) break;
                pending.insert(pending.end(), buf, buf + n);
                objif::Frame f;
                std::size_t used = 0;
                bool more = false;
                while (objif::decode_frame(pending, f, used, more) == objif::FrameError::kNone) {
                    pending.erase(pending.begin(),
                                  pending.begin() + static_cast<std::ptrdiff_t>(used));
                    answer_(fd, f, index++);
                }
            }
            ::close(fd);
        }
    }

    TempDir dir_;
    Answer answer_;
    std::uint16_t greeting_version_;
    int listen_ = -1;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

// A daemon of another release greets in its frame version: the open is refused naming both
// versions, and listing the daemons would show the same words.
TEST(UnixTransport, ADaemonOfAnotherFrameVersionIsRefusedNamingBothVersions) {
    for (const std::uint16_t version : {std::uint16_t(objif::kFrameVersion - 1),
                                        std::uint16_t(objif::kFrameVersion + 1)}) {
        ScriptedServer server([](int, const objif::Frame&, int) {}, version);
        const std::string error = open_error(server.uri(), APCI_TRANSPORT_ERROR);
        EXPECT_TRUE(contains(error, fmt::format("speaks wire-frame version {}, this library {}",
                                                version, objif::kFrameVersion)))
            << error;
        EXPECT_FALSE(contains(error, "not an rwmos-emu daemon")) << error;
    }
}

// ---- Device URIs and options

TEST(TransportUri, UnixWithoutPathIsInvalid) {
    EXPECT_TRUE(
        contains(open_error("unix:", APCI_INVALID_ARGUMENT), "needs the daemon's socket path"));
}

TEST(TransportUri, UnknownOptionIsInvalid) {
    EXPECT_TRUE(
        contains(open_error("unix:/tmp/x.sock?colour=blue", APCI_INVALID_ARGUMENT), "colour=blue"));
    EXPECT_TRUE(
        contains(open_error("shm:/tmp/x?colour=blue", APCI_INVALID_ARGUMENT), "colour=blue"));
}

TEST(TransportUri, TimeoutOptionMustBeMilliseconds) {
    for (const char* bad : {"timeout=0", "timeout=-5", "timeout=1s", "timeout=3600001", "timeout="})
        EXPECT_TRUE(
            contains(open_error(std::string("unix:/tmp/x.sock?") + bad, APCI_INVALID_ARGUMENT),
                     "milliseconds"))
            << bad;
}

TEST(TransportUri, SocketPathTooLongIsInvalid) {
    EXPECT_TRUE(
        contains(open_error("unix:/" + std::string(200, 'a'), APCI_INVALID_ARGUMENT), "too long"));
}

TEST(TransportUri, PciAddressMustBeDomainBusDevFn) {
    for (const char* bad :
         {"pci:", "pci:03:00.0", "pci:0000:03:00", "pci:0000:03:00.8", "pci:000g:03:00.0"})
        EXPECT_TRUE(contains(open_error(bad, APCI_INVALID_ARGUMENT), "pci:DOMAIN:BUS:DEV.FN"))
            << bad;
}

TEST(TransportUri, PciOptionsAreChecked) {
    for (const char* bad : {"?bar=6", "?offset=3", "?uio-map=9", "?speed=fast"})
        EXPECT_TRUE(contains(
            open_error(std::string("pci:0000:01:00.0") + bad, APCI_INVALID_ARGUMENT), "bar=0..5"))
            << bad;
}

// ---- unix:

TEST(UnixTransport, NoDaemonIsATransportErrorNamingThePath) {
    TempDir dir;
    const std::string text = open_error("unix:" + dir.file("none.sock"), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(text, dir.file("none.sock"))) << text;
    EXPECT_TRUE(contains(text, "No such file or directory")) << text;
    EXPECT_TRUE(contains(text, "is rwmos-emu running?")) << text;
}

TEST(UnixTransport, UnansweredRequestTimesOutAfterTheTimeout) {
    ScriptedServer server([](int, const objif::Frame&, int) {});  // never answers
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(server.uri("?timeout=150").c_str(), &b), APCI_OK)
        << apci_last_error(nullptr);
    std::uint32_t ms = 0;
    ASSERT_EQ(apci_get_timeout(b, &ms), APCI_OK);
    EXPECT_EQ(ms, 150u) << "the URI option sets the timeout";
    auto o = axis_count();
    std::int32_t v = 0;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_TIMEOUT);
    const auto took = std::chrono::steady_clock::now() - t0;
    EXPECT_GE(took, 150ms);
    EXPECT_LT(took, 2000ms);
    EXPECT_TRUE(contains(apci_last_error(b), "Timeout")) << apci_last_error(b);
    EXPECT_EQ(apci_is_connected(b), 1) << "a timeout does not lose the link";
    apci_close(b);
}

TEST(UnixTransport, LateReplyToATimedOutRequestIsDroppedNotTakenForTheNext) {
    ScriptedServer server([](int fd, const objif::Frame& request, int index) {
        if (index == 0) {
            std::this_thread::sleep_for(300ms);  // answers the first request too late
            ScriptedServer::send_read_reply(fd, request.sequence, 111);
        } else {
            ScriptedServer::send_read_reply(fd, request.sequence, 222);
        }
    });
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(server.uri("?timeout=100").c_str(), &b), APCI_OK);
    auto o = axis_count();
    std::int32_t v = 0;
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_TIMEOUT);
    ASSERT_EQ(apci_set_timeout(b, 2000), APCI_OK);
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(v, 222) << "the late reply (111) belongs to the request that timed out";
    apci_close(b);
}

TEST(UnixTransport, ReplyThatIsNotAFrameIsATransportError) {
    ScriptedServer server([](int fd, const objif::Frame&, int) {
        const char junk[] = "HTTP/1.1 400 Bad Request\r\n\r\n";
        (void)!::send(fd, junk, sizeof junk - 1, MSG_NOSIGNAL);
    });
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(server.uri().c_str(), &b), APCI_OK);
    auto o = axis_count();
    std::int32_t v = 0;
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(apci_last_error(b), "not a frame")) << apci_last_error(b);
    apci_close(b);
}

TEST(UnixTransport, ReplyWithTheWrongOpcodeIsABadFrame) {
    ScriptedServer server([](int fd, const objif::Frame& request, int) {
        std::vector<std::uint8_t> payload;
        objif::encode(objif::WriteReply{objif::Status::kOk, 1}, payload);
        ScriptedServer::send_frame(fd, 0x8002, request.sequence,
                                   payload);  // a write reply to a read
    });
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(server.uri().c_str(), &b), APCI_OK);
    auto o = axis_count();
    std::int32_t v = -1;
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_BAD_FRAME);
    EXPECT_EQ(v, -1) << "a failed call changes no output";
    EXPECT_TRUE(contains(apci_last_error(b), "answered ObjectWriteReply to ObjectRead"))
        << apci_last_error(b);
    apci_close(b);
}

TEST(UnixTransport, ErrorReplyBecomesItsStatusWithTheReason) {
    ScriptedServer server([](int fd, const objif::Frame& request, int) {
        std::vector<std::uint8_t> payload;
        objif::encode(objif::ErrorReply{objif::Status::kBadFrame, objif::FrameError::kBadCrc},
                      payload);
        ScriptedServer::send_frame(fd, 0xFFFF, request.sequence, payload);
    });
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(server.uri().c_str(), &b), APCI_OK);
    auto o = axis_count();
    std::int32_t v = 0;
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_BAD_FRAME);
    EXPECT_TRUE(contains(apci_last_error(b), "refused the ObjectRead frame: bad CRC"))
        << apci_last_error(b);
    apci_close(b);
}

TEST(UnixTransport, DaemonStoppingLosesTheLinkUntilReconnect) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
    auto o = axis_count();
    std::int32_t v = 0;
    ASSERT_EQ(apci_read_int(b, &o, &v), APCI_OK);
    EXPECT_EQ(apci_link_lost(b, nullptr, 0), 0u) << "the link works";
    ASSERT_EQ(d->stop(), 0);

    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(apci_last_error(b), "closed the connection")) << apci_last_error(b);
    EXPECT_EQ(apci_is_connected(b), 0);
    // What ended the link, alone; the call's words give it, then the C API's hint.
    char cause[512];
    const std::size_t n = apci_link_lost(b, cause, sizeof cause);
    ASSERT_GT(n, 0u);
    ASSERT_LT(n, sizeof cause);
    EXPECT_EQ(std::string(cause), "daemon " + d->socket_path() +
                                      " closed the connection: shutting down (SIGTERM)");
    EXPECT_TRUE(contains(apci_last_error(b),
                         std::string(cause) + "; apci_reconnect() reopens the link"))
        << apci_last_error(b);
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(apci_last_error(b), "link lost: " + std::string(cause) +
                                                 "; apci_reconnect() reopens the link"))
        << apci_last_error(b);
    EXPECT_EQ(apci_link_lost(b, nullptr, 0), n) << "the same cause for a later call";
    // Written as snprintf writes: cut to the room given, NUL-terminated, the whole length
    // returned; no room, nothing written.
    char small[8];
    std::memset(small, 'x', sizeof small);
    EXPECT_EQ(apci_link_lost(b, small, 5), n);
    EXPECT_EQ(std::string(small), "daem");
    EXPECT_EQ(small[5], 'x');
    small[0] = 'x';
    EXPECT_EQ(apci_link_lost(b, small, 0), n);
    EXPECT_EQ(small[0], 'x');
    EXPECT_EQ(apci_link_lost(nullptr, small, sizeof small), 0u);
    EXPECT_EQ(small[0], '\0') << "no board: an empty text";
    EXPECT_EQ(apci_reconnect(b), APCI_TRANSPORT_ERROR) << "nothing listens yet";
    EXPECT_TRUE(contains(apci_last_error(b), "reconnect")) << apci_last_error(b);

    // A daemon on the same path again.
    DaemonOptions again;
    again.socket_path = d->socket_path();
    auto d2 = Daemon::start(again);
    ASSERT_NE(d2, nullptr);
    ASSERT_EQ(apci_reconnect(b), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(apci_is_connected(b), 1);
    EXPECT_EQ(apci_link_lost(b, cause, sizeof cause), 0u) << "opened again";
    EXPECT_EQ(cause[0], '\0');
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_STALE_HANDLE)
        << "a new board: the old handle means nothing";
    o.handle = 0;
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(v, 8);
    apci_close(b);
}

TEST(UnixTransport, ManyBoardsOnOneDaemonShareOneBoardState) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    apci_board* a = nullptr;
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &a), APCI_OK);
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
    apci_object_descriptor angle{1300, 0, 20, 0, 0};
    ASSERT_EQ(apci_write_double(a, &angle, 33.0), APCI_OK);
    angle.handle = 0;
    double v = 0;
    ASSERT_EQ(apci_read_double(b, &angle, &v), APCI_OK);
    EXPECT_EQ(v, 33.0);
    apci_close(a);
    apci_close(b);
}

// ---- shm:

TEST(ShmTransport, MissingFileIsATransportErrorNamingIt) {
    TempDir dir;
    const std::string text = open_error("shm:" + dir.file("nothing"), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(text, dir.file("nothing"))) << text;
}

TEST(ShmTransport, FileTooShortIsRefused) {
    TempDir dir;
    std::ofstream(dir.file("short")) << "hello";
    EXPECT_TRUE(contains(open_error("shm:" + dir.file("short"), APCI_TRANSPORT_ERROR),
                         "a mailbox window needs"));
}

TEST(ShmTransport, FileThatIsNotAMailboxIsRefused) {
    TempDir dir;
    make_file(dir.file("zeros"), objif::mailbox::kWindowSize);
    EXPECT_TRUE(
        contains(open_error("shm:" + dir.file("zeros"), APCI_TRANSPORT_ERROR), "no mailbox here"));
}

TEST(ShmTransport, DaemonStoppingLosesTheLinkAndReconnectFindsTheNewOne) {
    DaemonOptions o;
    o.socket = false;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->shm_uri().c_str(), &b), APCI_OK);
    auto obj = axis_count();
    std::int32_t v = 0;
    ASSERT_EQ(apci_read_int(b, &obj, &v), APCI_OK);
    ASSERT_EQ(d->stop(), 0);

    EXPECT_EQ(apci_read_int(b, &obj, &v), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(apci_last_error(b), "apci_reconnect()")) << apci_last_error(b);
    EXPECT_EQ(apci_is_connected(b), 0);
    {
        std::string cause(apci_link_lost(b, nullptr, 0), '\0');
        ASSERT_EQ(apci_link_lost(b, cause.data(), cause.size() + 1), cause.size());
        EXPECT_FALSE(cause.empty());
        EXPECT_FALSE(contains(cause, "apci_reconnect")) << cause;
        EXPECT_TRUE(contains(apci_last_error(b), cause + "; apci_reconnect() reopens the link"))
            << apci_last_error(b);
    }

    DaemonOptions again;
    again.socket = false;
    again.shm = true;
    again.shm_path = d->shm_path();
    auto d2 = Daemon::start(again);
    ASSERT_NE(d2, nullptr);
    ASSERT_TRUE(apci_test::eventually([&] { return apci_reconnect(b) == APCI_OK; }))
        << apci_last_error(b);
    obj.handle = 0;  // a new board
    EXPECT_EQ(apci_read_int(b, &obj, &v), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(v, 8);
    apci_close(b);
}

TEST(ShmTransport, MailboxNobodyServesTimesOut) {
    TempDir dir;
    const std::string path = dir.file("dpram");
    {  // A mailbox marked serving whose board never answers (a hung firmware).
        std::vector<std::uint32_t> words(objif::mailbox::kWindowSize / 4);
        objif::mailbox::MappedWindow w(words.data(), objif::mailbox::kWindowSize, false);
        objif::mailbox::format(w);
        objif::mailbox::set_board_state(w, objif::mailbox::BoardState::kServing);
        std::ofstream(path, std::ios::binary)
            .write(reinterpret_cast<const char*>(words.data()),
                   static_cast<std::streamsize>(objif::mailbox::kWindowSize));
    }
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(("shm:" + path + "?timeout=100").c_str(), &b), APCI_OK)
        << apci_last_error(nullptr);
    auto o = axis_count();
    std::int32_t v = 0;
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_TIMEOUT);
    EXPECT_TRUE(contains(apci_last_error(b), "no reply from the board within 100 ms"))
        << apci_last_error(b);
    apci_close(b);
}

// ---- pci: (a fake sysfs tree; the BAR is the daemon's dual-port RAM file)

class PciTransport : public ::testing::Test {
  protected:
    void SetUp() override {
        DaemonOptions o;
        o.socket = false;
        o.shm = true;
        daemon_ = Daemon::start(o);
        ASSERT_NE(daemon_, nullptr);
    }
    std::unique_ptr<Daemon> daemon_;
};

TEST_F(PciTransport, MemoryBarIsMapped) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kMemory);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(sysfs.uri().c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    auto o = axis_count();
    std::int32_t v = 0;
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(v, 8);
    apci_close(b);
}

TEST_F(PciTransport, IoBarIsReadAndWrittenWordByWord) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kIo);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(sysfs.uri().c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    apci_object_descriptor angle{1300, 0, 20, 0, 0};
    ASSERT_EQ(apci_write_double(b, &angle, -12.75), APCI_OK) << apci_last_error(b);
    double v = 0;
    ASSERT_EQ(apci_read_double(b, &angle, &v), APCI_OK);
    EXPECT_EQ(v, -12.75);
    apci_close(b);
}

TEST_F(PciTransport, PciAndShmHostsShareTheMailbox) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kIo);
    apci_board* pci = nullptr;
    apci_board* shm = nullptr;
    ASSERT_EQ(apci_open(sysfs.uri().c_str(), &pci), APCI_OK);
    ASSERT_EQ(apci_open(daemon_->shm_uri().c_str(), &shm), APCI_OK);
    apci_object_descriptor plane{1300, 0, 12, 0, 0};
    for (std::int32_t i = 0; i < 50; ++i) {
        const std::int32_t value = 17 + i % 3;
        ASSERT_EQ(apci_write_int(i % 2 == 0 ? pci : shm, &plane, value), APCI_OK);
        std::int32_t back = 0;
        ASSERT_EQ(apci_read_int(i % 2 == 0 ? shm : pci, &plane, &back), APCI_OK);
        ASSERT_EQ(back, value);
    }
    apci_close(pci);
    apci_close(shm);
}

TEST_F(PciTransport, OtherVendorIsRefusedNamingIt) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kMemory, 0x8086);
    EXPECT_TRUE(
        contains(open_error(sysfs.uri(), APCI_INVALID_ARGUMENT), "vendor 0x8086, not ADDI-DATA"));
}

TEST_F(PciTransport, OlderVendorIdIsAccepted) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kMemory, 0x10e8);
    apci_board* b = nullptr;
    EXPECT_EQ(apci_open(sysfs.uri().c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    apci_close(b);
}

TEST_F(PciTransport, MissingFunctionIsATransportError) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kMemory);
    EXPECT_TRUE(contains(open_error("pci:0000:02:00.0", APCI_TRANSPORT_ERROR),
                         "no PCI function 0000:02:00.0"));
}

TEST_F(PciTransport, UnassignedBarIsATransportError) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kMemory);
    EXPECT_TRUE(contains(open_error(sysfs.uri() + "?bar=1", APCI_TRANSPORT_ERROR), "has no BAR 1"));
}

TEST_F(PciTransport, WindowBeyondTheBarIsRefused) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kMemory);
    EXPECT_TRUE(contains(open_error(sysfs.uri() + "?offset=0x30000", APCI_TRANSPORT_ERROR),
                         "the mailbox window needs"));
}

TEST_F(PciTransport, UioWithoutAUioDeviceSaysHowToBindOne) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kMemory);
    EXPECT_TRUE(
        contains(open_error(sysfs.uri() + "?uio", APCI_TRANSPORT_ERROR), "uio_pci_generic"));
}

TEST_F(PciTransport, UioMapIsMapped) {
    FakePciSysfs sysfs(daemon_->shm_path(), FakePciSysfs::BarKind::kMemory);
    TempDir dev;
    std::filesystem::create_directories(sysfs.device_dir() + "/uio/uio3");
    std::filesystem::create_symlink(daemon_->shm_path(), dev.file("uio3"));
    ::setenv("APCI_DEV_ROOT", dev.path().c_str(), 1);
    apci_board* b = nullptr;
    EXPECT_EQ(apci_open((sysfs.uri() + "?uio").c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    auto o = axis_count();
    std::int32_t v = 0;
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_OK) << apci_last_error(b);
    apci_close(b);
    ::unsetenv("APCI_DEV_ROOT");
}

// ---- Listing

struct Found {
    std::vector<std::pair<std::string, std::string>> boards;
    static void add(const char* uri, const char* description, void* user) {
        static_cast<Found*>(user)->boards.emplace_back(uri, description);
    }
    bool has(const std::string& uri) const {
        for (const auto& [u, d] : boards)
            if (u == uri) return true;
        return false;
    }
};

TEST(ListDevices, NamesPciBoardsAndRunningDaemons) {
    DaemonOptions o;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    FakePciSysfs sysfs(d->shm_path(), FakePciSysfs::BarKind::kMemory);
    ::setenv("APCI_RUNTIME_DIR", d->dir().path().c_str(), 1);
    Found found;
    // The daemon registers itself just after it starts serving.
    EXPECT_TRUE(apci_test::eventually([&] {
        found.boards.clear();
        return apci_list_devices(Found::add, &found) == APCI_OK && found.has(d->unix_uri());
    }));
    ::unsetenv("APCI_RUNTIME_DIR");
    EXPECT_TRUE(found.has(sysfs.uri()));
    EXPECT_TRUE(found.has(d->unix_uri()));
    EXPECT_TRUE(found.has(d->shm_uri()));
    for (const auto& [uri, description] : found.boards) {
        if (uri == sysfs.uri()) {
            EXPECT_TRUE(contains(description, "15b8:8001")) << description;
        }
        if (uri == d->unix_uri()) {
            EXPECT_TRUE(contains(description, std::to_string(d->pid()))) << description;
        }
    }
}

TEST(ListDevices, StoppedDaemonsAreNotListed) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    const std::string uri = d->unix_uri();
    ::setenv("APCI_RUNTIME_DIR", d->dir().path().c_str(), 1);
    ASSERT_EQ(d->stop(), 0);
    Found found;
    ASSERT_EQ(apci_list_devices(Found::add, &found), APCI_OK);
    ::unsetenv("APCI_RUNTIME_DIR");
    EXPECT_FALSE(found.has(uri));
}

TEST(ListDevices, NullCallbackIsInvalid) {
    EXPECT_EQ(apci_list_devices(nullptr, nullptr), APCI_INVALID_ARGUMENT);
}

// ---- The link API on any board

TEST(LinkApi, NullBoardIsInvalid) {
    std::uint32_t ms = 0;
    EXPECT_EQ(apci_set_timeout(nullptr, 10), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_get_timeout(nullptr, &ms), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_reconnect(nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_is_connected(nullptr), 0);
}

TEST(LinkApi, TimeoutOutOfRangeIsInvalidAndKeepsTheOldOne) {
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open("emu:", &b), APCI_OK);
    std::uint32_t ms = 0;
    ASSERT_EQ(apci_get_timeout(b, &ms), APCI_OK);
    EXPECT_EQ(ms, 2000u) << "the default";
    EXPECT_EQ(apci_set_timeout(b, 3'600'001), APCI_INVALID_ARGUMENT);
    EXPECT_TRUE(contains(apci_last_error(b), "outside 1 .. 3600000")) << apci_last_error(b);
    EXPECT_EQ(apci_get_timeout(b, nullptr), APCI_INVALID_ARGUMENT);
    ASSERT_EQ(apci_get_timeout(b, &ms), APCI_OK);
    EXPECT_EQ(ms, 2000u);
    apci_close(b);
}

// ---- The C++ wrapper's link calls

TEST(CppLink, TimeoutConnectedReconnectAndListWrapTheCApi) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    apci::Board board(d->unix_uri());
    ASSERT_TRUE(board) << board.last_error();
    ASSERT_TRUE(board.set_timeout(1234));
    EXPECT_EQ(board.timeout().value_or(0), 1234u);
    EXPECT_EQ(board.set_timeout(0).status, APCI_INVALID_ARGUMENT);
    EXPECT_TRUE(board.connected());
    EXPECT_EQ(board.link_lost(), "");
    ASSERT_EQ(d->stop(), 0);
    auto o = apci::object(1000, 0, 3, 0);
    EXPECT_EQ(board.read_int(o).status, APCI_TRANSPORT_ERROR);
    EXPECT_FALSE(board.connected());
    EXPECT_EQ(board.link_lost(),
              "daemon " + d->socket_path() + " closed the connection: shutting down (SIGTERM)");
    EXPECT_EQ(board.reconnect().status, APCI_TRANSPORT_ERROR);
    DaemonOptions again;
    again.socket_path = d->socket_path();
    auto d2 = Daemon::start(again);
    ASSERT_NE(d2, nullptr);
    EXPECT_TRUE(board.reconnect()) << board.last_error();
    ::setenv("APCI_RUNTIME_DIR", d2->dir().path().c_str(), 1);
    EXPECT_TRUE(apci_test::eventually([&] {
        for (const auto& b : apci::list_boards())
            if (b.uri == d->unix_uri()) return true;
        return false;
    }));
    ::unsetenv("APCI_RUNTIME_DIR");
}

}  // namespace
