; ISG FCT-C20 section 2.2 "Allgemeines #OTC Programmierbeispiel", complete with its #OTC lines.
; RADIUS, AUTO: the continuous wear (grinding_wear_const 100000 x 0.1 um/m) of the compensated
; contour N70, the approach N60 and the departure N80 wear-free. Tool data:
; examples/tools/wr_quad_disc.tools.
; ./build/bin/apcictl run examples/otc/general.nc --tools examples/tools/wr_quad_disc.tools
N10 F10000
N20 D1 (Anwahl Datensatz für Schleifscheibe)
N30 G0 X0 Y0 Z0
N40 #OTC[RADIUS, AUTO] (OTC-Betriebsart + Mode festlegen)
N50 #OTC ON (OTC-Anwahl)
N60 G41 G01 X50 (WRK-Anwahl, verschleißfreie Bewegung)
N70 X1000
N80 G40 X50 (WRK-Abwahl mit Verfahrbewegung um WZR abzubauen)
N90 #OTC OFF (OTC-Abwahl)
N100 G00 X50
N199 M30
