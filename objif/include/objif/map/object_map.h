// SPDX-License-Identifier: MIT
// The board's object map, part 1: the numbers (bus, device, index, subindex) of every object,
// their values and limits. Part 2, objif/map/objects.h, declares each object (name, type,
// access, range, default, unit) from these. Both the host (libapci, apcictl) and the emulator
// use them: the map is the contract between a host and a board, so a host tool builds without
// the emulator. docs/object-map.md is the spec page.
#pragma once

#include <cstdint>

namespace objif::map {

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

inline constexpr std::int32_t kAxisCount = 8;
inline constexpr std::int32_t kSpoolerCapacity = 256;  // profiles (design)
// The interpolation cycle, 1 ms by default (docs/design.md section 4), in microseconds.
inline constexpr std::int32_t kDefaultInterpolationCycleUs = 1000;
inline constexpr std::int32_t kMinInterpolationCycleUs = 250;
inline constexpr std::int32_t kMaxInterpolationCycleUs = 10000;
// Firmware version the emulator reports: (major << 16) | (minor << 8) | patch.
inline constexpr std::int32_t kFirmwareVersion = (1 << 16) | (0 << 8) | 0;

// Options register bits.
inline constexpr std::int32_t kOptionTc = 0x01;   // optionTC: TC module (bus 1300) present
inline constexpr std::int32_t kOptionOtc = 0x02;  // OTC module (bus 1330) present (design)
inline constexpr std::int32_t kOptionTempComp = 0x04;  // temperature compensation (bus 1320)

// PU: the unit of the TC tool values RADIUS and WkzLen ([APCI-TC] Table 3: "in der mit PU
// angewählten Einheit"). The board moves in interpolation units, mm (positions, feeds,
// profiles); docs/object-map.md section 2.
enum PuUnit : std::int32_t { kPuMillimetre = 0, kPuMicrometre = 1, kPuInch = 2 };
// A value in the unit `pu` selects, in interpolation units (mm), and back. A micrometre is
// 1/1000 mm (a division, so 500 um is exactly 0.5 mm); an inch 25.4 mm.
constexpr double pu_to_millimetres(double v, std::int32_t pu) noexcept {
    return pu == kPuMicrometre ? v / 1000.0 : pu == kPuInch ? v * 25.4 : v;
}
constexpr double millimetres_to_pu(double mm, std::int32_t pu) noexcept {
    return pu == kPuMicrometre ? mm * 1000.0 : pu == kPuInch ? mm / 25.4 : mm;
}
}  // namespace board

// ---- TC module, bus 1300 ([APCI-TC] Tables 1-3; lost OCR numbers per docs/design.md section 3).
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
inline constexpr std::int32_t kSubSelectionMode = 22;  // int r/w: 237 perpendicular (default), 139 indirect, 138 direct
inline constexpr std::int32_t kSubLengthMode = 23;     // int r/w: 0 while compensating (default), 1 always
inline constexpr std::int32_t kSubCuttingEdge = 24;    // int r/w 0..9: the tool's cutting edge position

inline constexpr std::int32_t kToolCount = 1024;  // WKZINDEX 0..1023 ([APCI-TC] Table 3)
// Tool radius and length limits in PU units (design): a radius is a size, so not negative; a
// length correction may be negative.
inline constexpr double kMaxRadius = 1.0e6;
inline constexpr double kMaxLength = 1.0e6;

// CornerMode values: the G-codes that select them in NC programs (docs/design.md section 8).
inline constexpr std::int32_t kCornerLinear = 25;
inline constexpr std::int32_t kCornerCircular = 26;
// SelectionMode values: how the compensation reaches and leaves the contour, by the ISG G-codes
// ([ISG-PROG]; docs/compensation.md "Approach and departure").
inline constexpr std::int32_t kSelectionDirect = 138;         // the first block straight to the second's offset
inline constexpr std::int32_t kSelectionIndirect = 139;       // the first / G40 block approach and depart
inline constexpr std::int32_t kSelectionPerpendicular = 237;  // right-angle moves (the board's own)
// LengthMode values: when WkzLen acts on the group's ZAxis (docs/compensation.md "Tool length").
inline constexpr std::int32_t kLengthWhileCompensating = 0;  // [APCI-TC]'s: while STATUS Run
inline constexpr std::int32_t kLengthAlways = 1;             // every profile, as NC controls do
// Side values: the G-codes of the selection.
inline constexpr std::int32_t kSideNone = 40;
inline constexpr std::int32_t kSideLeft = 41;
inline constexpr std::int32_t kSideRight = 42;
}  // namespace tc

// ---- 3D tool compensation module, bus 1310 ([TNC-3D]; design numbers, docs/design.md section 4;
// docs/object-map.md section 6, docs/3d-compensation.md).
namespace comp3d {
inline constexpr std::int32_t kBus = 1310;
inline constexpr std::int32_t kDevSettings = 0;     // the tool in force, modes, the next LN
inline constexpr std::int32_t kDevTools = 1;        // tool table, Index = tool 0..1023
inline constexpr std::int32_t kDevCorrections = 2;  // correction table, Index = row 0..1023

// DeviceNumber 0.
inline constexpr std::int32_t kIdxTool = 1;            // int r/w 0..1023: TOOL CALL n
inline constexpr std::int32_t kIdxCallDeltas = 2;      // double r/w, Sub 0 DL 1 DR 2 DR2
inline constexpr std::int32_t kIdxCorrectionRow = 3;   // int r/w 0..1023
inline constexpr std::int32_t kIdxProgPath = 4;        // int r/w: 0 OFF, 1 IS CONTOUR
inline constexpr std::int32_t kIdxReference = 5;       // int r/w: 0 tip, 1 centre
inline constexpr std::int32_t kIdxTcpm = 6;            // int r/w: 0 off, 1 M128 / FUNCTION TCPM
inline constexpr std::int32_t kIdxAllowOversize = 7;   // int r/w: 1 M107, 0 M108
inline constexpr std::int32_t kIdxSide = 8;            // int r/w: 40 R0, 41 RL, 42 RR
inline constexpr std::int32_t kIdxHeadAxisB = 9;       // int r/w 0..7: board axis of B
inline constexpr std::int32_t kIdxHeadAxisC = 10;      // int r/w -1..7: board axis of C, -1 none
inline constexpr std::int32_t kIdxSurfaceNormal = 11;  // double r/w, Sub 0 NX 1 NY 2 NZ
inline constexpr std::int32_t kIdxToolVector = 12;     // double r/w, Sub 0 TX 1 TY 2 TZ
inline constexpr std::int32_t kIdxArm = 13;            // int r/w 0..7: the next profile is an LN
inline constexpr std::int32_t kIdxLastError = 14;      // int r/w: Refusal code; a write clears
inline constexpr std::int32_t kIdxDeltas = 20;         // double r, Sub 0..2: summed DL DR DR2
inline constexpr std::int32_t kIdxLastTip = 21;        // double r, Sub 0..2: last TCP X Y Z

// DeviceNumber 1 SubIndex (Index = tool).
inline constexpr std::int32_t kSubR = 1;
inline constexpr std::int32_t kSubR2 = 2;
inline constexpr std::int32_t kSubDl = 3;
inline constexpr std::int32_t kSubDr = 4;
inline constexpr std::int32_t kSubDr2 = 5;
// DeviceNumber 2 SubIndex (Index = row).
inline constexpr std::int32_t kSubCorrDl = 1;
inline constexpr std::int32_t kSubCorrDr = 2;
inline constexpr std::int32_t kSubCorrDr2 = 3;

inline constexpr std::int32_t kToolCount = 1024;
inline constexpr std::int32_t kCorrectionRows = 1024;
// Arm bits: what the next spooled profile carries.
inline constexpr std::int32_t kArmNormal = 0x01;
inline constexpr std::int32_t kArmToolVector = 0x02;
inline constexpr std::int32_t kArmLine = 0x04;  // compensate without vectors (L with RL/RR)
inline constexpr std::int32_t kNoHeadAxis = -1;
// Largest magnitude of a tool value, delta or vector component (the math's kMaxCoordinate).
inline constexpr double kMaxValue = 1e5;
}  // namespace comp3d

// ---- OTC module, bus 1330: online tool (wear) compensation ([ISG-OTC], ISG FCT-C20; design
// numbers, docs/design.md section 4; docs/object-map.md section 5, docs/otc.md).
namespace otc {
inline constexpr std::int32_t kBus = 1330;
inline constexpr std::int32_t kDevChannel = 0;    // #OTC settings, channel control unit
inline constexpr std::int32_t kDevAxisUnits = 1;  // per-axis control units, Index = board axis
inline constexpr std::int32_t kDevTool = 2;       // the current tool (V.G.WZ_AKT)

// DeviceNumber 0.
inline constexpr std::int32_t kIdxActive = 1;          // int r/w: V.G.OTC_ACTIVE; 1 ON, 0 OFF
inline constexpr std::int32_t kIdxProcessingType = 2;  // int r/w: 0 RADIUS .. 3 SURF_NORM_DIR
inline constexpr std::int32_t kIdxMode = 3;            // int r/w: 0 CONT, 1 DISC, 2 AUTO
inline constexpr std::int32_t kIdxWearConst = 4;       // double r/w: WEAR_CONST=, 0.1 um/m
inline constexpr std::int32_t kIdxWearConstSource = 5;  // int r/w: 0 tool, 1 programmed
inline constexpr std::int32_t kIdxAccWeight = 6;       // int r/w: ACC_WEIGHT 1..100 %
inline constexpr std::int32_t kIdxLastError = 7;       // int r/w: error number; a write clears
inline constexpr std::int32_t kIdxEffectiveWearConst = 8;  // double r: the constant in force
inline constexpr std::int32_t kIdxRampVelocity = 10;      // double r/w: mm/s
inline constexpr std::int32_t kIdxRampAcceleration = 11;  // double r/w: PU/s^2
inline constexpr std::int32_t kIdxKinematics = 12;     // int r/w: #KIN ID, 0 none, 4 B head
inline constexpr std::int32_t kIdxTrafo = 13;          // int r/w: #TRAFO 0 OFF, 1 ON
inline constexpr std::int32_t kIdxToolAxisB = 14;      // int r/w: board axis of B (default 4)
inline constexpr std::int32_t kIdxRadiusOffsetUnit = 20;  // otc_radius_offset, SubIndex below

// Control unit SubIndex (MC_CONTROL_SGN32_UNIT, [ISG-OTC] section 2.7), on DeviceNumber 0
// Index 20 and on every Index of DeviceNumber 1. Values in 0.1 um.
inline constexpr std::int32_t kSubCommand = 1;  // command_w: int r/w
inline constexpr std::int32_t kSubEnable = 2;   // enable_w: int r/w 0..1
inline constexpr std::int32_t kSubRequest = 3;  // request_r: int r
inline constexpr std::int32_t kSubState = 4;    // state_r: int r
// The axis unit ManualMvBackToStart ([ISG-OTC] section 2.7.3), beside otc_offset on the same
// Index (the board axis): X_Command, X_Enable, X_Request, X_State.
inline constexpr std::int32_t kSubBackCommand = 5;  // int r/w 0..1: a rising edge moves back
inline constexpr std::int32_t kSubBackEnable = 6;   // int r/w 0..1
inline constexpr std::int32_t kSubBackRequest = 7;  // int r: the command the unit takes
inline constexpr std::int32_t kSubBackState = 8;    // int r: 1 while the axis moves back

// DeviceNumber 2 (Sub 0 unless noted).
inline constexpr std::int32_t kIdxToolNumber = 1;      // int r/w 0..1023: a change is a tool change
inline constexpr std::int32_t kIdxToolType = 2;        // int r/w: P-TOOL-00001 typ 0..3
inline constexpr std::int32_t kIdxToolWearConst = 3;   // double r/w: P-TOOL-00030, V.G.WZ_AKT.WEAR_CONST
inline constexpr std::int32_t kIdxToolMaxInfeed = 4;   // double r/w: P-TOOL-00031, 0.1 um
inline constexpr std::int32_t kIdxToolTiltAngle = 5;   // double r/w: P-TOOL-00138, 0.0001 degree
inline constexpr std::int32_t kIdxWearRadius = 10;     // double r: V.G.WZ_AKT.WEAR_RADIUS
inline constexpr std::int32_t kIdxWearRadiusCont = 11;  // double r: V.G.WZ_AKT.WEAR_RADIUS_CONT
inline constexpr std::int32_t kIdxWear = 12;           // double r: V.G.WZ_AKT.WEAR[Sub], Sub = axis

inline constexpr std::int32_t kGrindingToolType = 2;  // P-TOOL-00001: 2 Schleifwerkzeug
inline constexpr std::int32_t kNoKinematics = 0;
inline constexpr std::int32_t kBHeadKinematics = 4;  // #KIN ID of the B head (docs/design.md section 8)
inline constexpr std::int32_t kAxisCount = 8;        // DeviceNumber 1: one unit per board axis
// ACC_WEIGHT in percent ([ISG-OTC] section 2.1).
inline constexpr std::int32_t kMinAccWeight = 1;
inline constexpr std::int32_t kMaxAccWeight = 100;
inline constexpr std::int32_t kDefaultAccWeight = 100;
// The ramp of a discrete offset (design): above 0, at most 1e6 mm/s (or /s^2).
inline constexpr double kMinRamp = 1e-9;
inline constexpr double kMaxRamp = 1.0e6;
inline constexpr double kDefaultRampVelocity = 0.5;      // mm/s
inline constexpr double kDefaultRampAcceleration = 1.0;  // mm/s^2
inline constexpr std::int32_t kDefaultToolAxisB = 4;     // A, B, C after X, Y, Z: B is axis 4
// P-TOOL-00138 in 0.0001 degree, within [-45, 45] degrees.
inline constexpr double kTiltUnitInDegrees = 1e-4;
inline constexpr double kMaxTiltDegrees = 45.0;
}  // namespace otc

// ---- Temperature compensation in tool direction, bus 1320 ([SIN-TEMP]; design numbers,
// docs/design.md section 4; docs/object-map.md section 7, docs/temperature-compensation.md).
namespace tempcomp {
inline constexpr std::int32_t kBus = 1320;
inline constexpr std::int32_t kDevice = 0;
inline constexpr std::int32_t kIdxToolTempComp = 1;   // double r/w, Sub 0..2: SD 42960 [0..2]
inline constexpr std::int32_t kIdxToolTempCompOn = 2;  // int r/w int32: MD 20390, != 0 on
inline constexpr std::int32_t kIdxTempCompType = 3;   // int r/w 0..255, Sub = axis: MD 32750
inline constexpr std::int32_t kIdxToolHolder = 4;     // int r/w 0..1: orientable tool holder
inline constexpr std::int32_t kIdxHeadAxisB = 5;      // int r/w 0..7: board axis of the head's B
inline constexpr std::int32_t kIdxHeadAxisC = 6;      // int r/w -1..7: of its C, -1 none
inline constexpr std::int32_t kIdxRampVelocity = 7;   // double r/w: PU/s, ramp to zero
inline constexpr std::int32_t kIdxOffset = 10;        // double r, Sub = axis: the displacement
inline constexpr std::int32_t kNoHeadAxis = -1;
inline constexpr double kDefaultRampVelocity = 1.0;  // PU/s: 1 um per 1 ms cycle
inline constexpr double kMaxValue = 1e5;
inline constexpr double kMinRampVelocity = 1e-6;  // PU/s: RampVelocity's range
inline constexpr double kMaxRampVelocity = kMaxValue;
}  // namespace tempcomp

}  // namespace objif::map
