// SPDX-License-Identifier: MIT
#include "line_editor.h"

#include <histedit.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>

#include "shell_complete.h"

namespace apcictl {
namespace {

// The terminal's width in characters (80 when it does not say).
std::size_t terminal_width() {
    winsize size{};
    if (::ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
    return 80;
}

LineEditor* editor_of(EditLine* el) {
    void* data = nullptr;
    el_get(el, EL_CLIENTDATA, &data);
    return static_cast<LineEditor*>(data);
}

}  // namespace

LineEditor::LineEditor(const char* program, std::string prompt, Completer completer,
                       std::span<const std::string> history)
    : prompt_(std::move(prompt)), completer_(std::move(completer)) {
    el_ = el_init(program, stdin, stdout, stderr);
    history_ = history_init();
    if (el_ == nullptr || history_ == nullptr) {
        if (el_ != nullptr) el_end(el_);
        if (history_ != nullptr) history_end(history_);
        throw std::runtime_error("the terminal line editor (libedit) could not be started");
    }
    HistEvent event{};
    ::history(history_, &event, H_SETSIZE, static_cast<int>(history.size() + 1000));
    for (const auto& line : history) ::history(history_, &event, H_ENTER, line.c_str());

    el_set(el_, EL_CLIENTDATA, static_cast<void*>(this));
    el_set(el_, EL_EDITOR, "emacs");
    el_set(el_, EL_SIGNAL, 1);  // the terminal is restored if a signal ends the program
    el_set(el_, EL_PROMPT, &LineEditor::prompt_of);
    el_set(el_, EL_HIST, ::history, history_);
    // The wide form: libedit keeps these (static) strings as they are, where the narrow
    // el_set(EL_ADDFN) makes wide copies it never frees.
    el_wset(el_, EL_ADDFN, L"apcictl-complete", L"Complete a command or object name",
            &LineEditor::on_tab);
    el_set(el_, EL_BIND, "^I", "apcictl-complete", nullptr);
    el_source(el_, nullptr);  // the user's ~/.editrc, if any
}

LineEditor::~LineEditor() {
    el_end(el_);
    history_end(history_);
}

std::optional<std::string> LineEditor::read_line() {
    std::fflush(stdout);
    int count = 0;
    const char* text = el_gets(el_, &count);
    if (text == nullptr || count <= 0) return std::nullopt;
    std::string line(text, static_cast<std::size_t>(count));
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    return line;
}

void LineEditor::add_history(const std::string& line) {
    HistEvent event{};
    ::history(history_, &event, H_ENTER, line.c_str());
}

char* LineEditor::prompt_of(EditLine* el) {
    LineEditor* editor = editor_of(el);
    return editor != nullptr ? editor->prompt_.data() : const_cast<char*>("> ");
}

unsigned char LineEditor::on_tab(EditLine* el, int /*key*/) {
    LineEditor* editor = editor_of(el);
    const LineInfo* info = el_line(el);
    if (editor == nullptr || info == nullptr || !editor->completer_) return CC_REFRESH_BEEP;
    const std::string before(info->buffer, static_cast<std::size_t>(info->cursor - info->buffer));
    const auto candidates = editor->completer_(before);
    const TabAction action = tab_action(before, candidates);
    if (!action.insert.empty()) {
        if (el_insertstr(el, action.insert.c_str()) != 0) return CC_REFRESH_BEEP;
        return CC_REFRESH;
    }
    if (action.listed.empty()) return CC_REFRESH_BEEP;
    std::fputs("\n", stdout);
    std::fputs(candidate_columns(action.listed, terminal_width()).c_str(), stdout);
    std::fflush(stdout);
    return CC_REDISPLAY;
}

PlainLine read_plain_line(std::FILE* in, std::size_t max_length) {
    PlainLine line;
    bool any = false;
    bool too_long = false;
    for (int c = std::getc(in); c != EOF; c = std::getc(in)) {
        any = true;
        if (c == '\n') break;
        if (line.text.size() < max_length)
            line.text.push_back(static_cast<char>(c));
        else
            too_long = true;
    }
    if (std::ferror(in) != 0) {
        line.kind = PlainLine::Kind::kError;
        return line;
    }
    if (!any) {
        line.kind = PlainLine::Kind::kEnd;
        return line;
    }
    if (!too_long && !line.text.empty() && line.text.back() == '\r') line.text.pop_back();
    line.kind = too_long ? PlainLine::Kind::kTooLong : PlainLine::Kind::kLine;
    return line;
}

}  // namespace apcictl
