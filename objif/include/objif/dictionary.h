// SPDX-License-Identifier: MIT
// The object dictionary: modules (one per BusNumber) declare their objects as
// tables of Entry rows (device, index range, subindex, name, type, access,
// range, default, read/write hooks). The Dictionary resolves descriptors,
// issues and checks handles, and applies the checks in the documented order:
//   bus/device, index, subindex, (handle), access, type, range, state.
// "state" is the hook's job: the rules live next to the object they guard.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "objif/descriptor.h"
#include "objif/status.h"
#include "objif/value.h"

namespace objif {

enum class Access : std::uint8_t { kRead = 1, kWrite = 2, kReadWrite = 3 };
constexpr bool can_read(Access a) noexcept { return (static_cast<int>(a) & 1) != 0; }
constexpr bool can_write(Access a) noexcept { return (static_cast<int>(a) & 2) != 0; }
std::string_view access_name(Access a) noexcept;  // "r", "w", "r/w"

inline constexpr double kInt32Min = -2147483648.0;
inline constexpr double kInt32Max = 2147483647.0;

// The static description of one object (or of a row of objects over an index
// range, e.g. compensation groups 0..3).
struct ObjectInfo {
    std::int32_t device = 0;
    std::int32_t index_first = 0;
    std::int32_t index_last = 0;
    std::int32_t subindex = 0;
    std::string_view name;
    ValueType type = ValueType::kInt32;
    Access access = Access::kReadWrite;
    double min = kInt32Min;  // inclusive range checked on write
    double max = kInt32Max;
    Value default_value;
    std::string_view rule;  // where the rule comes from ("[APCI-TC] Table 2", "design: ...")

    constexpr bool covers(const Address& a) const noexcept {
        return a.device == device && a.index >= index_first && a.index <= index_last &&
               a.subindex == subindex;
    }
};

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

    struct AddressHash {
        std::size_t operator()(const Address& a) const noexcept;
    };

    std::vector<Module*> modules_;
    std::vector<Slot> slots_;  // slot i <-> handle low bits i+1
    std::unordered_map<Address, std::size_t, AddressHash> slot_of_;  // address -> slot i
};

}  // namespace objif
