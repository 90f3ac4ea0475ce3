%tc-walls-leads.nc
; What a wall is (docs/compensation.md, figure 6): a boss milled outside as CAM writes it, G41
; (tool D1, r = 5) on a straight lead-in N40, a tangent quarter arc N50 onto the contour at the
; middle of its top, the closed contour N60..N140 clockwise, a tangent quarter arc N150 off it
; and G40 on the straight lead-out N160. The contour's last path runs over the lead-in arc and its
; first over the lead-out arc: the leads are no walls (the tool only passes there), so nothing
; is warned.
N10 G17 G90 G26 F1000 D1
N20 G0 X-10 Y55 Z0
N30 G1 Z-5
N40 G41 G1 X-10 Y40
N50 G3 X0 Y30 I10 J0
N60 G1 X22
N70 G2 X30 Y22 I0 J-8
N80 G1 Y-22
N90 G2 X22 Y-30 I-8 J0
N100 G1 X-22
N110 G2 X-30 Y-22 I0 J8
N120 G1 Y22
N130 G2 X-22 Y30 I8 J0
N140 G1 X0
N150 G3 X10 Y40 I0 J10
N160 G40 G1 Y55
N170 G0 Z5
N180 M30
