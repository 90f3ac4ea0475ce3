; [TNC-3D], "Werkstückaufmaß erzeugen, CAM-Ausgabe Kugelmitte": the 6 mm ball mill leaves a
; stock allowance of 0.2 mm. The CAM points are ball centres (REFPNT CNT-CNT); the allowance is
; in the TOOL CALL; M107 allows the positive oversize. Tool data: examples/tools/3d_tools.tools
; (tool 3). The design surface is the plane Z = 0 tilted about Y by 30 degrees, N in Z-X.
0  BEGIN PGM 3D_ALLOWANCE MM
1  M107
2  TOOL CALL 3 Z S8000 DL+0.2 DR+0.2 DR2+0.2
3  FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS REFPNT CNT-CNT
4  L X+0 Y+0 Z+50 R0 FMAX
5  LN X+1.5 Y+0 Z+2.5980762 NX+0.5 NY+0 NZ+0.8660254 F800
6  LN X+1.5 Y+20 Z+2.5980762 NX+0.5 NY+0 NZ+0.8660254
7  LN X+1.5 Y+20 Z+2.5980762 NX+0.5 NY+0 NZ+0.8660254 TX+0 TY+0 TZ+1
8  LN X+1.5 Y+40 Z+2.5980762 NX+0.5 NY+0 NZ+0.8660254 TX+0 TY+0 TZ+1
9  FUNCTION RESET TCPM
10 L Z+50 FMAX
11 M30
12 END PGM 3D_ALLOWANCE MM
