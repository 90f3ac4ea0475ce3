; [TNC-3D], "3D-Werkzeugkorrektur beim Stirnfräsen", Beispiel: blocks 11 to 14 in a whole
; program. Tool data: examples/tools/3d_tools.tools (tool 1: the reground 6 mm ball mill).
;   11 L:  no compensation possible
;   12 LN without T, no TCPM: compensation perpendicular to the contour (T = the machine axis)
;   13 LN with T and M128: DL acts along T, DR2 along N
;   14 LN without T, M128: the tool stands perpendicular to the contour (T = N)
0  BEGIN PGM 3D_FACE MM
1  TOOL CALL 1 Z S8000
2  L X+0 Y+0 Z+50 R0 FMAX
3  L X+36.0084 Y+6.177 Z+10 R0 F1000
11 L X+36.0084 Y+6.177 Z-1.9209 R0
12 LN X+36.0084 Y+6.177 Z-1.9209 NX-0.4658107 NY+0 NZ+0.8848844 R0
13 LN X+36.0084 Y+6.177 Z-1.9209 NX-0.4658107 NY+0 NZ+0.8848844 TX+0.0000000 TY+0.6558846 TZ+0.7548612 R0 M128
14 LN X+36.0084 Y+6.177 Z-1.9209 NX-0.4658107 NY+0 NZ+0.8848844 R0 M128
15 L Z+50 R0 FMAX M129
16 M30
17 END PGM 3D_FACE MM
