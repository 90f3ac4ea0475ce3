// SPDX-License-Identifier: MIT
// Object numbers of the emulated firmware (header-only, so drivers and tools
// can name objects without linking the emulator). docs/object-map.md is the
// spec page: type, access, range, default and rule of every object.
#pragma once

#include <cstdint>

namespace rwmos {

// ---- Board module, bus 1000 (design numbers; docs/object-map.md).
namespace board {
inline constexpr std::int32_t kBus = 1000;
inline constexpr std::int32_t kDevice = 0;
inline constexpr std::int32_t kIdxFirmwareVersion = 1;   // int r
inline constexpr std::int32_t kIdxOptions = 2;           // int r, bits below
inline constexpr std::int32_t kIdxAxisCount = 3;         // int r
inline constexpr std::int32_t kIdxInterpolationCycle = 4;  // int r/w, microseconds
inline constexpr std::int32_t kIdxPu = 5;                // int r/w, PuUnit
inline constexpr std::int32_t kIdxSpoolerCapacity = 6;   // int r, profiles
inline constexpr std::int32_t kIdxSpoolerFill = 7;       // int r, profiles
inline constexpr std::int32_t kIdxAxisPosition = 10;     // double r, SubIndex = axis 0..7
inline constexpr std::int32_t kIdxRs = 30;               // int w, rs() command

// Options register bits.
inline constexpr std::int32_t kOptionTc = 0x01;  // optionTC: TC module (bus 1300) present

// PU: the unit of lengths given to the firmware (RADIUS, WkzLen, positions).
enum PuUnit : std::int32_t { kPuMillimetre = 0, kPuMicrometre = 1, kPuInch = 2 };
}  // namespace board

// ---- TC module, bus 1300 (seed 003 Tables 1-3; lost OCR numbers per DESIGN.md section 3).
namespace tc {
inline constexpr std::int32_t kBus = 1300;
inline constexpr std::int32_t kDevInit = 0;    // Table 2: initialisation
inline constexpr std::int32_t kDevGroups = 1;  // Table 3: compensation groups

// DeviceNumber 0.
inline constexpr std::int32_t kIdxClean = 1;
inline constexpr std::int32_t kIdxAxisNr = 11;  // SubIndex 0 X, 1 Y, 2 Z
inline constexpr std::int32_t kIdxTcPlane = 12;
inline constexpr std::int32_t kIdxReInit = 13;
inline constexpr std::int32_t kIdxReset = 14;
inline constexpr std::int32_t kIdxRotAngle = 20;
inline constexpr std::int32_t kIdxRotCenterX = 21;
inline constexpr std::int32_t kIdxRotCenterY = 22;
inline constexpr std::int32_t kSubX = 0;
inline constexpr std::int32_t kSubY = 1;
inline constexpr std::int32_t kSubZ = 2;

// TcPlane values (the G-code numbers).
inline constexpr std::int32_t kPlaneXY = 17;
inline constexpr std::int32_t kPlaneZX = 18;
inline constexpr std::int32_t kPlaneYZ = 19;

// DeviceNumber 1: Index = group 1..kGroupCount, 0 = the active group.
inline constexpr std::int32_t kGroupCount = 3;
inline constexpr std::int32_t kActiveGroupIndex = 0;
inline constexpr std::int32_t kSubError = 1;
inline constexpr std::int32_t kSubReset = 2;
inline constexpr std::int32_t kSubStatus = 3;
inline constexpr std::int32_t kSubXAxis = 4;
inline constexpr std::int32_t kSubYAxis = 5;
inline constexpr std::int32_t kSubRadius = 7;
inline constexpr std::int32_t kSubWkzIndex = 8;
inline constexpr std::int32_t kSubLeft = 9;
inline constexpr std::int32_t kSubRight = 10;
inline constexpr std::int32_t kSubZAxis = 11;
inline constexpr std::int32_t kSubWkzLen = 12;
// Extension objects (design).
inline constexpr std::int32_t kSubCornerMode = 20;  // int r/w: 26 circular (default), 25 linear
inline constexpr std::int32_t kSubSide = 21;        // int r: 40 none, 41 left, 42 right

inline constexpr std::int32_t kToolCount = 1024;  // WKZINDEX 0..1023 (seed 003 Table 3)

// CornerMode values: the G-codes that select them in NC programs (DESIGN.md section 8).
inline constexpr std::int32_t kCornerLinear = 25;
inline constexpr std::int32_t kCornerCircular = 26;
// Side values: the G-codes of the selection.
inline constexpr std::int32_t kSideNone = 40;
inline constexpr std::int32_t kSideLeft = 41;
inline constexpr std::int32_t kSideRight = 42;
}  // namespace tc

}  // namespace rwmos
