// SPDX-License-Identifier: MIT
#include "dry_run.h"

#include <fmt/format.h>

#include "objif/map/object_map.h"
#include "objif/map/objects.h"

namespace apci::run::detail {

namespace {

namespace map = objif::map;

// The emulator's axes run to where the board's stand at the rapid feed, at most this many
// cycles (a rapid over the whole +-1e5 range takes far fewer).
constexpr std::uint64_t kPlaceCycles = 1'000'000'000;

apci::ObjectDescriptor descriptor_of(std::int32_t bus, const objif::ObjectInfo& o) {
    return apci::object(bus, o.device, o.index_first, o.subindex);
}

// One object's value copied from `from` to `to` as its type says; false where either refuses.
bool copy_object(apci::Board& from, apci::Board& to, std::int32_t bus, const objif::ObjectInfo& o) {
    auto src = descriptor_of(bus, o);
    auto dst = descriptor_of(bus, o);
    if (o.type == objif::ValueType::kDouble) {
        const auto v = from.read_double(src);
        return v.ok() && to.write_double(dst, v.value).ok();
    }
    const auto v = from.read_int(src);
    return v.ok() && to.write_int(dst, v.value).ok();
}

// The emulator set up as `board` stands; false where the board has no TC module (its axis
// numbers cannot be read: nothing of the program is compensated) or the emulator refused.
bool set_up_like(apci::Board& board, apci::Board& emu) {
    for (const objif::ObjectInfo& o : map::tc::kObjects) {
        if (o.device != map::tc::kDevInit || o.access != objif::Access::kReadWrite) continue;
        if (!copy_object(board, emu, map::tc::kBus, o)) return false;
    }
    for (const objif::ObjectInfo& o : map::board::kObjects)
        if (o.index_first == map::board::kIdxInterpolationCycle &&
            !copy_object(board, emu, map::board::kBus, o))
            return false;
    const auto at = board.motion_status();
    if (!at.ok()) return false;
    apci_direct_command ja{};
    ja.code = APCI_DIRECT_JA;
    ja.axes = 0xFF;
    ja.feed = 0.0;
    for (int i = 0; i < APCI_AXIS_COUNT; ++i) ja.target[i] = at.value.position[i];
    if (!emu.direct(ja).ok()) return false;
    const auto placed = emu.run_until_idle(kPlaceCycles);
    return placed.ok() && (placed.value.flags & APCI_MOTION_IDLE) != 0u;
}

}  // namespace

std::optional<nc::Diagnostic> self_approach_dry_run(apci::Board& board, const RunInputs& inputs,
                                                    const ProgramSource& source,
                                                    const RunSettings& settings) {
    apci::Board emu("emu:");
    if (!emu.is_open() || !set_up_like(board, emu)) return std::nullopt;
    RunSettings dry = settings;
    dry.self_approach = SelfApproachMode::kError;
    dry.dry_run_first = false;
    RunSink nothing;
    auto ran = run_program(emu, nothing, inputs, source, dry);
    if (!ran.ok()) return std::nullopt;  // refused as the board's own run will refuse it
    for (const RunError& e : ran.value().errors) {
        if (e.code != "SelfApproach") continue;
        nc::Diagnostic d;
        d.kind = nc::ErrorKind::kProgramRule;
        d.file = source.name;
        d.line = e.block.line;
        d.column = 1;
        d.block = e.block.number;
        d.message = fmt::format(
            "{} (found by a dry run on the embedded emulator set up as the board stands, "
            "before anything moved: --self-approach error)",
            e.message);
        return d;
    }
    return std::nullopt;
}

}  // namespace apci::run::detail
