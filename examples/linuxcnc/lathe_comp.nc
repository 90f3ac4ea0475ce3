%lathe_comp
; LinuxCNC's regression test tests/ccomp/lathe-comp/test.ngc (its lathecomp.ngc with the sides
; of the two passes swapped), in our DIN 66025 dialect. docs/linuxcnc-examples.md; the test
; linuxcnc_examples_tests runs this file and the original and compares the whole path.
;
; What was changed, and why:
; - Inches kept: G70 is our G20 (the numbers are the original's).
; - T2 M6 G43 H2 is D2, T7 M6 G43 H9 is D7, T0 M6 and G49 are D0: our D selects wz[n] of
;   examples/linuxcnc/lathe.tools (0.1 in nose diameter, cutting edge positions 2 and 7, as
;   LinuxCNC's Q2 and Q7) with its length (0, as H2 and H9 of the lathe tool tables).
; - Dropped: G64 (path blending; we run every block exactly). M2 is M30. F30 (in/min) stays.
; - G26 added: LinuxCNC's outside corners are arcs; our programs start in G25 (the ISG default).
; - Kept as written: G18, the first pass without compensation, then the pass G41 with
;   T2 and the pass G42 with T7, every G41/G42/G40 alone in its block, the R arcs.
; - tests/ccomp/lathe-comp is not shipped in LinuxCNC's package: the test makes its test.ngc
;   from lathecomp.ngc by swapping G41 and G42, and checks the result against the file's
;   SHA-256.
;
; LinuxCNC controls the imaginary tip of a turning tool; so does ours, with the cutting edge
; position (docs/compensation.md, "Turning tools"): the whole path is LinuxCNC's within 1e-3 mm.
; Our run warns SelfApproach once: the approach of the first compensated pass comes near the
; second pass's last arc, which is written with the other sense (G2 against the first pass's G3).
; ./build/bin/apcictl run examples/linuxcnc/lathe_comp.nc --tools examples/linuxcnc/lathe.tools

G70 G18 F30 G26

D0

G0 X.3 Z0
G40
G1 X.1
G3 X0 Z.1 R.1
G1 Z1
G2 R.25 X-.25 Z1.25
G3 R.25 X-.5 Z1.5
G1 Z1.75
G0 X.3

D2

G0 Z0
G41
G1 X.1
G3 X0 Z.1 R.1
G1 Z1
G2 R.25 X-.25 Z1.25
G3 R.25 X-.5 Z1.5
G1 Z1.75
G40
G0 X.3

D7

G0 Z1.85
G0 X-.3
G42
G1 X-.4
G2 X-.5 Z1.75 R.1
G1 Z1.5
G2 R.25 X-.25 Z1.25
G3 R.25 X0 Z1
G1 Z.1
G2 R.1 X.1 Z0
G40
G0 X.3

D0

M30
