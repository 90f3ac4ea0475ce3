%tc-outside-linear.nc
; Outside corners with linear transitions, G25 (docs/compensation.md, figure 3): at a turn of
; 60 degrees the offset lines are extended until they meet; at 150 degrees each is extended by
; r only and a chamfer joins them (the bounded form). Tool D1, r = 5, on the outside (G42).
N10 G17 G90 G25 F1000 D1
; 60 degrees at (40, 0)
N20 G0 X0 Y0 Z0
N30 G42
N40 G1 X40
N50 X55 Y25.980762
N60 G40
; 150 degrees at (110, 0)
N70 G0 X70 Y0
N80 G42
N90 G1 X110
N100 X75.358984 Y20
N110 G40
N120 M30
