%tc-korr-error.nc
; A notch narrower than the tool (docs/compensation.md, figure 5): the plate is milled outside
; (G42, tool D1, r = 5), and its notch is 4 mm wide. The offset of the notch bottom N90 would
; run backwards between its two inside corners: KorrError. The board holds: nothing spooled
; before or after the error moves, and the plot shows the programmed contour with the marker.
N10 G17 G90 G26 F1000 D1
N20 G0 X30 Y-15 Z0
N30 G42
N40 G1 X30 Y0
N50 X60
N60 Y30
N70 X32
N80 Y15
N90 X28
N100 Y30
N110 X0
N120 Y0
N130 X30
N140 G40
N150 M30
