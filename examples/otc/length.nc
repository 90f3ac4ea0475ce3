; ISG FCT-C20 section 2.3 "Verschleiß in Werkzeuglänge" (its lines, its "..." left out).
; Tool data: examples/tools/wr_quad_disc.tools (D1, the grinding disc of [ISG-OTC] section 2.6,
; grinding_wear_const 100000 x 0.1 um/m): 1000 mm of path wear the disc by 10 mm on Z.
; ./build/bin/apcictl run examples/otc/length.nc --tools examples/tools/wr_quad_disc.tools
N30 D1                (Anwahl Datensatz für Schleifscheibe)
N40 G00 X0 Y0 Z0
N50 #OTC ON [LENGTH] (OTC-Anwahl)
N60 G1 X1000 F10000
N70 #OTC OFF          (OTC-Abwahl)
N80 M30
