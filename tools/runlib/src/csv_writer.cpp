// SPDX-License-Identifier: MIT
#include "apci/run/csv_writer.h"

namespace apci::run {

TraceCsvWriter::TraceCsvWriter(std::FILE* out, std::span<const std::string> axis_names)
    : sink_(out) {
    sink_.append("cycle,time_s");
    for (const std::string& name : axis_names) {
        sink_.put(',');
        sink_.append(name);
    }
    sink_.put('\n');
}

void TraceCsvWriter::sample(std::uint64_t cycle, double time_s, std::span<const double> positions) {
    sink_.print("{},{}", cycle, time_s);
    for (const double p : positions) sink_.print(",{}", p);
    sink_.put('\n');
    ++count_;
}

std::string axis_column_name(int axis) {
    if (axis >= 0 && static_cast<std::size_t>(axis) < kBoardAxisLetters.size())
        return std::string(1, kBoardAxisLetters[static_cast<std::size_t>(axis)]);
    return "a" + std::to_string(axis);
}

}  // namespace apci::run
