// SPDX-License-Identifier: MIT
// The object dictionary: modules (one per BusNumber) declare their objects as
// tables of Entry rows (device, index range, subindex, name, type, access,
// range, default, read/write hooks). The Dictionary resolves descriptors,
// issues and checks handles, and applies the checks in the documented order:
//   bus/device, index, subindex, (handle), access, type, range, state.
// "state" is the hook's job: the rules live next to the object they guard.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "objif/descriptor.h"
#include "objif/object_info.h"
#include "objif/status.h"
#include "objif/value.h"

namespace objif {

// A module serves one bus. Most modules derive from TableModule below.
class Module {
public:
    virtual ~Module() = default;
    virtual std::int32_t bus() const noexcept = 0;
    virtual std::string_view name() const noexcept = 0;
    // False when the firmware lacks the option (e.g. optionTC): every access
    // answers kNoSuchDevice.
    virtual bool present() const noexcept { return true; }

    // Lookup: nullptr and `why` (kNoSuchDevice / kObjectMissing / kSubMissing) if absent.
    virtual const ObjectInfo* find(const Address& a, Status& why) const noexcept = 0;
    // Called after address, access, type and range checks passed.
    virtual Status read(const ObjectInfo& info, const Address& a, Value& out) = 0;
    virtual Status write(const ObjectInfo& info, const Address& a, const Value& v) = 0;

    virtual std::size_t object_count() const noexcept = 0;
    virtual const ObjectInfo& object_at(std::size_t i) const noexcept = 0;

    // Handle generation: bumping it makes every handle issued for this module stale.
    std::uint16_t generation() const noexcept { return generation_; }

protected:
    void discard_handles() noexcept {
        ++generation_;
        if (generation_ == 0) generation_ = 1;
    }

private:
    std::uint16_t generation_ = 1;
};

// One row of a module's object table: the description plus member-function
// hooks. A readable object must name a read hook, a writable one a write hook.
template <class M>
struct Entry {
    ObjectInfo info;
    Status (M::*read)(const ObjectInfo&, const Address&, Value&) = nullptr;
    Status (M::*write)(const ObjectInfo&, const Address&, const Value&) = nullptr;
};

// One hook: a member function, or none (nullptr). Whether one is given is kept beside it, so
// attach() checks it without comparing member pointers, which gcc does not accept in a
// constant expression where -fsanitize=undefined instruments them.
template <class F>
struct Hook {
    F function = nullptr;
    bool given = false;
    constexpr Hook() = default;
    // Implicit: tables write a member function or nullptr.
    constexpr Hook(std::nullptr_t) noexcept {}
    constexpr Hook(F f) noexcept : function(f), given(true) {}
};

// The rules a module attaches to one row of the object map (objif/map/objects.h): its read
// and write hooks, in the map's order. `name` repeats the row's name, so a table out of step
// with the map does not compile.
template <class M>
struct Hooks {
    std::string_view name;
    Hook<Status (M::*)(const ObjectInfo&, const Address&, Value&)> read;
    Hook<Status (M::*)(const ObjectInfo&, const Address&, const Value&)> write;
};

namespace detail {
// Not constexpr: attach() reaching one of these does not compile, and the compiler's message
// names it.
inline void hooks_out_of_step_with_the_object_map() noexcept {}
inline void a_read_hook_is_given_exactly_for_a_readable_object() noexcept {}
inline void a_write_hook_is_given_exactly_for_a_writable_object() noexcept {}
}  // namespace detail

// A module's table: each row of the map with its hooks. Checked at compile time: the hooks
// follow the map row by row, a readable object has a read hook and only a readable one, a
// writable object a write hook and only a writable one.
template <class M, std::size_t N>
consteval std::array<Entry<M>, N> attach(const std::array<ObjectInfo, N>& objects,
                                         const std::array<Hooks<M>, N>& hooks) {
    std::array<Entry<M>, N> table{};
    for (std::size_t i = 0; i < N; ++i) {
        const ObjectInfo& o = objects[i];
        const Hooks<M>& h = hooks[i];
        if (o.name != h.name) detail::hooks_out_of_step_with_the_object_map();
        if (can_read(o.access) != h.read.given)
            detail::a_read_hook_is_given_exactly_for_a_readable_object();
        if (can_write(o.access) != h.write.given)
            detail::a_write_hook_is_given_exactly_for_a_writable_object();
        table[i] = Entry<M>{o, h.read.function, h.write.function};
    }
    return table;
}

template <class M>
class TableModule : public Module {
public:
    const ObjectInfo* find(const Address& a, Status& why) const noexcept override {
        bool device_seen = false, index_seen = false;
        for (const auto& e : self().table()) {
            if (e.info.device != a.device) continue;
            device_seen = true;
            if (a.index < e.info.index_first || a.index > e.info.index_last) continue;
            index_seen = true;
            if (e.info.subindex == a.subindex) return &e.info;
        }
        why = !device_seen ? Status::kNoSuchDevice
                           : (!index_seen ? Status::kObjectMissing : Status::kSubMissing);
        return nullptr;
    }
    Status read(const ObjectInfo& info, const Address& a, Value& out) override {
        const auto& e = entry_of(info);
        if (!e.read) return Status::kWriteOnly;
        return (self_mut().*e.read)(info, a, out);
    }
    Status write(const ObjectInfo& info, const Address& a, const Value& v) override {
        const auto& e = entry_of(info);
        if (!e.write) return Status::kReadOnly;
        return (self_mut().*e.write)(info, a, v);
    }
    std::size_t object_count() const noexcept override { return self().table().size(); }
    const ObjectInfo& object_at(std::size_t i) const noexcept override {
        return self().table()[i].info;
    }

private:
    const M& self() const noexcept { return static_cast<const M&>(*this); }
    M& self_mut() noexcept { return static_cast<M&>(*this); }
    // ObjectInfo is the first member of Entry<M>, and find() hands out pointers
    // into the table, so the entry is recovered from the info's address.
    const Entry<M>& entry_of(const ObjectInfo& info) const noexcept {
        const auto tbl = self().table();
        const auto i = static_cast<std::size_t>(
            reinterpret_cast<const Entry<M>*>(&info) - tbl.data());
        return tbl[i];
    }
};

// Checks a value against an object's type and range: kTypeMismatch,
// kInvalidValue (NaN, infinity), kValueTooLow, kValueTooHigh or kOk.
Status check_value(const ObjectInfo& info, const Value& v) noexcept;

class Dictionary {
public:
    // The dictionary does not own modules; they outlive it (the Board owns both).
    Status add(Module* module);

    // Resolve the descriptor (issue or check its handle) and read. `want` is the
    // caller's expected type: a mismatch is kTypeMismatch.
    Status read(Descriptor& d, ValueType want, Value& out);
    // Resolve and write; on any error no state changes.
    Status write(Descriptor& d, const Value& v);
    // Resolve without access: fills info/module, issues the handle.
    Status resolve(Descriptor& d, const ObjectInfo*& info, Module*& module);

    Module* module(std::int32_t bus) const noexcept;
    std::span<Module* const> modules() const noexcept { return modules_; }

private:
    struct Slot {
        Address address;
        Module* module;
        const ObjectInfo* info;
    };
    static constexpr unsigned kSlotBits = 16;
    Status issue(const Address& a, Module* m, const ObjectInfo* info, Handle& out);


    std::vector<Module*> modules_;
    std::vector<Slot> slots_;  // slot i <-> handle low bits i+1
    std::unordered_map<Address, std::size_t, AddressHash> slot_of_;  // address -> slot i
};

}  // namespace objif
