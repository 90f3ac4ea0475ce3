// SPDX-License-Identifier: MIT
#include "plc_unit.h"

#include <fmt/format.h>

#include <string>

#include "run_context.h"
#include "otc_unit.h"
#include "temp_unit.h"

namespace apci::run::exec {

namespace {

namespace otc = objif::map::otc;
namespace tcomp = objif::map::tempcomp;

}  // namespace

// ---- the scripted PLC (apcictl run --plc)

const std::uint64_t* PlcUnit::next_cycle() const noexcept {
    if (plc_ == nullptr || next_cycle_ >= plc_->cycle_writes().size()) return nullptr;
    return &plc_->cycle_writes()[next_cycle_].at;
}

// Writes every cycle entry whose cycle has come.
bool PlcUnit::due() {
    while (const std::uint64_t* at = next_cycle()) {
        if (*at > run_.cycles_run()) break;
        if (!write(plc_->cycle_writes()[next_cycle_++])) return false;
    }
    return true;
}

// After the program: the clock runs on to the remaining cycle entries.
bool PlcUnit::after_end() {
    while (const std::uint64_t* at = next_cycle()) {
        const std::uint64_t now = run_.cycles_run();
        if (*at > now && !run_.step_clock(*at - now)) return false;
        if (!due()) return false;
    }
    return true;
}

// The first event of a block: its block entries, after the moves before it have run.
bool PlcUnit::block(const nc::BlockOrigin& o) {
    if (plc_ == nullptr || plc_->block_writes().empty()) return true;
    if (o.block == last_block_ && o.line == last_line_) return true;
    last_block_ = o.block;
    last_line_ = o.line;
    if (o.block < 0) return true;
    bool synced = false;
    for (const PlcWrite& w : plc_->block_writes()) {
        if (w.at != static_cast<std::uint64_t>(o.block)) continue;
        if (!synced && !run_.run_clock()) return false;
        synced = true;
        if (!write(w)) return false;
    }
    return true;
}

bool PlcUnit::write(const PlcWrite& w) {
    const BlockRef at = w.when == PlcWrite::When::kBlock
                            ? BlockRef{static_cast<std::int64_t>(w.at), 0}
                            : BlockRef{};
    const std::string what =
        fmt::format("{}:{}: PLC {} = {}", plc_->file(), w.line, plc_unit_name(w), w.value);
    TempUnit& temp = run_.temp_unit();
    switch (w.unit) {
        case PlcWrite::Unit::kToolTempComp:
            return temp.needed(at, what) &&
                   temp.write(temp_object(tcomp::kIdxToolTempComp, w.index), w.value, at, what);
        case PlcWrite::Unit::kToolTempCompOn:
            return temp.needed(at, what) &&
                   temp.write(temp_object(tcomp::kIdxToolTempCompOn),
                              static_cast<std::int32_t>(w.value), at, what);
        case PlcWrite::Unit::kTempCompType:
            return temp.needed(at, what) &&
                   temp.write(temp_object(tcomp::kIdxTempCompType, run_.channel_axis(w.index)),
                              static_cast<std::int32_t>(w.value), at, what);
        case PlcWrite::Unit::kToolHolder:
        case PlcWrite::Unit::kToolHolderAxisB:
        case PlcWrite::Unit::kToolHolderAxisC: {
            const std::int32_t index =
                w.unit == PlcWrite::Unit::kToolHolder        ? tcomp::kIdxToolHolder
                : w.unit == PlcWrite::Unit::kToolHolderAxisB ? tcomp::kIdxHeadAxisB
                                                             : tcomp::kIdxHeadAxisC;
            return temp.needed(at, what) &&
                   temp.write(temp_object(index), static_cast<std::int32_t>(w.value), at, what);
        }
        case PlcWrite::Unit::kTempRampVelocity:
            return temp.needed(at, what) &&
                   temp.write(temp_object(tcomp::kIdxRampVelocity), w.value, at, what);
        case PlcWrite::Unit::kOtcRadiusOffset:
        case PlcWrite::Unit::kOtcOffset:
            break;
    }
    OtcUnit& otc_unit = run_.otc_unit();
    if (!otc_unit.needed(at, what)) return false;
    const std::int32_t sub =
        w.field == PlcWrite::Field::kCommand ? otc::kSubCommand : otc::kSubEnable;
    auto o = w.unit == PlcWrite::Unit::kOtcRadiusOffset
                 ? otc_object(otc::kDevChannel, otc::kIdxRadiusOffsetUnit, sub)
                 : otc_object(otc::kDevAxisUnits, run_.channel_axis(w.index), sub);
    return otc_unit.write(o, static_cast<std::int32_t>(w.value), at, what);
}

}  // namespace apci::run::exec
