// SPDX-License-Identifier: MIT
// The 3D tool compensation's correction table ([TNC-3D]: the control offsets the tool by
// "die Summe der Deltawerte aus der Werkzeugverwaltung, dem Werkzeugaufruf und den
// Korrekturtabellen"; "programmierten Werkzeugkorrektur (Werkzeugaufruf oder
// Korrekturtabelle)"). A Klartext program selects a row with FUNCTION CORRDATA TCS #n and
// leaves it with FUNCTION CORRDATA RESET TCS (row 0: no correction). The file, in the form of
// the tool list: one "corr[n].dl|dr|dr2 value" a line, in mm, '#' comments, blank lines; rows
// 1..1023, a value within the board's -1e5..1e5 (bus 1310 DeviceNumber 2). docs/nc-programs.md
// ("Correction table") is the spec.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "apci/nc/block.h"
#include "apci/nc/diagnostic.h"

namespace apci::nc {

// Rows 1..kMaxCorrectionRow; the board's table has rows 0..1023, row 0 being no correction.
inline constexpr int kMaxCorrectionRow = 1023;
// The range of a delta value (the board's object range, docs/object-map.md section 6.2).
inline constexpr double kCorrectionLimit = 1e5;

struct CorrectionRow {
    int row = 0;                           // 1..kMaxCorrectionRow
    double dl = 0.0, dr = 0.0, dr2 = 0.0;  // mm; unset values are 0
};

class CorrectionTable {
  public:
    // The row, or null when the table does not define it.
    const CorrectionRow* find(int row) const noexcept;
    // The rows in the order of their numbers.
    const std::vector<CorrectionRow>& rows() const noexcept { return rows_; }
    bool empty() const noexcept { return rows_.empty(); }

  private:
    friend Result<CorrectionTable> parse_correction_table(std::string_view text,
                                                          std::string_view file);
    CorrectionRow& define(int row);
    std::vector<CorrectionRow> rows_;
};

// Errors name file, line and column and what was expected; a value given twice is refused.
Result<CorrectionTable> parse_correction_table(std::string_view text, std::string_view file);
Result<CorrectionTable> load_correction_table(const std::string& path);

}  // namespace apci::nc
