%comp_g1
; LinuxCNC's example comp-g1.ngc ("a G1 straight feed entry and exit move with cutter radius
; compensation from the tool table"), in our DIN 66025 dialect. docs/linuxcnc-examples.md; the
; test linuxcnc_examples_tests runs this file and the original and compares the paths.
;
; What was changed, and why:
; - Inches converted to mm: every coordinate and I/J is the original's times 25.4, exactly
;   (our dialect has no G20); F60 (in/min) is F1524.
; - T4 M6 is D4 (our D selects wz[4] of the tool list examples/linuxcnc/comp_g1.tools: radius
;   12.7 mm, the original's 1 inch diameter); T0 M6 is D0. M2 is M30.
; - G17 G90 written out (the defaults of both); "J-1" and "I-1" keep their single centre word.
; - Kept as written: the uncompensated part outline first, then the same contour with G41 alone,
;   the entry move, the contour, G40 alone and the exit move, in the original's order.
; - G26 added: LinuxCNC's outside corners are arcs; our programs start in G25 (the ISG default).
;
; Our G41 block switches the compensation before its move (docs/compensation.md): the entry
; move (G1 X50.8 Y76.2) is our first compensated element, reached by a straight approach, and
; G40 ends the last one with a departure to its programmed end before the exit move runs. The
; contour between is LinuxCNC's path within 1e-3 mm.

(comp-g1.ngc)
(this file needs X-4 to X5 travel and Y-3 to Y5 travel: X-101.6 to X127, Y-76.2 to Y127)

G17 G90 G26
F1524 (set feed to 60 IPM)

(first, no compensation so we can see the part outline)
G0 Z25.4
G0 X50.8 Y76.2
G1 Z0
G2 X76.2 Y50.8 J-25.4 (part outline)
G1 Y-25.4
G2 X50.8 Y-50.8 I-25.4
G1 X-76.2
G1 X35.56 Y71.12
G2 X50.8 Y76.2 I15.24 J-20.32

(with compensation)
D4 (change tool: T4 M6)
G0 Z25.4
(straight line entries must not form a concave path or it is an error)
G0 X0 Y88.9 (change Y3.5 to Y4 to see the concave entry error: Y88.9, Y101.6)
G1 Z0
G41 (turn cutter comp left on)
G1 X50.8 Y76.2 (entry move)
G2 X76.2 Y50.8 J-25.4 (same path as above)
G1 Y-25.4
G2 X50.8 Y-50.8 I-25.4
G1 X-76.2
G1 X35.56 Y71.12
G2 X50.8 Y76.2 I15.24 J-20.32
G40 (turn cutter comp off)
G1 X76.2 Y88.9 (exit move can be any angle)
D0 (remove tool: T0 M6)

M30
