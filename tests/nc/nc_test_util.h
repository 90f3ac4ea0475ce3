// SPDX-License-Identifier: MIT
// Helpers for the NC front end tests: run a program text through both passes.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "apci/nc/program.h"

namespace apci::nc::test {

struct RunResult {
    std::vector<Event> events;
    std::optional<Diagnostic> error;
};

// Validation pass, then the execution pass collecting every event.
inline RunResult run(std::string_view text, const InterpreterOptions& options = {}) {
    RunResult r;
    Result<Program> program = Program::from_text(text, "prog.nc", options);
    if (!program) {
        r.error = program.error();
        return r;
    }
    Result<EventStream> stream = program.value().events();
    if (!stream) {
        r.error = stream.error();
        return r;
    }
    Event ev;
    for (;;) {
        const EventStream::Next n = stream.value().next(ev);
        if (n == EventStream::Next::kEnd) break;
        if (n == EventStream::Next::kError) {
            r.error = stream.value().error();
            break;
        }
        r.events.push_back(ev);
    }
    return r;
}

// "file:line:col: message" of the first error, or "" when the program runs.
inline std::string error_of(std::string_view text, const InterpreterOptions& options = {}) {
    RunResult r = run(text, options);
    return r.error ? r.error->to_string() : std::string();
}

// What the program's error says an input does not define (kNothing without an error).
inline Undefined undefined_of(std::string_view text, const InterpreterOptions& options = {}) {
    RunResult r = run(text, options);
    return r.error ? r.error->undefined : Undefined::kNothing;
}

// The events of a program that must run; moves only when moves_only.
inline std::vector<Event> events_of(std::string_view text, const InterpreterOptions& options = {}) {
    RunResult r = run(text, options);
    if (r.error) ADD_FAILURE() << "unexpected error: " << r.error->to_string();
    return r.events;
}

template <typename T>
std::vector<T> only(const std::vector<Event>& events) {
    std::vector<T> out;
    for (const Event& e : events) {
        if (const T* t = std::get_if<T>(&e.data)) out.push_back(*t);
    }
    return out;
}

}  // namespace apci::nc::test
