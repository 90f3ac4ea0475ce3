; ISG FCT-C20 section 2.2 "Allgemeines #OTC Programmierbeispiel", without its #OTC lines
; (N40, N50, N90). Tool data: examples/tools/wr_quad_disc.tools.
N10 F10000
N20 D1 (Anwahl Datensatz für Schleifscheibe)
N30 G0 X0 Y0 Z0
N60 G41 G01 X50 (WRK-Anwahl, verschleißfreie Bewegung)
N70 X1000
N80 G40 X50 (WRK-Abwahl mit Verfahrbewegung um WZR abzubauen)
N100 G00 X50
N199 M30
