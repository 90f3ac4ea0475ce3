%wr_quad_disc.nc
; ISG FCT-C20 section 2.2 "OTC mit diskreter Zustellung", without its #OTC lines (N50, N110).
; Tool data: examples/tools/wr_quad_disc.tools (D1, a grinding disc of radius 30 mm).
N20 G17G90
N22 D1 G25 ( Linearer Übergangssatz)
N40 G1 X0Y0Z0 F600

N55 G42
N60 G1 X2
N70 G1 X102
N80 G26 Y100 (Zirkularer Übergangssatz)

N90 X2
N95 Y0

N100 G40 G1 X0

N99999 M30
