%qpocket_qpex
; LinuxCNC's ngcgui subroutine qpocket.ngc ("Quadrilateral pocketing using cutter radius
; compensation"), called as its example caller qpex.ngc calls it, in our DIN 66025 dialect.
; docs/linuxcnc-examples.md; the test linuxcnc_examples_tests runs this file and the original
; (the program ngcgui makes: the preamble in_std.ngc, o<qpex> call with qpex's defaults, m2)
; and compares the paths.
;
; The original as LinuxCNC's ngcgui sample configuration runs it (sim/axis/ngcgui: an inch
; machine, preamble in_std.ngc, tool table sim.tbl): qpex.ngc with its defaults (T1,
; dir 2 = conventional, feed 10 in/min, depth 1 in in steps of 0.4 in, zsafe 0.2 in,
; zstart 0, stepover 0.9) calls qpocket.ngc seven times: a square, a rectangle turned 30
; degrees, a parallelogram, a kite, a triangle turned 45 degrees, a second kite in the first
; one's place, a dart. T1 is sim.tbl's, 0.1 in in diameter: radius 1.27 mm (qpocket.tools).
; Each pocket is one stretch under G42: a quarter arc entry, then in each depth pass (Z-10.16,
; Z-20.32, Z-25.4) the outline at the smallest scale the tool fits (ramping down), the outlines
; growing by the stepover up to the full one (each begins at the next corner), back to the
; entry point for the next pass; at the end along the next side, the lift, and G40.
;
; Block delete: qpocket's G42 stands on a block-delete line ("/ g42"). LinuxCNC runs it with
; block delete off, its default (and rs274's): the compensation is on, as here, where G42 is an
; ordinary block. With block delete on, LinuxCNC would mill the pockets uncompensated.
;
; What was changed, and why:
; - Inches converted to mm: every length is LinuxCNC's value times 25.4 (our dialect has no
;   G20; qpex.ngc's own numbers exactly: its 0.5 in is 12.7); the feed 10 in/min is F254.
; - The subroutines are unrolled (our dialect has none): qpex.ngc, qpocket.ngc and ngcgui's
;   utility subroutines (dir, pointsdata, loadtool, move, line, dot). Their arithmetic (the
;   centroid, the scale of each outline, the rotations, the entry points, the angles at the
;   corners; in degrees and double precision, as rs274 computes) was done when this file was
;   written, the results written to 6 decimals of a mm. Each call is marked with its line in
;   qpex.ngc. qpocket reads the tool's diameter from the tool table (#5410) and adds 0.01 in
;   for its scaling and its entry points; that is in the numbers.
; - T1 M6 G43 (o<loadtool>) is D1 (tool lengths 0).
; - Dropped, as our dialect has no such words: G20 G49 G94 G54 and G64 P (in_std.ngc; qpocket's
;   g64), S1000 M3, the (debug, ...) messages, and M110 (a user M code of the configuration:
;   it clears AXIS' notifications). m2 is M30.
; - Kept as written: every move in the original's order, G0 and G1, the Z words where the
;   original writes them, G42 alone before the entry arc, the G0 Z lift under G42, G40 alone,
;   and the zero-length G1 to the corner where the last outline ended ("final a").
; - G26 added: LinuxCNC's outside corners are arcs; our programs start in G25 (the ISG default).
;
; The whole tool path agrees with LinuxCNC's (docs/linuxcnc-examples.md). The outlines of a
; pocket, its depth passes and the two kites in one place pass over what was cut before, by
; design: each pocket's outlines inside its last are cleared by it, the moves between them are
; leads, and the run warns nothing (docs/compensation.md, "What is a wall").
G17 G40 G90 G26 ; in_std.ngc: g17 g20 g40 g49 g90 g94 g54 g64

(qpex.ngc line 42: o<qpocket> call, the square at X50.8 Y0, turned 0 degrees)
G40 ; g40: qpocket makes sure compensation is off at start
D1 ; T1 M6 G43 (o<loadtool>)
F254 ; f10: feed in inches per minute
G0 Z5.08 ; g0 z#<zsafe>
G0 X49.403 Y-1.397 ; preentry 1
G0 X49.403 Y-2.794 ; preentry 2
G42 ; "/ g42": cutter radius comp right of path (block delete off)
G2 X48.006 Y-1.397 I0 J1.397 ; arc entry
G1 Z0 ; plunge to start height from zsafe
G1 X48.006 Y2.794 Z-10.16 ; ramp down to zcurrent, smallest outline
G1 X53.594 Y2.794
G1 X53.594 Y-2.794
G1 X48.006 Y-2.794
G1 X48.006 Y2.794
G1 X56.1086 Y5.3086 Z-10.16 ; outline at scale 0.418
G1 X56.1086 Y-5.3086
G1 X45.4914 Y-5.3086
G1 X45.4914 Y5.3086
G1 X56.1086 Y5.3086
G1 X58.6232 Y-7.8232 Z-10.16 ; outline at scale 0.616
G1 X42.9768 Y-7.8232
G1 X42.9768 Y7.8232
G1 X58.6232 Y7.8232
G1 X58.6232 Y-7.8232
G1 X40.4622 Y-10.3378 Z-10.16 ; outline at scale 0.814
G1 X40.4622 Y10.3378
G1 X61.1378 Y10.3378
G1 X61.1378 Y-10.3378
G1 X40.4622 Y-10.3378
G1 X38.1 Y12.7 Z-10.16 ; outline at scale 1
G1 X63.5 Y12.7
G1 X63.5 Y-12.7
G1 X38.1 Y-12.7
G1 X38.1 Y12.7
G1 X48.006 Y-1.397 Z-10.16 ; depth pass 2: return to the interior entry point
G1 X48.006 Y2.794 Z-20.32 ; ramp down to zcurrent, smallest outline
G1 X53.594 Y2.794
G1 X53.594 Y-2.794
G1 X48.006 Y-2.794
G1 X48.006 Y2.794
G1 X56.1086 Y5.3086 Z-20.32 ; outline at scale 0.418
G1 X56.1086 Y-5.3086
G1 X45.4914 Y-5.3086
G1 X45.4914 Y5.3086
G1 X56.1086 Y5.3086
G1 X58.6232 Y-7.8232 Z-20.32 ; outline at scale 0.616
G1 X42.9768 Y-7.8232
G1 X42.9768 Y7.8232
G1 X58.6232 Y7.8232
G1 X58.6232 Y-7.8232
G1 X40.4622 Y-10.3378 Z-20.32 ; outline at scale 0.814
G1 X40.4622 Y10.3378
G1 X61.1378 Y10.3378
G1 X61.1378 Y-10.3378
G1 X40.4622 Y-10.3378
G1 X38.1 Y12.7 Z-20.32 ; outline at scale 1
G1 X63.5 Y12.7
G1 X63.5 Y-12.7
G1 X38.1 Y-12.7
G1 X38.1 Y12.7
G1 X48.006 Y-1.397 Z-20.32 ; depth pass 3: return to the interior entry point
G1 X48.006 Y2.794 Z-25.4 ; ramp down to zcurrent, smallest outline
G1 X53.594 Y2.794
G1 X53.594 Y-2.794
G1 X48.006 Y-2.794
G1 X48.006 Y2.794
G1 X56.1086 Y5.3086 Z-25.4 ; outline at scale 0.418
G1 X56.1086 Y-5.3086
G1 X45.4914 Y-5.3086
G1 X45.4914 Y5.3086
G1 X56.1086 Y5.3086
G1 X58.6232 Y-7.8232 Z-25.4 ; outline at scale 0.616
G1 X42.9768 Y-7.8232
G1 X42.9768 Y7.8232
G1 X58.6232 Y7.8232
G1 X58.6232 Y-7.8232
G1 X40.4622 Y-10.3378 Z-25.4 ; outline at scale 0.814
G1 X40.4622 Y10.3378
G1 X61.1378 Y10.3378
G1 X61.1378 Y-10.3378
G1 X40.4622 Y-10.3378
G1 X38.1 Y12.7 Z-25.4 ; outline at scale 1
G1 X63.5 Y12.7
G1 X63.5 Y-12.7
G1 X38.1 Y-12.7
G1 X38.1 Y12.7
G1 X38.1 Y12.7 ; final a: the corner where the last outline ends
G1 X39.497 Y12.7 ; final b: along the next side, to turn compensation off
G0 Z5.08
G40 ; cutter radius compensation off

(qpex.ngc line 58: o<qpocket> call, the rectangle at X50.8 Y50.8, turned 30 degrees)
G40 ; g40: qpocket makes sure compensation is off at start
D1 ; T1 M6 G43 (o<loadtool>)
F254 ; f10: feed in inches per minute
(g0 z#<zsafe> left out: Z is there, and LinuxCNC stays where the compensation ended)
G0 X51.685663 Y46.471988 ; preentry 1
G0 X52.384163 Y45.26215 ; preentry 2
G42 ; "/ g42": cutter radius comp right of path (block delete off)
G2 X50.475825 Y45.773488 I-0.6985 J1.209837 ; arc entry
G1 Z0 ; plunge to start height from zsafe
G1 X45.586325 Y54.24235 Z-10.16 ; ramp down to zcurrent, smallest outline
G1 X50.425675 Y57.03635
G1 X56.013675 Y47.35765
G1 X51.174325 Y44.56365
G1 X45.586325 Y54.24235
G1 X50.088782 Y62.649065 Z-10.16 ; outline at scale 0.418
G1 X60.705982 Y44.259535
G1 X51.511218 Y38.950935
G1 X40.894018 Y57.340465
G1 X50.088782 Y62.649065
G1 X65.39829 Y41.16142 Z-10.16 ; outline at scale 0.616
G1 X51.84811 Y33.33822
G1 X36.20171 Y60.43858
G1 X49.75189 Y68.26178
G1 X65.39829 Y41.16142
G1 X52.185003 Y27.725505 Z-10.16 ; outline at scale 0.814
G1 X31.509403 Y63.536695
G1 X49.414997 Y73.874495
G1 X70.090597 Y38.063305
G1 X52.185003 Y27.725505
G1 X27.101477 Y66.447045 Z-10.16 ; outline at scale 1
G1 X49.098523 Y79.147045
G1 X74.498523 Y35.152955
G1 X52.501477 Y22.452955
G1 X27.101477 Y66.447045
G1 X50.475825 Y45.773488 Z-10.16 ; depth pass 2: return to the interior entry point
G1 X45.586325 Y54.24235 Z-20.32 ; ramp down to zcurrent, smallest outline
G1 X50.425675 Y57.03635
G1 X56.013675 Y47.35765
G1 X51.174325 Y44.56365
G1 X45.586325 Y54.24235
G1 X50.088782 Y62.649065 Z-20.32 ; outline at scale 0.418
G1 X60.705982 Y44.259535
G1 X51.511218 Y38.950935
G1 X40.894018 Y57.340465
G1 X50.088782 Y62.649065
G1 X65.39829 Y41.16142 Z-20.32 ; outline at scale 0.616
G1 X51.84811 Y33.33822
G1 X36.20171 Y60.43858
G1 X49.75189 Y68.26178
G1 X65.39829 Y41.16142
G1 X52.185003 Y27.725505 Z-20.32 ; outline at scale 0.814
G1 X31.509403 Y63.536695
G1 X49.414997 Y73.874495
G1 X70.090597 Y38.063305
G1 X52.185003 Y27.725505
G1 X27.101477 Y66.447045 Z-20.32 ; outline at scale 1
G1 X49.098523 Y79.147045
G1 X74.498523 Y35.152955
G1 X52.501477 Y22.452955
G1 X27.101477 Y66.447045
G1 X50.475825 Y45.773488 Z-20.32 ; depth pass 3: return to the interior entry point
G1 X45.586325 Y54.24235 Z-25.4 ; ramp down to zcurrent, smallest outline
G1 X50.425675 Y57.03635
G1 X56.013675 Y47.35765
G1 X51.174325 Y44.56365
G1 X45.586325 Y54.24235
G1 X50.088782 Y62.649065 Z-25.4 ; outline at scale 0.418
G1 X60.705982 Y44.259535
G1 X51.511218 Y38.950935
G1 X40.894018 Y57.340465
G1 X50.088782 Y62.649065
G1 X65.39829 Y41.16142 Z-25.4 ; outline at scale 0.616
G1 X51.84811 Y33.33822
G1 X36.20171 Y60.43858
G1 X49.75189 Y68.26178
G1 X65.39829 Y41.16142
G1 X52.185003 Y27.725505 Z-25.4 ; outline at scale 0.814
G1 X31.509403 Y63.536695
G1 X49.414997 Y73.874495
G1 X70.090597 Y38.063305
G1 X52.185003 Y27.725505
G1 X27.101477 Y66.447045 Z-25.4 ; outline at scale 1
G1 X49.098523 Y79.147045
G1 X74.498523 Y35.152955
G1 X52.501477 Y22.452955
G1 X27.101477 Y66.447045
G1 X27.101477 Y66.447045 ; final a: the corner where the last outline ends
G1 X28.311315 Y67.145545 ; final b: along the next side, to turn compensation off
G0 Z5.08
G40 ; cutter radius compensation off

(qpex.ngc line 74: o<qpocket> call, the parallelogram at X0 Y50.8, turned 0 degrees)
G40 ; g40: qpocket makes sure compensation is off at start
D1 ; T1 M6 G43 (o<loadtool>)
F254 ; f10: feed in inches per minute
(g0 z#<zsafe> left out: Z is there, and LinuxCNC stays where the compensation ended)
G0 X-3.327607 Y49.403 ; preentry 1
G0 X-3.952364 Y48.153485 ; preentry 2
G42 ; "/ g42": cutter radius comp right of path (block delete off)
G2 X-4.577121 Y50.027757 I0.624757 J1.249515 ; arc entry
G1 Z0 ; plunge to start height from zsafe
G1 X-2.794 Y53.594 Z-10.16 ; ramp down to zcurrent, smallest outline
G1 X5.588 Y53.594
G1 X2.794 Y48.006
G1 X-5.588 Y48.006
G1 X-2.794 Y53.594
G1 X10.6172 Y56.1086 Z-10.16 ; outline at scale 0.418
G1 X5.3086 Y45.4914
G1 X-10.6172 Y45.4914
G1 X-5.3086 Y56.1086
G1 X10.6172 Y56.1086
G1 X7.8232 Y42.9768 Z-10.16 ; outline at scale 0.616
G1 X-15.6464 Y42.9768
G1 X-7.8232 Y58.6232
G1 X15.6464 Y58.6232
G1 X7.8232 Y42.9768
G1 X-20.6756 Y40.4622 Z-10.16 ; outline at scale 0.814
G1 X-10.3378 Y61.1378
G1 X20.6756 Y61.1378
G1 X10.3378 Y40.4622
G1 X-20.6756 Y40.4622
G1 X-12.7 Y63.5 Z-10.16 ; outline at scale 1
G1 X25.4 Y63.5
G1 X12.7 Y38.1
G1 X-25.4 Y38.1
G1 X-12.7 Y63.5
G1 X-4.577121 Y50.027757 Z-10.16 ; depth pass 2: return to the interior entry point
G1 X-2.794 Y53.594 Z-20.32 ; ramp down to zcurrent, smallest outline
G1 X5.588 Y53.594
G1 X2.794 Y48.006
G1 X-5.588 Y48.006
G1 X-2.794 Y53.594
G1 X10.6172 Y56.1086 Z-20.32 ; outline at scale 0.418
G1 X5.3086 Y45.4914
G1 X-10.6172 Y45.4914
G1 X-5.3086 Y56.1086
G1 X10.6172 Y56.1086
G1 X7.8232 Y42.9768 Z-20.32 ; outline at scale 0.616
G1 X-15.6464 Y42.9768
G1 X-7.8232 Y58.6232
G1 X15.6464 Y58.6232
G1 X7.8232 Y42.9768
G1 X-20.6756 Y40.4622 Z-20.32 ; outline at scale 0.814
G1 X-10.3378 Y61.1378
G1 X20.6756 Y61.1378
G1 X10.3378 Y40.4622
G1 X-20.6756 Y40.4622
G1 X-12.7 Y63.5 Z-20.32 ; outline at scale 1
G1 X25.4 Y63.5
G1 X12.7 Y38.1
G1 X-25.4 Y38.1
G1 X-12.7 Y63.5
G1 X-4.577121 Y50.027757 Z-20.32 ; depth pass 3: return to the interior entry point
G1 X-2.794 Y53.594 Z-25.4 ; ramp down to zcurrent, smallest outline
G1 X5.588 Y53.594
G1 X2.794 Y48.006
G1 X-5.588 Y48.006
G1 X-2.794 Y53.594
G1 X10.6172 Y56.1086 Z-25.4 ; outline at scale 0.418
G1 X5.3086 Y45.4914
G1 X-10.6172 Y45.4914
G1 X-5.3086 Y56.1086
G1 X10.6172 Y56.1086
G1 X7.8232 Y42.9768 Z-25.4 ; outline at scale 0.616
G1 X-15.6464 Y42.9768
G1 X-7.8232 Y58.6232
G1 X15.6464 Y58.6232
G1 X7.8232 Y42.9768
G1 X-20.6756 Y40.4622 Z-25.4 ; outline at scale 0.814
G1 X-10.3378 Y61.1378
G1 X20.6756 Y61.1378
G1 X10.3378 Y40.4622
G1 X-20.6756 Y40.4622
G1 X-12.7 Y63.5 Z-25.4 ; outline at scale 1
G1 X25.4 Y63.5
G1 X12.7 Y38.1
G1 X-25.4 Y38.1
G1 X-12.7 Y63.5
G1 X-12.7 Y63.5 ; final a: the corner where the last outline ends
G1 X-11.836607 Y63.5 ; final b: along the next side, to turn compensation off
G0 Z5.08
G40 ; cutter radius compensation off

(qpex.ngc line 89: o<qpocket> call, the kite at X-50.8 Y50.8, turned 0 degrees)
G40 ; g40: qpocket makes sure compensation is off at start
D1 ; T1 M6 G43 (o<loadtool>)
F254 ; f10: feed in inches per minute
(g0 z#<zsafe> left out: Z is there, and LinuxCNC stays where the compensation ended)
G0 X-49.766201 Y36.233545 ; preentry 1
G0 X-48.410912 Y35.894723 ; preentry 2
G42 ; "/ g42": cutter radius comp right of path (block delete off)
G2 X-50.105024 Y34.878256 I-1.355289 J0.338822 ; arc entry
G1 Z0 ; plunge to start height from zsafe
G1 X-50.8 Y35.052 Z-10.16 ; ramp down to zcurrent, smallest outline
G1 X-56.388 Y33.655
G1 X-50.8 Y39.243
G1 X-45.212 Y33.655
G1 X-50.8 Y35.052
G1 X-61.4172 Y31.5595 Z-10.16 ; outline at scale 0.418
G1 X-50.8 Y42.1767
G1 X-40.1828 Y31.5595
G1 X-50.8 Y34.2138
G1 X-61.4172 Y31.5595
G1 X-50.8 Y45.1104 Z-10.16 ; outline at scale 0.616
G1 X-35.1536 Y29.464
G1 X-50.8 Y33.3756
G1 X-66.4464 Y29.464
G1 X-50.8 Y45.1104
G1 X-30.1244 Y27.3685 Z-10.16 ; outline at scale 0.814
G1 X-50.8 Y32.5374
G1 X-71.4756 Y27.3685
G1 X-50.8 Y48.0441
G1 X-30.1244 Y27.3685
G1 X-50.8 Y31.75 Z-10.16 ; outline at scale 1
G1 X-76.2 Y25.4
G1 X-50.8 Y50.8
G1 X-25.4 Y25.4
G1 X-50.8 Y31.75
G1 X-50.105024 Y34.878256 Z-10.16 ; depth pass 2: return to the interior entry point
G1 X-50.8 Y35.052 Z-20.32 ; ramp down to zcurrent, smallest outline
G1 X-56.388 Y33.655
G1 X-50.8 Y39.243
G1 X-45.212 Y33.655
G1 X-50.8 Y35.052
G1 X-61.4172 Y31.5595 Z-20.32 ; outline at scale 0.418
G1 X-50.8 Y42.1767
G1 X-40.1828 Y31.5595
G1 X-50.8 Y34.2138
G1 X-61.4172 Y31.5595
G1 X-50.8 Y45.1104 Z-20.32 ; outline at scale 0.616
G1 X-35.1536 Y29.464
G1 X-50.8 Y33.3756
G1 X-66.4464 Y29.464
G1 X-50.8 Y45.1104
G1 X-30.1244 Y27.3685 Z-20.32 ; outline at scale 0.814
G1 X-50.8 Y32.5374
G1 X-71.4756 Y27.3685
G1 X-50.8 Y48.0441
G1 X-30.1244 Y27.3685
G1 X-50.8 Y31.75 Z-20.32 ; outline at scale 1
G1 X-76.2 Y25.4
G1 X-50.8 Y50.8
G1 X-25.4 Y25.4
G1 X-50.8 Y31.75
G1 X-50.105024 Y34.878256 Z-20.32 ; depth pass 3: return to the interior entry point
G1 X-50.8 Y35.052 Z-25.4 ; ramp down to zcurrent, smallest outline
G1 X-56.388 Y33.655
G1 X-50.8 Y39.243
G1 X-45.212 Y33.655
G1 X-50.8 Y35.052
G1 X-61.4172 Y31.5595 Z-25.4 ; outline at scale 0.418
G1 X-50.8 Y42.1767
G1 X-40.1828 Y31.5595
G1 X-50.8 Y34.2138
G1 X-61.4172 Y31.5595
G1 X-50.8 Y45.1104 Z-25.4 ; outline at scale 0.616
G1 X-35.1536 Y29.464
G1 X-50.8 Y33.3756
G1 X-66.4464 Y29.464
G1 X-50.8 Y45.1104
G1 X-30.1244 Y27.3685 Z-25.4 ; outline at scale 0.814
G1 X-50.8 Y32.5374
G1 X-71.4756 Y27.3685
G1 X-50.8 Y48.0441
G1 X-30.1244 Y27.3685
G1 X-50.8 Y31.75 Z-25.4 ; outline at scale 1
G1 X-76.2 Y25.4
G1 X-50.8 Y50.8
G1 X-25.4 Y25.4
G1 X-50.8 Y31.75
G1 X-50.8 Y31.75 ; final a: the corner where the last outline ends
G1 X-51.138822 Y31.665294 ; final b: along the next side, to turn compensation off
G0 Z5.08
G40 ; cutter radius compensation off

(qpex.ngc line 105: o<qpocket> call, the triangle at X-50.8 Y0, turned 45 degrees)
G40 ; g40: qpocket makes sure compensation is off at start
D1 ; T1 M6 G43 (o<loadtool>)
F254 ; f10: feed in inches per minute
(g0 z#<zsafe> left out: Z is there, and LinuxCNC stays where the compensation ended)
G0 X-44.114297 Y-5.932669 ; preentry 1
G0 X-43.125482 Y-4.945829 ; preentry 2
G42 ; "/ g42": cutter radius comp right of path (block delete off)
G2 X-43.127458 Y-6.921484 I-0.988816 J-0.98684 ; arc entry
G1 Z0 ; plunge to start height from zsafe
G1 X-43.503362 Y-7.296638 Z-10.16 ; ramp down to zcurrent, smallest outline
G1 X-45.477043 Y-9.27427
G1 X-47.452699 Y-3.347301
G1 X-41.52573 Y-5.322957
G1 X-43.503362 Y-7.296638
G1 X-46.069147 Y-12.238347 Z-10.16 ; outline at scale 0.209
G1 X-49.822894 Y-0.977106
G1 X-38.561653 Y-4.730853
G1 X-42.319154 Y-8.480846
G1 X-46.069147 Y-12.238347
G1 X-52.193089 Y1.393089 Z-10.16 ; outline at scale 0.308
G1 X-35.597576 Y-4.138749
G1 X-41.134945 Y-9.665055
G1 X-46.661251 Y-15.202424
G1 X-52.193089 Y1.393089
G1 X-32.633499 Y-3.546644 Z-10.16 ; outline at scale 0.407
G1 X-39.950737 Y-10.849263
G1 X-47.253356 Y-18.166501
G1 X-54.563284 Y3.763284
G1 X-32.633499 Y-3.546644
G1 X-38.766529 Y-12.033471 Z-10.16 ; outline at scale 0.506
G1 X-47.84546 Y-21.130579
G1 X-56.933479 Y6.133479
G1 X-29.669421 Y-2.95454
G1 X-38.766529 Y-12.033471
G1 X-48.437564 Y-24.094656 Z-10.16 ; outline at scale 0.605
G1 X-59.303674 Y8.503674
G1 X-26.705344 Y-2.362436
G1 X-37.58232 Y-13.21768
G1 X-48.437564 Y-24.094656
G1 X-61.673869 Y10.873869 Z-10.16 ; outline at scale 0.704
G1 X-23.741267 Y-1.770332
G1 X-36.398112 Y-14.401888
G1 X-49.029668 Y-27.058733
G1 X-61.673869 Y10.873869
G1 X-20.77719 Y-1.178228 Z-10.16 ; outline at scale 0.803
G1 X-35.213903 Y-15.586097
G1 X-49.621772 Y-30.02281
G1 X-64.044064 Y13.244064
G1 X-20.77719 Y-1.178228
G1 X-34.029695 Y-16.770305 Z-10.16 ; outline at scale 0.902
G1 X-50.213877 Y-32.986887
G1 X-66.414259 Y15.614259
G1 X-17.813113 Y-0.586123
G1 X-34.029695 Y-16.770305
G1 X-50.8 Y-35.921024 Z-10.16 ; outline at scale 1
G1 X-68.760512 Y17.960512
G1 X-14.878976 Y0
G1 X-32.857448 Y-17.942552
G1 X-50.8 Y-35.921024
G1 X-43.127458 Y-6.921484 Z-10.16 ; depth pass 2: return to the interior entry point
G1 X-43.503362 Y-7.296638 Z-20.32 ; ramp down to zcurrent, smallest outline
G1 X-45.477043 Y-9.27427
G1 X-47.452699 Y-3.347301
G1 X-41.52573 Y-5.322957
G1 X-43.503362 Y-7.296638
G1 X-46.069147 Y-12.238347 Z-20.32 ; outline at scale 0.209
G1 X-49.822894 Y-0.977106
G1 X-38.561653 Y-4.730853
G1 X-42.319154 Y-8.480846
G1 X-46.069147 Y-12.238347
G1 X-52.193089 Y1.393089 Z-20.32 ; outline at scale 0.308
G1 X-35.597576 Y-4.138749
G1 X-41.134945 Y-9.665055
G1 X-46.661251 Y-15.202424
G1 X-52.193089 Y1.393089
G1 X-32.633499 Y-3.546644 Z-20.32 ; outline at scale 0.407
G1 X-39.950737 Y-10.849263
G1 X-47.253356 Y-18.166501
G1 X-54.563284 Y3.763284
G1 X-32.633499 Y-3.546644
G1 X-38.766529 Y-12.033471 Z-20.32 ; outline at scale 0.506
G1 X-47.84546 Y-21.130579
G1 X-56.933479 Y6.133479
G1 X-29.669421 Y-2.95454
G1 X-38.766529 Y-12.033471
G1 X-48.437564 Y-24.094656 Z-20.32 ; outline at scale 0.605
G1 X-59.303674 Y8.503674
G1 X-26.705344 Y-2.362436
G1 X-37.58232 Y-13.21768
G1 X-48.437564 Y-24.094656
G1 X-61.673869 Y10.873869 Z-20.32 ; outline at scale 0.704
G1 X-23.741267 Y-1.770332
G1 X-36.398112 Y-14.401888
G1 X-49.029668 Y-27.058733
G1 X-61.673869 Y10.873869
G1 X-20.77719 Y-1.178228 Z-20.32 ; outline at scale 0.803
G1 X-35.213903 Y-15.586097
G1 X-49.621772 Y-30.02281
G1 X-64.044064 Y13.244064
G1 X-20.77719 Y-1.178228
G1 X-34.029695 Y-16.770305 Z-20.32 ; outline at scale 0.902
G1 X-50.213877 Y-32.986887
G1 X-66.414259 Y15.614259
G1 X-17.813113 Y-0.586123
G1 X-34.029695 Y-16.770305
G1 X-50.8 Y-35.921024 Z-20.32 ; outline at scale 1
G1 X-68.760512 Y17.960512
G1 X-14.878976 Y0
G1 X-32.857448 Y-17.942552
G1 X-50.8 Y-35.921024
G1 X-43.127458 Y-6.921484 Z-20.32 ; depth pass 3: return to the interior entry point
G1 X-43.503362 Y-7.296638 Z-25.4 ; ramp down to zcurrent, smallest outline
G1 X-45.477043 Y-9.27427
G1 X-47.452699 Y-3.347301
G1 X-41.52573 Y-5.322957
G1 X-43.503362 Y-7.296638
G1 X-46.069147 Y-12.238347 Z-25.4 ; outline at scale 0.209
G1 X-49.822894 Y-0.977106
G1 X-38.561653 Y-4.730853
G1 X-42.319154 Y-8.480846
G1 X-46.069147 Y-12.238347
G1 X-52.193089 Y1.393089 Z-25.4 ; outline at scale 0.308
G1 X-35.597576 Y-4.138749
G1 X-41.134945 Y-9.665055
G1 X-46.661251 Y-15.202424
G1 X-52.193089 Y1.393089
G1 X-32.633499 Y-3.546644 Z-25.4 ; outline at scale 0.407
G1 X-39.950737 Y-10.849263
G1 X-47.253356 Y-18.166501
G1 X-54.563284 Y3.763284
G1 X-32.633499 Y-3.546644
G1 X-38.766529 Y-12.033471 Z-25.4 ; outline at scale 0.506
G1 X-47.84546 Y-21.130579
G1 X-56.933479 Y6.133479
G1 X-29.669421 Y-2.95454
G1 X-38.766529 Y-12.033471
G1 X-48.437564 Y-24.094656 Z-25.4 ; outline at scale 0.605
G1 X-59.303674 Y8.503674
G1 X-26.705344 Y-2.362436
G1 X-37.58232 Y-13.21768
G1 X-48.437564 Y-24.094656
G1 X-61.673869 Y10.873869 Z-25.4 ; outline at scale 0.704
G1 X-23.741267 Y-1.770332
G1 X-36.398112 Y-14.401888
G1 X-49.029668 Y-27.058733
G1 X-61.673869 Y10.873869
G1 X-20.77719 Y-1.178228 Z-25.4 ; outline at scale 0.803
G1 X-35.213903 Y-15.586097
G1 X-49.621772 Y-30.02281
G1 X-64.044064 Y13.244064
G1 X-20.77719 Y-1.178228
G1 X-34.029695 Y-16.770305 Z-25.4 ; outline at scale 0.902
G1 X-50.213877 Y-32.986887
G1 X-66.414259 Y15.614259
G1 X-17.813113 Y-0.586123
G1 X-34.029695 Y-16.770305
G1 X-50.8 Y-35.921024 Z-25.4 ; outline at scale 1
G1 X-68.760512 Y17.960512
G1 X-14.878976 Y0
G1 X-32.857448 Y-17.942552
G1 X-50.8 Y-35.921024
G1 X-50.8 Y-35.921024 ; final a: the corner where the last outline ends
G1 X-51.515599 Y-33.774227 ; final b: along the next side, to turn compensation off
G0 Z5.08
G40 ; cutter radius compensation off

(qpex.ngc line 121: o<qpocket> call, the kite at X-50.8 Y50.8, turned 0 degrees)
G40 ; g40: qpocket makes sure compensation is off at start
D1 ; T1 M6 G43 (o<loadtool>)
F254 ; f10: feed in inches per minute
(g0 z#<zsafe> left out: Z is there, and LinuxCNC stays where the compensation ended)
G0 X-49.433033 Y29.395155 ; preentry 1
G0 X-48.183518 Y30.019912 ; preentry 2
G42 ; "/ g42": cutter radius comp right of path (block delete off)
G2 X-48.808276 Y28.14564 I-1.249515 J-0.624757 ; arc entry
G1 Z0 ; plunge to start height from zsafe
G1 X-50.8 Y27.149778 Z-10.16 ; ramp down to zcurrent, smallest outline
G1 X-54.525333 Y29.012444
G1 X-50.8 Y32.737778
G1 X-47.074667 Y29.012444
G1 X-50.8 Y27.149778
G1 X-57.878133 Y28.453644 Z-10.16 ; outline at scale 0.278667
G1 X-50.8 Y35.531778
G1 X-43.721867 Y28.453644
G1 X-50.8 Y24.914578
G1 X-57.878133 Y28.453644
G1 X-50.8 Y38.325778 Z-10.16 ; outline at scale 0.410667
G1 X-40.369067 Y27.894844
G1 X-50.8 Y22.679378
G1 X-61.230933 Y27.894844
G1 X-50.8 Y38.325778
G1 X-37.016267 Y27.336044 Z-10.16 ; outline at scale 0.542667
G1 X-50.8 Y20.444178
G1 X-64.583733 Y27.336044
G1 X-50.8 Y41.119778
G1 X-37.016267 Y27.336044
G1 X-50.8 Y18.208978 Z-10.16 ; outline at scale 0.674667
G1 X-67.936533 Y26.777244
G1 X-50.8 Y43.913778
G1 X-33.663467 Y26.777244
G1 X-50.8 Y18.208978
G1 X-71.289333 Y26.218444 Z-10.16 ; outline at scale 0.806667
G1 X-50.8 Y46.707778
G1 X-30.310667 Y26.218444
G1 X-50.8 Y15.973778
G1 X-71.289333 Y26.218444
G1 X-50.8 Y49.501778 Z-10.16 ; outline at scale 0.938667
G1 X-26.957867 Y25.659644
G1 X-50.8 Y13.738578
G1 X-74.642133 Y25.659644
G1 X-50.8 Y49.501778
G1 X-25.4 Y25.4 Z-10.16 ; outline at scale 1
G1 X-50.8 Y12.7
G1 X-76.2 Y25.4
G1 X-50.8 Y50.8
G1 X-25.4 Y25.4
G1 X-48.808276 Y28.14564 Z-10.16 ; depth pass 2: return to the interior entry point
G1 X-50.8 Y27.149778 Z-20.32 ; ramp down to zcurrent, smallest outline
G1 X-54.525333 Y29.012444
G1 X-50.8 Y32.737778
G1 X-47.074667 Y29.012444
G1 X-50.8 Y27.149778
G1 X-57.878133 Y28.453644 Z-20.32 ; outline at scale 0.278667
G1 X-50.8 Y35.531778
G1 X-43.721867 Y28.453644
G1 X-50.8 Y24.914578
G1 X-57.878133 Y28.453644
G1 X-50.8 Y38.325778 Z-20.32 ; outline at scale 0.410667
G1 X-40.369067 Y27.894844
G1 X-50.8 Y22.679378
G1 X-61.230933 Y27.894844
G1 X-50.8 Y38.325778
G1 X-37.016267 Y27.336044 Z-20.32 ; outline at scale 0.542667
G1 X-50.8 Y20.444178
G1 X-64.583733 Y27.336044
G1 X-50.8 Y41.119778
G1 X-37.016267 Y27.336044
G1 X-50.8 Y18.208978 Z-20.32 ; outline at scale 0.674667
G1 X-67.936533 Y26.777244
G1 X-50.8 Y43.913778
G1 X-33.663467 Y26.777244
G1 X-50.8 Y18.208978
G1 X-71.289333 Y26.218444 Z-20.32 ; outline at scale 0.806667
G1 X-50.8 Y46.707778
G1 X-30.310667 Y26.218444
G1 X-50.8 Y15.973778
G1 X-71.289333 Y26.218444
G1 X-50.8 Y49.501778 Z-20.32 ; outline at scale 0.938667
G1 X-26.957867 Y25.659644
G1 X-50.8 Y13.738578
G1 X-74.642133 Y25.659644
G1 X-50.8 Y49.501778
G1 X-25.4 Y25.4 Z-20.32 ; outline at scale 1
G1 X-50.8 Y12.7
G1 X-76.2 Y25.4
G1 X-50.8 Y50.8
G1 X-25.4 Y25.4
G1 X-48.808276 Y28.14564 Z-20.32 ; depth pass 3: return to the interior entry point
G1 X-50.8 Y27.149778 Z-25.4 ; ramp down to zcurrent, smallest outline
G1 X-54.525333 Y29.012444
G1 X-50.8 Y32.737778
G1 X-47.074667 Y29.012444
G1 X-50.8 Y27.149778
G1 X-57.878133 Y28.453644 Z-25.4 ; outline at scale 0.278667
G1 X-50.8 Y35.531778
G1 X-43.721867 Y28.453644
G1 X-50.8 Y24.914578
G1 X-57.878133 Y28.453644
G1 X-50.8 Y38.325778 Z-25.4 ; outline at scale 0.410667
G1 X-40.369067 Y27.894844
G1 X-50.8 Y22.679378
G1 X-61.230933 Y27.894844
G1 X-50.8 Y38.325778
G1 X-37.016267 Y27.336044 Z-25.4 ; outline at scale 0.542667
G1 X-50.8 Y20.444178
G1 X-64.583733 Y27.336044
G1 X-50.8 Y41.119778
G1 X-37.016267 Y27.336044
G1 X-50.8 Y18.208978 Z-25.4 ; outline at scale 0.674667
G1 X-67.936533 Y26.777244
G1 X-50.8 Y43.913778
G1 X-33.663467 Y26.777244
G1 X-50.8 Y18.208978
G1 X-71.289333 Y26.218444 Z-25.4 ; outline at scale 0.806667
G1 X-50.8 Y46.707778
G1 X-30.310667 Y26.218444
G1 X-50.8 Y15.973778
G1 X-71.289333 Y26.218444
G1 X-50.8 Y49.501778 Z-25.4 ; outline at scale 0.938667
G1 X-26.957867 Y25.659644
G1 X-50.8 Y13.738578
G1 X-74.642133 Y25.659644
G1 X-50.8 Y49.501778
G1 X-25.4 Y25.4 Z-25.4 ; outline at scale 1
G1 X-50.8 Y12.7
G1 X-76.2 Y25.4
G1 X-50.8 Y50.8
G1 X-25.4 Y25.4
G1 X-25.4 Y25.4 ; final a: the corner where the last outline ends
G1 X-27.133609 Y24.533195 ; final b: along the next side, to turn compensation off
G0 Z5.08
G40 ; cutter radius compensation off

(qpex.ngc line 137: o<qpocket> call, the dart at X0 Y-25.4, turned 0 degrees)
G40 ; g40: qpocket makes sure compensation is off at start
D1 ; T1 M6 G43 (o<loadtool>)
F254 ; f10: feed in inches per minute
(g0 z#<zsafe> left out: Z is there, and LinuxCNC stays where the compensation ended)
G0 X1.033799 Y-39.966455 ; preentry 1
G0 X2.389088 Y-40.305277 ; preentry 2
G42 ; "/ g42": cutter radius comp right of path (block delete off)
G2 X0.694976 Y-41.321744 I-1.355289 J0.338822 ; arc entry
G1 Z0 ; plunge to start height from zsafe
G1 X0 Y-41.148 Z-10.16 ; ramp down to zcurrent, smallest outline
G1 X-5.588 Y-42.545
G1 X0 Y-36.957
G1 X5.588 Y-42.545
G1 X0 Y-41.148
G1 X-10.6172 Y-44.6405 Z-10.16 ; outline at scale 0.418
G1 X0 Y-34.0233
G1 X10.6172 Y-44.6405
G1 X0 Y-41.9862
G1 X-10.6172 Y-44.6405
G1 X0 Y-31.0896 Z-10.16 ; outline at scale 0.616
G1 X15.6464 Y-46.736
G1 X0 Y-42.8244
G1 X-15.6464 Y-46.736
G1 X0 Y-31.0896
G1 X20.6756 Y-48.8315 Z-10.16 ; outline at scale 0.814
G1 X0 Y-43.6626
G1 X-20.6756 Y-48.8315
G1 X0 Y-28.1559
G1 X20.6756 Y-48.8315
G1 X0 Y-44.45 Z-10.16 ; outline at scale 1
G1 X-25.4 Y-50.8
G1 X0 Y-25.4
G1 X25.4 Y-50.8
G1 X0 Y-44.45
G1 X0.694976 Y-41.321744 Z-10.16 ; depth pass 2: return to the interior entry point
G1 X0 Y-41.148 Z-20.32 ; ramp down to zcurrent, smallest outline
G1 X-5.588 Y-42.545
G1 X0 Y-36.957
G1 X5.588 Y-42.545
G1 X0 Y-41.148
G1 X-10.6172 Y-44.6405 Z-20.32 ; outline at scale 0.418
G1 X0 Y-34.0233
G1 X10.6172 Y-44.6405
G1 X0 Y-41.9862
G1 X-10.6172 Y-44.6405
G1 X0 Y-31.0896 Z-20.32 ; outline at scale 0.616
G1 X15.6464 Y-46.736
G1 X0 Y-42.8244
G1 X-15.6464 Y-46.736
G1 X0 Y-31.0896
G1 X20.6756 Y-48.8315 Z-20.32 ; outline at scale 0.814
G1 X0 Y-43.6626
G1 X-20.6756 Y-48.8315
G1 X0 Y-28.1559
G1 X20.6756 Y-48.8315
G1 X0 Y-44.45 Z-20.32 ; outline at scale 1
G1 X-25.4 Y-50.8
G1 X0 Y-25.4
G1 X25.4 Y-50.8
G1 X0 Y-44.45
G1 X0.694976 Y-41.321744 Z-20.32 ; depth pass 3: return to the interior entry point
G1 X0 Y-41.148 Z-25.4 ; ramp down to zcurrent, smallest outline
G1 X-5.588 Y-42.545
G1 X0 Y-36.957
G1 X5.588 Y-42.545
G1 X0 Y-41.148
G1 X-10.6172 Y-44.6405 Z-25.4 ; outline at scale 0.418
G1 X0 Y-34.0233
G1 X10.6172 Y-44.6405
G1 X0 Y-41.9862
G1 X-10.6172 Y-44.6405
G1 X0 Y-31.0896 Z-25.4 ; outline at scale 0.616
G1 X15.6464 Y-46.736
G1 X0 Y-42.8244
G1 X-15.6464 Y-46.736
G1 X0 Y-31.0896
G1 X20.6756 Y-48.8315 Z-25.4 ; outline at scale 0.814
G1 X0 Y-43.6626
G1 X-20.6756 Y-48.8315
G1 X0 Y-28.1559
G1 X20.6756 Y-48.8315
G1 X0 Y-44.45 Z-25.4 ; outline at scale 1
G1 X-25.4 Y-50.8
G1 X0 Y-25.4
G1 X25.4 Y-50.8
G1 X0 Y-44.45
G1 X0 Y-44.45 ; final a: the corner where the last outline ends
G1 X-0.338822 Y-44.534706 ; final b: along the next side, to turn compensation off
G0 Z5.08
G40 ; cutter radius compensation off

M30 (m2)
