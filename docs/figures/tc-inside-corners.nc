%tc-inside-corners.nc
; Inside corners (docs/compensation.md, figure 1): the tool (D1, r = 5) is on the inside of
; each corner, so both offset elements are cut back to their intersection.
N10 G17 G90 G26 F1000 D1
; line-line: G41 (tool left), the path turns left at (40, 0)
N20 G0 X0 Y0 Z0
N30 G41
N40 G1 X40
N50 Y30
N60 G40
; arc-arc: two counter-clockwise arcs meeting at (100, 0), the tool left, inside both
N70 G0 X60 Y0
N80 G41
N90 G3 X100 Y0 I20 J20
N100 G3 X75 Y25 I-25 J0
N110 G40
N120 M30
