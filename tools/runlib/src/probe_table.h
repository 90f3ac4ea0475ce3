// SPDX-License-Identifier: MIT
// Tables the self-approach check keeps without an allocation per entry: a table over 64-bit
// keys with a value each (open addressing), a set of keys, and the items of a uniform grid's
// cells. Shared by the check's grid (self_approach.cpp) and its wall model's loops
// (wall_model.cpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace apci::run::detail {

// A table over 64-bit keys, each with a value: open addressing, linear probing, at most half
// full, the slots doubling from 1024. No allocation per key once the slots have grown.
template <class Value>
class ProbeTable {
  public:
    struct Slot {
        std::uint64_t key = 0;
        bool taken = false;
        Value value{};
    };
    // The key's slot, and whether it is new (its value then the default, for the caller to set).
    std::pair<Slot&, bool> emplace(std::uint64_t key) {
        if (2 * (count_ + 1) > slots_.size()) grow();
        Slot& s = slots_[find(slots_, key)];
        if (s.taken) return {s, false};
        s.key = key;
        s.taken = true;
        ++count_;
        return {s, true};
    }
    // The key's slot, or null.
    const Slot* get(std::uint64_t key) const {
        if (slots_.empty()) return nullptr;
        const Slot& s = slots_[find(slots_, key)];
        return s.taken ? &s : nullptr;
    }
    // Empty, keeping the memory.
    void clear() {
        std::fill(slots_.begin(), slots_.end(), Slot{});
        count_ = 0;
    }

  private:
    // The key's slot, or the empty one where it would go.
    static std::size_t find(const std::vector<Slot>& slots, std::uint64_t key) {
        const std::size_t mask = slots.size() - 1;
        // Mixed so that the high half reaches the low bits (a grid cell's key is its row and
        // column in the high and low half).
        const std::uint64_t h = (key ^ (key >> 31)) * 0x9E3779B97F4A7C15ULL;
        std::size_t i = (h ^ (h >> 32)) & mask;
        while (slots[i].taken && slots[i].key != key) i = (i + 1) & mask;
        return i;
    }
    [[gnu::noinline]] void grow() {
        std::vector<Slot> bigger(slots_.empty() ? 1024 : 2 * slots_.size());
        for (const Slot& s : slots_)
            if (s.taken) bigger[find(bigger, s.key)] = s;
        slots_.swap(bigger);
    }
    std::vector<Slot> slots_;
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

// The items of a uniform grid's cells: per cell (a 64-bit key, in a ProbeTable) a list of item
// positions, the latest first, the lists' nodes in one array: no allocation per cell or per
// item once the arrays have grown.
class CellIndex {
  public:
    // Adds the item to the cell, unless it is the cell's latest already.
    void add(std::uint64_t cell, std::uint32_t item) {
        auto [slot, fresh] = heads_.emplace(cell);
        if (!fresh && nodes_[slot.value.node].item == item) return;
        nodes_.push_back(Node{item, fresh ? kEnd : slot.value.node});
        slot.value.node = static_cast<std::uint32_t>(nodes_.size() - 1);
    }
    // Appends the items of the cell to `out`.
    void append(std::uint64_t cell, std::vector<std::uint32_t>& out) const {
        const auto* slot = heads_.get(cell);
        if (slot == nullptr) return;
        for (std::uint32_t n = slot->value.node; n != kEnd; n = nodes_[n].next)
            out.push_back(nodes_[n].item);
    }
    // Empty, keeping the memory.
    void clear() {
        heads_.clear();
        nodes_.clear();
    }

  private:
    static constexpr std::uint32_t kEnd = ~std::uint32_t{0};
    struct Head {
        std::uint32_t node = kEnd;  // the cell's latest node
    };
    struct Node {
        std::uint32_t item;
        std::uint32_t next;
    };
    ProbeTable<Head> heads_;
    std::vector<Node> nodes_;
};


}  // namespace apci::run::detail
