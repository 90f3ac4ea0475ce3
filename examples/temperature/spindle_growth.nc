; SINUMERIK 840D FB1 W1 section 2.8 ([SIN-TEMP]), temperature compensation in tool direction: the
; program writes the spindle's growth, as the machine's thermal model estimates it after each
; pass, into SD 42960 TOOL_TEMP_COMP[2] (+Z: the tool is lifted by what the spindle grew). Each
; write acts from its block on (the axes stop at the write, as at a PLC block entry): N40 runs
; 0.015 mm higher, N60 and N70 0.025 mm, and N80 takes the compensation off before N90.
; The machine data come from the PLC script (MD 20390 TOOL_TEMP_COMP_ON, bit 2 of MD 32750
; TEMP_COMP_TYPE of Z); without them the writes reach the board and displace nothing.
; ./build/bin/apcictl run examples/temperature/spindle_growth.nc --plc examples/temperature/plc/machine_data.plc
%spindle_growth
N10 G0 X0 Y0 Z10
N20 G1 X50 F3000
N30 $SC_TOOL_TEMP_COMP[2] = 0.015
N40 G1 X100
N50 $SC_TOOL_TEMP_COMP[2] = $SC_TOOL_TEMP_COMP[2] + 0.010
N60 G1 Y20
N70 G1 X0
N80 $SC_TOOL_TEMP_COMP[2] = 0
N90 G0 Z50
N100 M30
