%wr_quad_disc.nc
; ISG FCT-C20 section 2.2 / [ISG-OTC-EN] "OTC mit diskreter Zustellung", complete with its #OTC lines.
; Tool data: examples/tools/wr_quad_disc.tools (D1, a grinding disc of radius 30 mm). The PLC
; commands the 2 mm of [ISG-OTC-EN]: examples/otc/plc/wr_quad_disc.plc (or -2 mm: ..._negative.plc).
; ./build/bin/apcictl run examples/otc/wr_quad_disc.nc --tools examples/tools/wr_quad_disc.tools --plc examples/otc/plc/wr_quad_disc.plc
N20 G17G90
N22 D1 G25 ( Linearer Übergangssatz)
N40 G1 X0Y0Z0 F600

N50 #OTC ON[RADIUS DISC]
N55 G42
N60 G1 X2
N70 G1 X102
N80 G26 Y100 (Zirkularer Übergangssatz)

N90 X2
N95 Y0

N100 G40 G1 X0
N110 #OTC OFF

N99999 M30
