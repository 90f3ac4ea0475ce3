%tc-closed-contour.nc
; A closed contour with approach and departure (docs/compensation.md, figure 4): a plate with
; a rounded corner and a notch as wide as the tool, milled outside with G42 (tool D1, r = 5)
; and circular transitions. A lead-in element N40 and a lead-out element N150: under G139 (the
; programs' initial state) the lead-in is the approach and G40 leaves the tool at the lead-out's
; offset end, away from the part.
N10 G17 G90 G26 F1000 D1
N20 G0 X30 Y-20 Z0
N30 G42
N40 G1 X30 Y0
N50 X80
N60 Y30
N70 G3 X60 Y50 I-20 J0
N80 G1 X45
N90 Y35
N100 X35
N110 Y50
N120 X0
N130 Y0
N140 X30
N150 Y-20
N160 G40
N170 M30
