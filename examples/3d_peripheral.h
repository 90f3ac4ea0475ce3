; [TNC-3D], "3D-Werkzeugkorrektur beim Umfangsfräsen", Beispiel: blocks 11 to 13 in a whole
; program. Tool data: examples/tools/3d_tools.tools (tool 2: the reground 12 mm end mill).
;   11 L with rotary axes, M128, RL: the side of the correction from RL
;   12 LN with T perpendicular to N, M128
;   13 LN with T and without N, M128
0  BEGIN PGM 3D_PERIPHERAL MM
1  TOOL CALL 2 Z S6000
2  L X+40 Y+102.4717 Z+20 R0 FMAX
3  L X+40 Z-7.1088 F500
11 L X+48.4074 Y+102.4717 Z-7.1088 C-267.9784 B-20.0115 RL M128
12 LN X+60.6593 Y+102.4690 Z-7.1012 NX0.0000 NY0.9397 NZ0.3420 TX-0.0807 TY-0.3409 TZ0.9366 R0 M128
13 LN X+60.6593 Y+102.4690 Z-7.1012 TX-0.0807 TY-0.3409 TZ0.9366 M128
14 L Z+20 R0 FMAX M129
15 M30
16 END PGM 3D_PERIPHERAL MM
