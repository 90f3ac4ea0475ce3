; ISG FCT-C20 section 2.4 "OTC-Schleifen mit Kinematiktyp 4" (its lines; its "..." left
; out, M30 added). #KIN ID[4] is the B head (docs/design.md section 8). The PLC commands 1 mm along
; the tool: examples/otc/plc/tool_dir.plc.
; ./build/bin/apcictl run examples/otc/tool_dir.nc --tools examples/tools/wr_quad_disc.tools --plc examples/otc/plc/tool_dir.plc
N30 D1 (Anwahl Datensatz für Schleifscheibe)
N40 G00 X0 Y0 Z300 B0
N50 #KIN ID[4]
N50 #TRAFO ON
N60 G00 B45
N70 G01 X100 Z50 F1000
N80 #OTC ON [TOOL_DIR, DISC] (OTC-Anwahl)
N90 $FOR P1=0, 20, 1
N100 G91 G01 X10 Z-10 F2000
N110 X-10 Z10
N120 $ENDFOR
N120 #OTC OFF (OTC-Abwahl)
N130 #TRAFO OFF
N140 M30
