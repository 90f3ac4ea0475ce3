%tc-walls-pocket.nc
; What a wall is (docs/compensation.md, figure 7): a round pocket widened in passes from the
; inside out in one compensated stretch: G41 counter-clockwise (tool D1, r = 5, inside), the full
; circles N50 (radius 10), N70 (18) and N90 (26) about the centre, joined by the lines N60 and
; N80. Each pass cuts over the contour of the one before: only the last, largest pass is the
; pocket's wall; the passes it encloses are cleared, no walls, and nothing is warned.
N10 G17 G90 G26 F1000 D1
N20 G0 X0 Y0 Z0
N30 G1 Z-5
N40 G41 G1 X10
N50 G3 I-10
N60 G1 X18
N70 G3 I-18
N80 G1 X26
N90 G3 I-26
N100 G40 G1 X15
N110 G0 Z5
N120 M30
