// SPDX-License-Identifier: MIT
#include "apci/run/json_writer.h"

#include "apci/apci.h"

namespace apci::run {

void JsonRunWriter::begin_segments() {
    if (begun_) return;
    begun_ = true;
    sink_.append("{\"segments\":[");
}

void JsonRunWriter::point(const Point& p) {
    sink_.put('[');
    append_json_number(sink_, p.x());
    sink_.put(',');
    append_json_number(sink_, p.y());
    sink_.put(',');
    append_json_number(sink_, p.z());
    sink_.put(']');
}

void JsonRunWriter::block(const BlockRef& b) {
    sink_.append("\"block\":");
    append_integer(sink_, b.number);
    if (b.number == kNoBlock && b.line != 0) {
        sink_.append(",\"line\":");
        append_integer(sink_, static_cast<std::int64_t>(b.line));
    }
}

// Plain appends rather than format strings: this runs once per executed segment.
void JsonRunWriter::segment(const PathSegment& s) {
    begin_segments();
    sink_.append(count_ == 0 ? "\n{" : ",\n{");
    block(s.block);
    sink_.append(",\"kind\":\"");
    sink_.append(kind_name(s.kind));
    sink_.append("\",\"role\":\"");
    sink_.append(role_name(s.role));
    sink_.append("\",\"start\":");
    point(s.start);
    sink_.append(",\"end\":");
    point(s.end);
    if (s.kind == SegmentKind::kArc) {
        sink_.append(",\"center\":");
        point(s.center);
        sink_.append(s.ccw ? ",\"ccw\":true,\"plane\":" : ",\"ccw\":false,\"plane\":");
        append_integer(sink_, s.plane);
    }
    sink_.put('}');
    ++count_;
}

namespace {

// ["KorrError","CalcError"]: the names of the set bits in [APCI-TC] Table 4 (bits it does not name as "bitN").
void bit_names(TextSink& sink, std::int32_t value, const char* (*name_of)(int)) {
    sink.put('[');
    bool first = true;
    for (int bit = 0; bit < 32; ++bit) {
        if ((static_cast<std::uint32_t>(value) & (1u << bit)) == 0) continue;
        if (!first) sink.put(',');
        first = false;
        const char* name = name_of(bit);
        if (name != nullptr) {
            append_json_string(sink, name);
        } else {
            sink.print("\"bit{}\"", bit);
        }
    }
    sink.put(']');
}

}  // namespace

bool JsonRunWriter::finish(std::span<const RunError> errors,
                           std::span<const GroupRegisters> registers) {
    return finish(errors, registers, {}, {});
}

void JsonRunWriter::error_list(std::span<const RunError> errors) {
    for (std::size_t i = 0; i < errors.size(); ++i) {
        sink_.append(i == 0 ? "\n{" : ",\n{");
        block(errors[i].block);
        sink_.append(",\"code\":");
        append_json_string(sink_, errors[i].code);
        sink_.append(",\"message\":");
        append_json_string(sink_, errors[i].message);
        sink_.put('}');
    }
}

bool JsonRunWriter::finish(std::span<const RunError> errors,
                           std::span<const GroupRegisters> registers,
                           std::span<const std::pair<std::string, double>> variables,
                           std::span<const RunError> notices,
                           std::span<const RunError> warnings) {
    begin_segments();
    sink_.append("],\n\"errors\":[");
    error_list(errors);
    if (!warnings.empty()) {
        sink_.append("],\n\"warnings\":[");
        error_list(warnings);
    }
    if (!notices.empty()) {
        sink_.append("],\n\"notices\":[");
        error_list(notices);
    }
    sink_.append("],\n\"registers\":{");
    for (std::size_t i = 0; i < registers.size(); ++i) {
        const GroupRegisters& g = registers[i];
        if (i != 0) sink_.put(',');
        sink_.print("\"{}\":", g.group);
        if (!g.readable) {
            sink_.append("null");
            continue;
        }
        sink_.print("{{\"ERROR\":{},\"ERROR_bits\":", g.error);
        bit_names(sink_, g.error, apci_tc_error_bit_name);
        sink_.print(",\"STATUS\":{},\"STATUS_bits\":", g.status);
        bit_names(sink_, g.status, apci_tc_status_bit_name);
        sink_.put('}');
    }
    // The readable NC variables by their names in [ISG-OTC] (the OTC module's; docs/design.md section 7).
    sink_.append("},\n\"variables\":{");
    for (std::size_t i = 0; i < variables.size(); ++i) {
        if (i != 0) sink_.put(',');
        append_json_string(sink_, variables[i].first);
        sink_.put(':');
        append_json_number(sink_, variables[i].second);
    }
    sink_.append("}}\n");
    return sink_.flush();
}

}  // namespace apci::run
