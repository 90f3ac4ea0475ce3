// SPDX-License-Identifier: MIT
// Tables the self-approach check keeps without an allocation per entry: a table over 64-bit
// keys with a value each (open addressing), a set of keys, and the items of a uniform grid's
// cells in one or more lists; and the grid's arithmetic (a cell's index).
// Shared by the check's grid (self_approach.cpp) and its wall model's loops (wall_model.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace apci::run::detail {

// A table over 64-bit keys, each with a value: open addressing, linear probing, at most three
// quarters full, the slots doubling from 1024. The keys and the values in arrays of their own
// (a key of 8 bytes and a value of 4 take 12, not 16), key 0 marking a free slot and the key 0
// itself kept apart. No allocation per key once the slots have grown. An empty Value keeps no
// values at all (a set).
template <class Value>
class ProbeTable {
  public:
    // The key's value, and whether it is new (the value then Value{}, for the caller to set).
    std::pair<Value&, bool> emplace(std::uint64_t key) {
        if (key == 0) {
            const bool fresh = !zero_taken_;
            zero_taken_ = true;
            count_ += fresh;
            return {zero_value_, fresh};
        }
        if (4 * (count_ + 1) > 3 * keys_.size()) grow();
        const std::size_t at = find(keys_, key);
        if (keys_[at] == key) return {value_at(at), false};
        keys_[at] = key;
        ++count_;
        return {value_at(at), true};
    }
    // The key's value, or null.
    const Value* get(std::uint64_t key) const {
        if (key == 0) return zero_taken_ ? &zero_value_ : nullptr;
        if (keys_.empty()) return nullptr;
        const std::size_t at = find(keys_, key);
        if (keys_[at] != key) return nullptr;
        if constexpr (kValues) return &values_[at];
        return &zero_value_;
    }
    // Empty, keeping the memory.
    void clear() {
        std::fill(keys_.begin(), keys_.end(), 0);
        if constexpr (kValues) std::fill(values_.begin(), values_.end(), Value{});
        zero_taken_ = false;
        zero_value_ = Value{};
        count_ = 0;
    }

  private:
    static constexpr bool kValues = !std::is_empty_v<Value>;
    Value& value_at(std::size_t at) {
        if constexpr (kValues) return values_[at];
        return zero_value_;
    }
    // The key's slot, or the free one where it would go (key not 0).
    static std::size_t find(const std::vector<std::uint64_t>& keys, std::uint64_t key) {
        const std::size_t mask = keys.size() - 1;
        // Mixed so that the high half reaches the low bits (a grid cell's key is its row and
        // column in the high and low half).
        const std::uint64_t h = (key ^ (key >> 31)) * 0x9E3779B97F4A7C15ULL;
        std::size_t i = (h ^ (h >> 32)) & mask;
        while (keys[i] != 0 && keys[i] != key) i = (i + 1) & mask;
        return i;
    }
    [[gnu::noinline]] void grow() {
        const std::size_t size = keys_.empty() ? 1024 : 2 * keys_.size();
        std::vector<std::uint64_t> keys(size, 0);
        std::vector<Value> values(kValues ? size : 0);
        for (std::size_t i = 0; i < keys_.size(); ++i) {
            if (keys_[i] == 0) continue;
            const std::size_t at = find(keys, keys_[i]);
            keys[at] = keys_[i];
            if constexpr (kValues) values[at] = values_[i];
        }
        keys_.swap(keys);
        values_.swap(values);
    }
    std::vector<std::uint64_t> keys_;
    std::vector<Value> values_;
    bool zero_taken_ = false;
    Value zero_value_{};
    std::size_t count_ = 0;
};

// A set of 64-bit keys.
class KeySet {
  public:
    // True when the key was not in the set (it is now).
    bool insert(std::uint64_t key) { return table_.emplace(key).second; }
    // Empty, keeping the memory.
    void clear() { table_.clear(); }

  private:
    struct Nothing {};
    ProbeTable<Nothing> table_;
};

// The items of a uniform grid's cells in Lists lists: per cell (a 64-bit key, in a ProbeTable)
// and list a chain of item positions, the latest first, the chains' nodes in one array per
// list: no allocation per cell or per item once the arrays have grown. A cell is looked up once
// for all its lists (append_and_add).
template <std::size_t Lists>
class CellIndex {
  public:
    // Adds the item to the cell's list, unless it is that list's latest there already.
    void add(std::size_t list, std::uint64_t cell, std::uint32_t item) {
        push(list, heads_.emplace(cell).first, item);
    }
    // Appends the items of the cell's list to `out`.
    void append(std::size_t list, std::uint64_t cell, std::vector<std::uint32_t>& out) const {
        if (const Head* head = heads_.get(cell)) walk(list, *head, out);
    }
    // Both at one lookup: the items of list `from` in the cell appended to `out`, and `item`
    // added to list `to` there.
    void append_and_add(std::size_t from, std::size_t to, std::uint64_t cell, std::uint32_t item,
                        std::vector<std::uint32_t>& out) {
        Head& head = heads_.emplace(cell).first;
        walk(from, head, out);
        push(to, head, item);
    }
    // Empty, keeping the memory.
    void clear() {
        heads_.clear();
        for (auto& n : nodes_) n.clear();
    }

  private:
    static constexpr std::uint32_t kEnd = ~std::uint32_t{0};
    struct Head {
        Head() { node.fill(kEnd); }
        std::array<std::uint32_t, Lists> node;  // each list's latest node in the cell
    };
    struct Node {
        std::uint32_t item;
        std::uint32_t next;
    };
    void push(std::size_t list, Head& head, std::uint32_t item) {
        std::vector<Node>& nodes = nodes_[list];
        const std::uint32_t latest = head.node[list];
        if (latest != kEnd && nodes[latest].item == item) return;
        nodes.push_back(Node{item, latest});
        head.node[list] = static_cast<std::uint32_t>(nodes.size() - 1);
    }
    void walk(std::size_t list, const Head& head, std::vector<std::uint32_t>& out) const {
        const std::vector<Node>& nodes = nodes_[list];
        for (std::uint32_t n = head.node[list]; n != kEnd; n = nodes[n].next)
            out.push_back(nodes[n].item);
    }
    ProbeTable<Head> heads_;
    std::array<std::vector<Node>, Lists> nodes_;
};

// A cell of a uniform grid, column i and row j, as one key of a ProbeTable or CellIndex (the
// column in the high half, the row in the low: ProbeTable's hash mixes the halves).
inline std::uint64_t cell_key(std::int64_t i, std::int64_t j) noexcept {
    return (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(j & 0xffffffff);
}

// static_cast<std::int64_t>(std::floor(q)) for every q whose floor an int64 holds, without a
// call into the library (x86-64 before SSE4.1 has no instruction for floor): truncated towards
// zero, one less where that is above q.
inline std::int64_t floor_index(double q) noexcept {
    const auto i = static_cast<std::int64_t>(q);
    return static_cast<double>(i) > q ? i - 1 : i;
}

}  // namespace apci::run::detail
