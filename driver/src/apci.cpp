// SPDX-License-Identifier: MIT
// The C API boundary: every exported function is noexcept, checks its
// pointers, converts objif::Status to apci_status here and nowhere else, and
// records the per-board last-error text.
#include "apci/apci.h"

#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <type_traits>

#include <fmt/format.h>

#include "c_api.h"
#include "objif/status.h"
#include "transport.h"

namespace apci {
// Errors of calls that have no board (apci_open, NULL board).
thread_local std::string t_last_error;
}  // namespace apci

namespace {

using apci::fail;
using apci::t_last_error;
using apci::to_c;
using objif::Status;

// The C codes are the objif codes; the compiler keeps the two lists in step.
constexpr bool same(apci_status c, Status s) { return c == static_cast<apci_status>(s); }
static_assert(same(APCI_OK, Status::kOk));
static_assert(same(APCI_NO_SUCH_DEVICE, Status::kNoSuchDevice));
static_assert(same(APCI_OBJECT_MISSING, Status::kObjectMissing));
static_assert(same(APCI_SUB_MISSING, Status::kSubMissing));
static_assert(same(APCI_STALE_HANDLE, Status::kStaleHandle));
static_assert(same(APCI_HANDLE_MISMATCH, Status::kHandleMismatch));
static_assert(same(APCI_READ_ONLY, Status::kReadOnly));
static_assert(same(APCI_WRITE_ONLY, Status::kWriteOnly));
static_assert(same(APCI_TYPE_MISMATCH, Status::kTypeMismatch));
static_assert(same(APCI_VALUE_TOO_HIGH, Status::kValueTooHigh));
static_assert(same(APCI_VALUE_TOO_LOW, Status::kValueTooLow));
static_assert(same(APCI_INVALID_VALUE, Status::kInvalidValue));
static_assert(same(APCI_WRONG_DEVICE_STATE, Status::kWrongDeviceState));
static_assert(same(APCI_BUSY, Status::kBusy));
static_assert(same(APCI_GENERAL_ERROR, Status::kGeneralError));
static_assert(same(APCI_BAD_FRAME, Status::kBadFrame));
static_assert(same(APCI_UNKNOWN_OPCODE, Status::kUnknownOpcode));
static_assert(same(APCI_TRANSPORT_ERROR, Status::kTransportError));
static_assert(same(APCI_TIMEOUT, Status::kTimeout));
static_assert(same(APCI_NOT_SUPPORTED, Status::kNotSupported));
static_assert(same(APCI_INVALID_ARGUMENT, Status::kInvalidArgument));
static_assert(same(APCI_NO_MEMORY, Status::kNoMemory));
static_assert(APCI_STATUS_COUNT == objif::kStatusCount, "apci.h lists every objif status");

objif::Descriptor to_objif(const apci_object_descriptor& o) noexcept {
    return objif::Descriptor{objif::Address{o.bus, o.device, o.index, o.subindex}, o.handle};
}

std::string describe(std::string_view op, const objif::Address& a, std::string_view value,
                     Status s, std::string_view detail) {
    std::string text = fmt::format("{} {}", op, a.to_string());
    if (!value.empty()) text += fmt::format(" = {}", value);
    text += fmt::format(": {} ({})", objif::status_name(s), objif::status_message(s));
    if (!detail.empty()) text += fmt::format(": {}", detail);
    return text;
}

// Common checks of the four accessors; `op` names the C function for errors.
bool arguments_ok(apci_board* board, const apci_object_descriptor* object, const void* value,
                  std::string_view op, apci_status& status) noexcept {
    if (board == nullptr) {
        status = fail(nullptr, Status::kInvalidArgument,
                      [&] { return fmt::format("{}: board is NULL", op); });
        return false;
    }
    if (object == nullptr) {
        status = fail(board, Status::kInvalidArgument,
                      [&] { return fmt::format("{}: object descriptor is NULL", op); });
        return false;
    }
    if (value == nullptr) {
        status = fail(board, Status::kInvalidArgument,
                      [&] { return fmt::format("{}: value pointer is NULL", op); });
        return false;
    }
    return true;
}

template <class T>
apci_status read_typed(apci_board* board, apci_object_descriptor* object, T* value,
                       std::string_view op) noexcept {
    apci_status status = APCI_OK;
    if (!arguments_ok(board, object, value, op, status)) return status;
    constexpr auto want =
        std::is_same_v<T, double> ? objif::ValueType::kDouble : objif::ValueType::kInt32;
    objif::Descriptor d = to_objif(*object);
    objif::Value v;
    const Status s = board->transport->read(d, want, v);
    object->handle = d.handle;
    if (!objif::ok(s)) {
        return fail(board, s, [&] {
            return describe(fmt::format("read {}", objif::value_type_name(want)), d.address, {},
                            s, apci::failure_words(board, s));
        });
    }
    if (v.type() != want) {  // a board must never answer another type; do not guess
        return fail(board, Status::kTypeMismatch, [&] {
            return describe("read", d.address, {}, Status::kTypeMismatch,
                            "the board answered a value of the other type");
        });
    }
    if constexpr (std::is_same_v<T, double>) {
        *value = v.as_double();
    } else {
        *value = v.as_int();
    }
    board->last_error.clear();
    board->board_message.clear();
    return APCI_OK;
}

apci_status write_value(apci_board* board, apci_object_descriptor* object,
                        const objif::Value& v, std::string_view op) noexcept {
    apci_status status = APCI_OK;
    if (!arguments_ok(board, object, &v, op, status)) return status;
    objif::Descriptor d = to_objif(*object);
    const Status s = board->transport->write(d, v);
    object->handle = d.handle;
    if (!objif::ok(s)) {
        return fail(board, s, [&] {
            return describe(fmt::format("write {}", objif::value_type_name(v.type())), d.address,
                            v.to_string(), s, apci::failure_words(board, s));
        });
    }
    board->last_error.clear();
    board->board_message.clear();
    return APCI_OK;
}

}  // namespace

extern "C" {

const char* apci_version(void) noexcept {
    return "0.2.0";
}
static_assert(APCI_VERSION_MAJOR == 0 && APCI_VERSION_MINOR == 2 && APCI_VERSION_PATCH == 0,
              "apci_version() repeats the header's version");

const char* apci_status_name(apci_status status) noexcept {
    // The table's names are string literals, so data() is NUL-terminated.
    return objif::status_name(static_cast<Status>(status)).data();
}

const char* apci_status_message(apci_status status) noexcept {
    return objif::status_message(static_cast<Status>(status)).data();
}

apci_status apci_open(const char* uri, apci_board** out) noexcept {
    if (out == nullptr) {
        return fail(nullptr, Status::kInvalidArgument,
                    [] { return std::string("apci_open: out pointer is NULL"); });
    }
    *out = nullptr;
    const std::string_view text = uri != nullptr ? std::string_view(uri) : std::string_view();
    std::string why;
    apci::DeviceUri parsed;
    Status s = apci::parse_device_uri(text, parsed, why);
    std::unique_ptr<apci::Transport> transport;
    if (objif::ok(s)) s = apci::open_transport(parsed, transport, why);
    if (!objif::ok(s)) {
        return fail(nullptr, s, [&] {
            return fmt::format("open '{}': {} ({}){}{}", text, objif::status_name(s),
                               objif::status_message(s), why.empty() ? "" : ": ", why);
        });
    }
    auto* board = new (std::nothrow) apci_board;
    if (board == nullptr) {
        return fail(nullptr, Status::kNoMemory,
                    [&] { return fmt::format("open '{}': out of memory", text); });
    }
    board->transport = std::move(transport);
    t_last_error.clear();
    *out = board;
    return APCI_OK;
}

void apci_close(apci_board* board) noexcept {
    if (board == nullptr) return;
    apci::drop_motion_claim(board);
    delete board;  // the transport's destructor closes the link; it does not throw
}

const char* apci_last_error(const apci_board* board) noexcept {
    return board != nullptr ? board->last_error.c_str() : t_last_error.c_str();
}

const char* apci_last_board_message(const apci_board* board) noexcept {
    return board != nullptr ? board->board_message.c_str() : "";
}

apci_status apci_read_int(apci_board* board, apci_object_descriptor* object, int32_t* value) noexcept {
    return read_typed(board, object, value, "apci_read_int");
}

apci_status apci_read_double(apci_board* board, apci_object_descriptor* object, double* value) noexcept {
    return read_typed(board, object, value, "apci_read_double");
}

apci_status apci_write_int(apci_board* board, apci_object_descriptor* object, int32_t value) noexcept {
    return write_value(board, object, objif::Value::of_int(value), "apci_write_int");
}

apci_status apci_write_double(apci_board* board, apci_object_descriptor* object, double value) noexcept {
    return write_value(board, object, objif::Value::of_double(value), "apci_write_double");
}

}  // extern "C"
