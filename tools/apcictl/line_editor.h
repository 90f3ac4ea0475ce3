// SPDX-License-Identifier: MIT
// Where `apcictl shell` reads its lines: a terminal through libedit (line editing, the
// session's history, TAB completion by a function of the text before the cursor), or any
// other input plainly, a line at a time with a bound on its length.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <istream>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

struct editline;
struct history;

namespace apcictl {

// A terminal line editor (libedit, emacs keys; ~/.editrc is read, editrc(5)). Up and Down walk
// the history, TAB asks `completer` for the candidates of the word before the cursor
// (shell_complete.h: inserted, extended to their common prefix, or listed).
class LineEditor {
  public:
    using Completer = std::function<std::vector<std::string>(std::string_view)>;

    // Why no editor can be made (libedit is loaded when first asked: dlopen of libedit.so.2);
    // empty when it can.
    static std::string unavailable();

    LineEditor(const char* program, std::string prompt, Completer completer,
               std::span<const std::string> history);
    ~LineEditor();
    LineEditor(const LineEditor&) = delete;
    LineEditor& operator=(const LineEditor&) = delete;

    // The next line without its newline; nullopt at the end of input (Ctrl-D on an empty line)
    // or when the terminal cannot be read.
    std::optional<std::string> read_line();
    // Adds a line to the history Up recalls (the caller decides which lines are kept).
    void add_history(const std::string& line);

  private:
    static char* prompt_of(editline* el);
    static unsigned char on_tab(editline* el, int key);

    std::string prompt_;
    Completer completer_;
    editline* el_ = nullptr;
    history* history_ = nullptr;
};

// One line read plainly from `in`: its text without the newline, or why there is none.
struct PlainLine {
    enum class Kind { kLine, kTooLong, kEnd, kError };
    Kind kind = Kind::kEnd;
    std::string text;  // kLine: the line; kTooLong: its first `max_length` characters
    std::uint64_t consumed = 0;  // bytes read for it, its line end included
};

// Reads up to the next newline (or the end of the input; a '\r' before the newline is dropped).
// A line longer than `max_length` (its line end, "\n" or "\r\n", not counted) is read to its
// end but only its first `max_length` characters are kept (kTooLong): the input is never held
// whole. kError: the stream failed. `apcictl shell` reads a pipe this way, `apcictl script`
// its file.
// At most `max_consumed` bytes are read: a line not ended by then is kTooLong.
PlainLine read_plain_line(std::FILE* in, std::size_t max_length,
                          std::uint64_t max_consumed = UINT64_MAX);
PlainLine read_plain_line(std::istream& in, std::size_t max_length,
                          std::uint64_t max_consumed = UINT64_MAX);

}  // namespace apcictl
