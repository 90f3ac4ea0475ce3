// SPDX-License-Identifier: MIT
#include "line_editor.h"

#include <dlfcn.h>
#include <histedit.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "shell_complete.h"

namespace apcictl {
namespace {

// libedit's functions, loaded when the first editor starts: every other command (and the shell
// on a pipe) starts without loading the line editor and the libraries it brings
// (docs/apcictl.md, "shell"). Each has the type its declaration in histedit.h gives it.
struct EditLib {
    decltype(&::el_init) init = nullptr;
    decltype(&::el_end) end = nullptr;
    decltype(&::el_set) set = nullptr;
    decltype(&::el_wset) wset = nullptr;
    decltype(&::el_get) get = nullptr;
    decltype(&::el_gets) gets = nullptr;
    decltype(&::el_source) source = nullptr;
    decltype(&::el_line) line = nullptr;
    decltype(&::el_insertstr) insertstr = nullptr;
    decltype(&::history_init) history_init = nullptr;
    decltype(&::history_end) history_end = nullptr;
    decltype(&::history) history = nullptr;
    void* handle = nullptr;  // the library, loaded for the rest of the process
    std::string error;       // why it could not be loaded; empty when every function is there
};

// The soname of Debian's libedit2 (the library libedit-dev builds against).
constexpr const char* kLibEdit = "libedit.so.2";

template <typename F>
void bind(void* handle, const char* name, F& f, std::string& error) {
    f = reinterpret_cast<F>(::dlsym(handle, name));
    if (f == nullptr && error.empty()) error = std::string(kLibEdit) + " has no " + name;
}

EditLib load_edit_lib() {
    EditLib lib;
    lib.handle = ::dlopen(kLibEdit, RTLD_NOW | RTLD_LOCAL);
    void* const handle = lib.handle;
    if (handle == nullptr) {
        const char* why = ::dlerror();
        lib.error = why != nullptr ? why : std::string(kLibEdit) + " could not be loaded";
        return lib;
    }
    bind(handle, "el_init", lib.init, lib.error);
    bind(handle, "el_end", lib.end, lib.error);
    bind(handle, "el_set", lib.set, lib.error);
    bind(handle, "el_wset", lib.wset, lib.error);
    bind(handle, "el_get", lib.get, lib.error);
    bind(handle, "el_gets", lib.gets, lib.error);
    bind(handle, "el_source", lib.source, lib.error);
    bind(handle, "el_line", lib.line, lib.error);
    bind(handle, "el_insertstr", lib.insertstr, lib.error);
    bind(handle, "history_init", lib.history_init, lib.error);
    bind(handle, "history_end", lib.history_end, lib.error);
    bind(handle, "history", lib.history, lib.error);
    return lib;
}

const EditLib& edit_lib() {
    static const EditLib lib = load_edit_lib();
    return lib;
}

// The terminal's width in characters (80 when it does not say).
std::size_t terminal_width() {
    winsize size{};
    if (::ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
    return 80;
}

LineEditor* editor_of(EditLine* el) {
    void* data = nullptr;
    edit_lib().get(el, EL_CLIENTDATA, &data);
    return static_cast<LineEditor*>(data);
}

}  // namespace

std::string LineEditor::unavailable() {
    return edit_lib().error;
}

LineEditor::LineEditor(const char* program, std::string prompt, Completer completer,
                       std::span<const std::string> history)
    : prompt_(std::move(prompt)), completer_(std::move(completer)) {
    const EditLib& lib = edit_lib();
    if (!lib.error.empty())
        throw std::runtime_error("the terminal line editor (libedit) could not be loaded: " +
                                 lib.error);
    el_ = lib.init(program, stdin, stdout, stderr);
    history_ = lib.history_init();
    if (el_ == nullptr || history_ == nullptr) {
        if (el_ != nullptr) lib.end(el_);
        if (history_ != nullptr) lib.history_end(history_);
        throw std::runtime_error("the terminal line editor (libedit) could not be started");
    }
    HistEvent event{};
    lib.history(history_, &event, H_SETSIZE, static_cast<int>(history.size() + 1000));
    for (const auto& line : history) lib.history(history_, &event, H_ENTER, line.c_str());

    lib.set(el_, EL_CLIENTDATA, static_cast<void*>(this));
    lib.set(el_, EL_EDITOR, "emacs");
    lib.set(el_, EL_SIGNAL, 1);  // the terminal is restored if a signal ends the program
    lib.set(el_, EL_PROMPT, &LineEditor::prompt_of);
    lib.set(el_, EL_HIST, lib.history, history_);
    // The wide form: libedit keeps these (static) strings as they are, where the narrow
    // el_set(EL_ADDFN) makes wide copies it never frees.
    lib.wset(el_, EL_ADDFN, L"apcictl-complete", L"Complete a command or object name",
             &LineEditor::on_tab);
    lib.set(el_, EL_BIND, "^I", "apcictl-complete", nullptr);
    lib.source(el_, nullptr);  // the user's ~/.editrc, if any
}

LineEditor::~LineEditor() {
    edit_lib().end(el_);
    edit_lib().history_end(history_);
}

std::optional<std::string> LineEditor::read_line() {
    std::fflush(stdout);
    int count = 0;
    const char* text = edit_lib().gets(el_, &count);
    if (text == nullptr || count <= 0) return std::nullopt;
    std::string line(text, static_cast<std::size_t>(count));
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    return line;
}

void LineEditor::add_history(const std::string& line) {
    HistEvent event{};
    edit_lib().history(history_, &event, H_ENTER, line.c_str());
}

char* LineEditor::prompt_of(EditLine* el) {
    LineEditor* editor = editor_of(el);
    return editor != nullptr ? editor->prompt_.data() : const_cast<char*>("> ");
}

unsigned char LineEditor::on_tab(EditLine* el, int /*key*/) {
    LineEditor* editor = editor_of(el);
    const EditLib& lib = edit_lib();
    const LineInfo* info = lib.line(el);
    if (editor == nullptr || info == nullptr || !editor->completer_) return CC_REFRESH_BEEP;
    const std::string before(info->buffer, static_cast<std::size_t>(info->cursor - info->buffer));
    const auto candidates = editor->completer_(before);
    const TabAction action = tab_action(before, candidates);
    if (!action.insert.empty()) {
        if (lib.insertstr(el, action.insert.c_str()) != 0) return CC_REFRESH_BEEP;
        return CC_REFRESH;
    }
    if (action.listed.empty()) return CC_REFRESH_BEEP;
    std::fputs("\n", stdout);
    std::fputs(candidate_columns(action.listed, terminal_width()).c_str(), stdout);
    std::fflush(stdout);
    return CC_REDISPLAY;
}

namespace {

// A line of at most `max_length` characters without its line end; `next` gives the next
// character or EOF. One character more than the bound is kept until the line ends, so that a
// line of exactly `max_length` characters ended by "\r\n" is not taken for a longer one.
template <class Next>
PlainLine read_line_with(Next&& next, std::size_t max_length, std::uint64_t max_consumed) {
    PlainLine line;
    bool any = false;
    bool too_long = false;
    while (line.consumed < max_consumed) {
        const int c = next();
        if (c == EOF) break;
        any = true;
        ++line.consumed;
        if (c == '\n') break;
        if (line.consumed == max_consumed) too_long = true;  // not ended within the bound
        if (line.text.size() <= max_length)
            line.text.push_back(static_cast<char>(c));
        else
            too_long = true;
    }
    if (!any) {
        line.kind = PlainLine::Kind::kEnd;
        return line;
    }
    if (!too_long && !line.text.empty() && line.text.back() == '\r') line.text.pop_back();
    if (line.text.size() > max_length) {
        too_long = true;
        line.text.resize(max_length);
    }
    line.kind = too_long ? PlainLine::Kind::kTooLong : PlainLine::Kind::kLine;
    return line;
}

}  // namespace

PlainLine read_plain_line(std::FILE* in, std::size_t max_length, std::uint64_t max_consumed) {
    PlainLine line = read_line_with([in] { return std::getc(in); }, max_length, max_consumed);
    if (std::ferror(in) != 0) line = PlainLine{PlainLine::Kind::kError, {}, line.consumed};
    return line;
}

PlainLine read_plain_line(std::istream& in, std::size_t max_length, std::uint64_t max_consumed) {
    std::streambuf* buffer = in.rdbuf();
    if (buffer == nullptr) return PlainLine{PlainLine::Kind::kError, {}, 0};
    // sbumpc gives a character as 0..255 or EOF (char_traits<char>::eof()).
    return read_line_with([buffer] { return buffer->sbumpc(); }, max_length, max_consumed);
}

}  // namespace apcictl
