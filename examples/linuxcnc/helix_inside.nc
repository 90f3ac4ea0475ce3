%helix_inside
; LinuxCNC's ngcgui subroutine helix.ngc ("in/out cutting, cw/ccw dir with radius comp,
; D-holes"), its inside cut, in our DIN 66025 dialect. docs/linuxcnc-examples.md; the test
; linuxcnc_examples_tests runs this file and the original (the program ngcgui makes: the
; preamble in_std.ngc, o<helix> call, m2) and compares the paths.
;
; LinuxCNC ships no circular pocket widened in passes under cutter radius compensation:
; cpocket.gcmc (gcmc_lib) widens a hole in passes but puts the tool radius into its own
; geometry (no G41/G42), and the helical hole millings with G41 (helix.ngc, o100 of
; useful-subroutines.ngc, mmount.ngc's o100) mill one diameter, in depth passes. This is
; helix.ngc's inside cut, a hole in depth passes on one circle, without the D flat (d_angle 0).
;
; The call: helix's defaults and those of its shipped callers hole_circle.ngc and
; helix_rtheta.ngc (T1, 2000 rpm, feed 10 in/min, dir 3 = ccw, inside 1, zsafe 0.5 in, face
; and D angle 0, zstart 0); the hole, which nothing in LinuxCNC gives helix, is LinuxCNC's own
; helical hole example (useful-subroutines.ngc: "o100 call [.25] [0] [.01] [.0625] [.25]
; [.0625]", "T1 is a 1/16th end mill"): centre X0.25 Y0, diameter 0.25 in, depth 0.0625 in,
; half the tool's diameter down per lap (o100's step): zincr 0.03125 in. In an inch
; configuration with preamble in_std.ngc (Smithy's, which offer helix.ngc in ngcgui).
; T1 1/16 in: radius 0.79375 mm (helix.tools).
;
; Block delete: helix's G41 stands on a block-delete line ("/ g41"). LinuxCNC runs it with
; block delete off, its default (and rs274's): the compensation is on, as here, where G41 is an
; ordinary block.
;
; What was changed, and why:
; - Inches converted to mm: every length is LinuxCNC's value times 25.4 (our dialect has no
;   G20); the feed 10 in/min is F254.
; - The subroutines are unrolled (our dialect has none): helix.ngc and ngcgui's entry and
;   loadtool. Their arithmetic (the start point opposite the flat, the quarter arc entry of
;   o<entry> with the tool's diameter plus 0.001 in, the depth of each lap; in degrees and
;   double precision, as rs274 computes) was done when this file was written, the results
;   written to 6 decimals of a mm.
; - T1 M6 G43 (o<loadtool>) is D1 (tool lengths 0).
; - Dropped, as our dialect has no such words: G20 G49 G94 G54 and G64 P (in_std.ngc), S2000 M3.
;   m2 is M30.
; - Kept as written: every move in the original's order, G41 alone before the entry arc, the
;   half circles of each lap (the first going down, the second level), the zero-length G1
;   between them (the D flat, of zero length with d_angle 0), the G0 Z moves under G41, G40
;   alone.
; - G26 added: LinuxCNC's outside corners are arcs; our programs start in G25 (the ISG default).
G17 G40 G90 G26 ; in_std.ngc: g17 g20 g40 g49 g90 g94 g54 g64

(o<helix> call [1][2000][10][3][1][0.0625][0.03125][0.5][0.25][0][0.25][0][0][0][0][1][0][0])
D1 ; T1 M6 G43 (o<loadtool>)
G40 ; G40: cutter radius compensation off
F254 ; f10: feed in inches per minute
G0 Z12.7
G0 X3.98145 Y0.80645 Z12.7 ; pre-entry point
G41 ; "/ g41": cutter radius comp left of path (block delete off)
G3 X3.175 Y0 I0 J-0.80645 ; entry arc
G0 Z1.27 ; hardcoded delta
G1 Z0 ; plunge
G3 X9.525 Y0 I3.175 J0 Z-0.79375 ; lap 1: down to Z-0.79375
G1 X9.525 Y0
G3 X3.175 Y0 I-3.175 J0 Z-0.79375
G3 X9.525 Y0 I3.175 J0 Z-1.5875 ; lap 2: down to Z-1.5875
G1 X9.525 Y0
G3 X3.175 Y0 I-3.175 J0 Z-1.5875
G3 X9.525 Y0 I3.175 J0 Z-1.5875 ; final traverse at full depth
G1 X9.525 Y0
G3 X3.175 Y0 I-3.175 J0 Z-1.5875
G0 Z12.7
G40

M30 (m2)
