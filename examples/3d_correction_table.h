; [TNC-3D], "3D-Werkzeugkorrektur beim Stirnfräsen", Beispiel (blocks 12 to 14 of
; examples/3d_face_milling.h) with the tool as designed (tool 3 of examples/tools/3d_tools.tools,
; the 6 mm ball mill without deltas) and the regrinding in the correction table
; (examples/tools/3d_corrections.corr row 1: DR -0.1, DR2 -0.1): the same tips as the reground
; tool 1 of the tool table. FUNCTION CORRDATA RESET TCS leaves the table before the retreat.
; ./build/bin/apcictl run examples/3d_correction_table.h --tools examples/tools/3d_tools.tools --corr examples/tools/3d_corrections.corr
0  BEGIN PGM 3D_CORR MM
1  TOOL CALL 3 Z S8000
2  FUNCTION CORRDATA TCS #1
3  L X+0 Y+0 Z+50 R0 FMAX
4  L X+36.0084 Y+6.177 Z+10 R0 F1000
11 L X+36.0084 Y+6.177 Z-1.9209 R0
12 LN X+36.0084 Y+6.177 Z-1.9209 NX-0.4658107 NY+0 NZ+0.8848844 R0
13 LN X+36.0084 Y+6.177 Z-1.9209 NX-0.4658107 NY+0 NZ+0.8848844 TX+0.0000000 TY+0.6558846 TZ+0.7548612 R0 M128
14 LN X+36.0084 Y+6.177 Z-1.9209 NX-0.4658107 NY+0 NZ+0.8848844 R0 M128
15 FUNCTION CORRDATA RESET TCS
16 L Z+50 R0 FMAX M129
17 M30
18 END PGM 3D_CORR MM
