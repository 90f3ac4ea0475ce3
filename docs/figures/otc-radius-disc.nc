; docs/otc.md: RADIUS, DISC. The PLC commands 2 mm (otc-radius-disc.plc); the offset builds up
; over several cycles along the first edges, and at the G26 corners (arcs of the 5 mm tool
; radius) the normal turns faster than the ramp follows: the offset lags ([ISG-OTC-EN], point 3).
N10 G17 G90 F600
N20 D1 G26
N30 G0 X0 Y0
N40 #OTC ON [RADIUS DISC]
N50 G42 G1 X10
N60 X40
N70 Y30
N80 X10
N90 Y0
N100 G40 X0
N110 #OTC OFF
M30
