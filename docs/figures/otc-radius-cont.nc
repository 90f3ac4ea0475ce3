; docs/otc.md: RADIUS, CONT. 100 mm of contour at [ISG-OTC]'s 100000 x 0.1 um/m wear the disc by
; 1 mm: the tool centre comes closer to the contour along the path; the approach after G41 and
; the departure after G40 are wear-free ([ISG-OTC] section 2.2).
N10 G17 F3000
N20 D1
N30 G0 X0 Y0
N40 #OTC ON [RADIUS CONT]
N50 G41 G1 X10
N60 X110
N70 G40 X120
N80 #OTC OFF
M30
