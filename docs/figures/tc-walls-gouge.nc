%tc-walls-gouge.nc
; A real gouge (docs/compensation.md, figure 8): a boss with a keyhole cut up into it from
; below, milled outside with the leads of figure 6 (tool D1, r = 5, 10 mm across). The tool fits
; the round chamber (radius 10) but not the neck, 8 mm wide: its path up the neck's right side
; (N110) comes within 3 mm of the left side (N130), back down (N130) within 3 mm of the right
; side (N110), and round the neck's corners within 3 mm of the sides across. No corner rule sees
; it; the sides are walls, and the run warns every pair, each 2 mm deep, and marks it in the
; plot.
N10 G17 G90 G26 F1000 D1
N20 G0 X-10 Y55 Z0
N30 G1 Z-5
N40 G41 G1 X-10 Y40
N50 G3 X0 Y30 I10 J0
N60 G1 X22
N70 G2 X30 Y22 I0 J-8
N80 G1 Y-22
N90 G2 X22 Y-30 I-8 J0
N100 G1 X4
N110 Y-14.165
N120 G3 X-4 Y-14.165 I-4 J9.165
N130 G1 Y-30
N140 X-22
N150 G2 X-30 Y-22 I0 J8
N160 G1 Y22
N170 G2 X-22 Y30 I8 J0
N180 G1 X0
N190 G3 X10 Y40 I0 J10
N200 G40 G1 Y55
N210 G0 Z5
N220 M30
