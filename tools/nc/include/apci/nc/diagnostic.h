// SPDX-License-Identifier: MIT
// Errors of the NC front end: every one names file, line and column and says what was wrong,
// printed as "prog.nc:12:7: expected a number after 'X'". Nothing here throws; functions return
// Result<T> (a value or a Diagnostic).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace apci::nc {

// What kind of mistake a diagnostic reports; apcictl prints the name as the error "code".
enum class ErrorKind : std::uint8_t {
    kIo,           // the file cannot be opened or read, or changed between the passes
    kSyntax,       // malformed text: missing number, unclosed comment, stray character
    kUnknownWord,  // an address letter, G/M code or tool field that the front end does not know
    kConflict,     // two words in one block that exclude each other (G0 with G2, G41 with G42)
    kValue,        // a number out of its range or not whole where it must be
    kGeometry,     // an arc the program asks for cannot exist (R too small, end off the circle)
    kProgramRule,  // a modal rule broken (no feed before G1, plane change with G41/G42 on)
    kUnsupported,  // recognised but not built yet (Klartext dialect, ISG #/$ commands)
};
std::string_view error_kind_name(ErrorKind k) noexcept;  // "Syntax", "Geometry", ...

// What a program names that the run's inputs do not hold: callers add what to give (apcictl
// run: "no --tools file given"), by this kind, not by the message's words.
enum class Undefined : std::uint8_t {
    kNothing,
    kTool,           // D n / TOOL CALL n of a tool the tool list does not define
    kCorrectionRow,  // FUNCTION CORRDATA TCS #n of a row the correction table does not define
};

// Block number value meaning "the block has no N word".
inline constexpr std::int64_t kNoBlockNumber = -1;

struct Diagnostic {
    ErrorKind kind = ErrorKind::kSyntax;
    std::string file;          // as the caller named the source
    std::uint64_t line = 0;    // 1-based; 0 only for errors about the whole file (cannot open)
    std::uint32_t column = 0;  // 1-based, in characters (UTF-8 aware); 0 with line 0
    std::int64_t block = kNoBlockNumber;  // N number of the block, where known
    bool klartext = false;  // a Klartext block number (the line's leading number): not printed
    std::string message;                  // what was wrong / what was expected, no location prefix
    Undefined undefined = Undefined::kNothing;  // kProgramRule: an input does not define it

    // "file:line:col: N50: message" ("file:line:col: message" for a block without N or a
    // Klartext block; "file: message" when line is 0).
    std::string to_string() const;
};

// A value or the diagnostic that explains why there is none.
template <typename T>
class [[nodiscard]] Result {
  public:
    Result(T value) : v_(std::in_place_index<0>, std::move(value)) {}           // NOLINT
    Result(Diagnostic error) : v_(std::in_place_index<1>, std::move(error)) {}  // NOLINT

    bool ok() const noexcept { return v_.index() == 0; }
    explicit operator bool() const noexcept { return ok(); }
    // Callers check ok() first.
    T& value() & { return std::get<0>(v_); }
    const T& value() const& { return std::get<0>(v_); }
    T&& value() && { return std::get<0>(std::move(v_)); }
    const Diagnostic& error() const { return std::get<1>(v_); }

  private:
    std::variant<T, Diagnostic> v_;
};

}  // namespace apci::nc
