; ISG FCT-C20 sections 2.3 and 2.3.1: the LENGTH example with a disc tilted by 30 degrees
; (examples/tools/otc_tilt.tools: grinding_disc_tilt_angle 300000 x 0.0001 degree). The 10 mm of
; wear split over X (sin 30) and Z (cos 30).
; ./build/bin/apcictl run examples/otc/length_tilt.nc --tools examples/tools/otc_tilt.tools
N30 D1
N40 G00 X0 Y0 Z0
N50 #OTC ON [LENGTH]
N60 G1 X1000 F10000
N70 #OTC OFF
N80 M30
