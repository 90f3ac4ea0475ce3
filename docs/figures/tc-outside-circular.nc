%tc-outside-circular.nc
; Outside corners with circular transitions, G26 (docs/compensation.md, figure 2): the tool
; (D1, r = 5) is on the outside of each corner (G42); an arc of radius r about the corner
; joins the offset elements: line-line at (40, 0), line-arc at (40, 30).
N10 G17 G90 G26 F1000 D1
N20 G0 X0 Y0 Z0
N30 G42
N40 G1 X40
N50 Y30
N60 G3 X20 Y30 I-10 J-10
N70 G40
N80 M30
