; ISG FCT-C20 section 2.5 "OTC-Schleifen mit Kinematiktyp 4", SURF_NORM_DIR (its lines,
; M30 added). #HSC is accepted and reported as not emulated. The PLC commands 0.5 mm along the
; surface normal through the third axis's unit: examples/otc/plc/surf_norm_dir.plc.
; ./build/bin/apcictl run examples/otc/surf_norm_dir.nc --tools examples/tools/wr_quad_disc.tools --plc examples/otc/plc/surf_norm_dir.plc
N30 D1 (Anwahl Datensatz für Schleifscheibe)
N40 G00 X0 Y0 Z300 B0
N50 #KIN ID[4]
N50 #TRAFO ON
N60 G00 B0
N70 G01 X100 Z50 F1000
N80 #OTC ON [SURF_NORM_DIR, DISC] (OTC-Anwahl)
N85 #HSC ON[BSPLINE PATH_DEV 5 MERGE = 0]
N90 $FOR P1=0, 5, 1
N100 G91 G01 X3 Z-3 F2000
N110 X2 Z-2
N120 X5 Z-2
N130 X5 Z-1
N140 X5
N150 X5 Z-1
N160 X5 Z-2
N170 X2 Z-2
N180 X3 Z-3
N190 X-3 Z3 F2000
N200 X-2 Z2
N210 X-5 Z2
N220 X-5 Z1
N230 X-5
N240 X-5 Z1
N250 X-5 Z2
N260 X-2 Z2
N270 X-3 Z3
N280 $ENDFOR
N290 #HSC OFF
N300 #OTC OFF (OTC-Abwahl)
N310 #TRAFO OFF
M30
