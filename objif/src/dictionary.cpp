// SPDX-License-Identifier: MIT
#include "objif/dictionary.h"

#include <cmath>

#include "objif/enum_names.h"

namespace objif {

std::string_view access_name(Access a) noexcept {
    static constexpr auto kNames =
        enum_names<Access::kRead, Access::kReadWrite>({"r", "w", "r/w"}, "?");
    return kNames(a);
}

Status check_value(const ObjectInfo& info, const Value& v) noexcept {
    if (v.type() != info.type) return Status::kTypeMismatch;
    const double x = v.numeric();
    if (!std::isfinite(x)) return Status::kInvalidValue;
    if (x < info.min) return Status::kValueTooLow;
    if (x > info.max) return Status::kValueTooHigh;
    return Status::kOk;
}

Status Dictionary::add(Module* module) {
    if (module == nullptr) return Status::kInvalidArgument;
    for (auto* m : modules_)
        if (m->bus() == module->bus()) return Status::kInvalidArgument;
    modules_.push_back(module);
    return Status::kOk;
}

Module* Dictionary::module(std::int32_t bus) const noexcept {
    for (auto* m : modules_)
        if (m->bus() == bus) return m;
    return nullptr;
}

// Handle layout: bits 31..16 the module's handle generation at issue time,
// bits 15..0 the slot number + 1. Slots are per address and never freed (the
// address space of the object map is small and fixed), so a handle stays
// cheap to check: one vector index and one compare. Issuing finds an
// address's slot by hash, so resolving every object of the map once costs
// time linear in the number of objects.
std::size_t AddressHash::operator()(const Address& a) const noexcept {
    std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a style, a field at a time
    for (const std::int32_t field : {a.bus, a.device, a.index, a.subindex}) {
        h ^= static_cast<std::uint32_t>(field);
        h *= 0x100000001b3ULL;
    }
    return static_cast<std::size_t>(h);
}

Status Dictionary::issue(const Address& a, Module* m, const ObjectInfo* info, Handle& out) {
    std::size_t slot = slots_.size();
    if (const auto it = slot_of_.find(a); it != slot_of_.end()) {
        slot = it->second;
    } else {
        if (slots_.size() >= (1u << kSlotBits) - 1) return Status::kNoMemory;
        slots_.push_back(Slot{a, m, info});
        slot_of_.emplace(a, slot);
    }
    out = (static_cast<Handle>(m->generation()) << kSlotBits) | static_cast<Handle>(slot + 1);
    return Status::kOk;
}

Status Dictionary::resolve(Descriptor& d, const ObjectInfo*& info, Module*& module) {
    const Address& a = d.address;
    Module* m = this->module(a.bus);
    if (m == nullptr || !m->present()) return Status::kNoSuchDevice;
    Status why = Status::kOk;
    const ObjectInfo* found = m->find(a, why);
    // A module that finds nothing names why; one that forgets is still refused.
    if (found == nullptr) return ok(why) ? Status::kObjectMissing : why;
    if (d.handle != kNoHandle) {
        const std::size_t slot = (d.handle & ((1u << kSlotBits) - 1));
        const auto gen = static_cast<std::uint16_t>(d.handle >> kSlotBits);
        if (slot == 0 || slot > slots_.size()) return Status::kStaleHandle;
        const Slot& s = slots_[slot - 1];
        if (gen != s.module->generation()) return Status::kStaleHandle;
        if (!(s.address == a)) return Status::kHandleMismatch;
    } else {
        Handle h = kNoHandle;
        const Status st = issue(a, m, found, h);
        if (!ok(st)) return st;
        d.handle = h;
    }
    info = found;
    module = m;
    return Status::kOk;
}

Status Dictionary::read(Descriptor& d, ValueType want, Value& out) {
    // A resolved descriptor keeps its handle even if a later check fails: the
    // firmware issues the handle on resolution, as it would on the board.
    const ObjectInfo* info = nullptr;
    Module* m = nullptr;
    Status st = resolve(d, info, m);
    if (!ok(st)) return st;
    if (!can_read(info->access)) return Status::kWriteOnly;
    if (want != info->type) return Status::kTypeMismatch;
    Value v;
    st = m->read(*info, d.address, v);
    if (!ok(st)) return st;
    out = v;
    return Status::kOk;
}

Status Dictionary::write(Descriptor& d, const Value& v) {
    const ObjectInfo* info = nullptr;
    Module* m = nullptr;
    Status st = resolve(d, info, m);
    if (!ok(st)) return st;
    if (!can_write(info->access)) return Status::kReadOnly;
    st = check_value(*info, v);
    if (!ok(st)) return st;
    // The hook may discard handles (TC Clean); the caller's handle was issued
    // under the old generation, which is exactly what makes it stale.
    return m->write(*info, d.address, v);
}

}  // namespace objif
