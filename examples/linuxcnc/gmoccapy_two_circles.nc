%gmoccapy_two_circles
; LinuxCNC's example gmoccapy_2_tools_with_cutter_radius_compensation.ngc ("testprogram to
; mill two circles with cutter radius compensation and two different tools"), in our DIN 66025
; dialect. docs/linuxcnc-examples.md; the test linuxcnc_examples_tests runs this file and the
; original and compares the paths.
;
; What was changed, and why:
; - Already in mm (G21): the coordinates are the original's.
; - T3 M6 G43 is D3, T1 M6 G43 is D1 (our D selects wz[n] of the tool list
;   examples/linuxcnc/gmoccapy.tools: radius 1.5 and 0.5 mm). No G43: tool lengths are 0.
; - Dropped, as our dialect has no such words: G21 (mm is our only unit), G54, G61, G49, G80,
;   S, M3, M5, M7, M8, M9, the (MSG, ...) message and M1 (optional stop). M2 is M30.
; - Kept as written: G17 G40 G90, every move in the original's order, G41 alone before each
;   arc entry, the full circles "G3 I-20" and "G3 I-15", the arcs out with G41 still on, the
;   G0 Z30 under G41, G40 alone after it.
; - G26 added: LinuxCNC's outside corners are arcs; our programs start in G25 (the ISG default).
;
; Our run warns nothing: the arcs in and out of the first circle (tool 3) are its leads, and the
; first circle, a pocket's pass, clears the second, smaller one inside it (tool 1) at the same
; depth (docs/compensation.md, "What is a wall").

; set the basic settings, this should be
; on every program the beginning
G17
G40
G90
G26

; get the first tool
D3

; go to center of the workpiece
G0 X50 Y50
G0 Z30

G0 Z10
F250
G1 Z0

; tool radius compensation
; go in circle with lower feed rate
G41
G3 X70 Y50 Z-1 I10 J0

; make first circle with normal feed
F2000
G3 I-20

; out of the workpiece
G3 X50 Y50 Z1 I-10 J0
G0 Z30

; turn off cutter radius compensation, otherwise no tool change is possible
G40
D1

; go again to the center of the workpiece
G0 X50 Y50
G0 Z10

G0 Z10
F400
G1 Z1

; Werkzeugradienkompensation ein
; Anfahrradius mit Eintauchgeschwindigkeit
G41
G3 X65 Y50 Z-1 I7.5 J0

; 2. Kreis mit Vorschubgeschwindigkeit fräsen
F1000
G3 I-15

; Aus dem Werkstück
G3 X50 Y50 Z1 I-7.5 J0
G0 Z30

G0 Z30
G0 X50 Y50

M30 ; program end
