// SPDX-License-Identifier: MIT
// What a client can observe of a Board: the status and value of every
// readable object at every index of its table row. Two equal snapshots mean
// no observable state changed in between.
//
// The whole map is 8,368 addresses, too many to read twice for every fuzz
// input; `same_as` compares a board with a full snapshot taken once, at
// every object's first and last index and at one more index chosen by the
// caller's salt (the input's hash), so that over a campaign every index of
// every table is compared.
#pragma once

#include <cstdint>
#include <vector>

#include "objif/dictionary.h"
#include "rwmos/board.h"

namespace fuzz {

struct ObservedObject {
    objif::Address address;
    objif::Status status = objif::Status::kOk;
    objif::Value value;

    friend bool operator==(const ObservedObject& a, const ObservedObject& b) noexcept {
        // Doubles are compared bit for bit through Value's ==; every value is finite.
        return a.address == b.address && a.status == b.status && a.value == b.value;
    }
};

inline std::vector<ObservedObject> snapshot(rwmos::EmulatedBoard& board) {
    std::vector<ObservedObject> seen;
    for (objif::Module* module : board.dictionary().modules()) {
        for (std::size_t i = 0; i < module->object_count(); ++i) {
            const objif::ObjectInfo& info = module->object_at(i);
            if (!objif::can_read(info.access)) continue;
            for (std::int32_t index = info.index_first; index <= info.index_last; ++index) {
                ObservedObject o;
                o.address = {module->bus(), info.device, index, info.subindex};
                objif::Descriptor d{o.address, objif::kNoHandle};
                o.status = board.read(d, info.type, o.value);
                seen.push_back(o);
            }
        }
    }
    return seen;
}

// Compares `board` with `full` (a snapshot() of a board in the state it
// should still be in) at every readable object's first and last index and
// at index first + salt mod (number of indices). Returns the address of the
// first difference, or nullptr.
inline const objif::Address* first_difference(rwmos::EmulatedBoard& board,
                                               const std::vector<ObservedObject>& full,
                                               std::uint64_t salt) {
    std::size_t at = 0;  // full is in snapshot() order: module, object, index
    for (objif::Module* module : board.dictionary().modules()) {
        for (std::size_t i = 0; i < module->object_count(); ++i) {
            const objif::ObjectInfo& info = module->object_at(i);
            if (!objif::can_read(info.access)) continue;
            const auto count = static_cast<std::uint64_t>(info.index_last - info.index_first) + 1;
            const std::uint64_t picks[] = {0, count - 1, salt % count};
            for (const std::uint64_t k : picks) {
                const ObservedObject& expected = full.at(at + k);
                ObservedObject o;
                o.address = expected.address;
                objif::Descriptor d{o.address, objif::kNoHandle};
                o.status = board.read(d, info.type, o.value);
                if (!(o == expected)) return &expected.address;
            }
            at += count;
        }
    }
    return at == full.size() ? nullptr : &full.back().address;
}

}  // namespace fuzz
