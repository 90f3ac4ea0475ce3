/* SPDX-License-Identifier: MIT */
/* The motion calls of apci.h compiled as strict C11. */
#include <string.h>

#include "apci/apci.h"

/* Spools a G01 and a G03, runs the clock, reads the segments back.
 * Returns 0 on success, else the number of the failed step. */
int c_motion_round_trip(void) {
    apci_board* board = NULL;
    if (apci_open("emu:", &board) != APCI_OK) return 1;
    /* Members not named are zero (C11 6.7.9). */
    apci_profile line = {.kind = APCI_PROFILE_LINE, .axes = 0x03, .tag = 1, .feed = 600.0};
    line.target[0] = 10.0;
    apci_profile arc = line;
    arc.kind = APCI_PROFILE_ARC_CCW;
    arc.tag = 2;
    arc.target[0] = 0.0;
    arc.target[1] = 10.0;
    arc.arc_axes[0] = 0;
    arc.arc_axes[1] = 1;
    apci_motion_status status;
    apci_segment segments[4];
    size_t count = 0;
    int step = 0;
    if (apci_spool_profile(board, &line, NULL) != APCI_OK)
        step = 2;
    else if (apci_spool_profile(board, &arc, NULL) != APCI_OK)
        step = 3;
    else if (apci_run_until_idle(board, 1000000u, &status) != APCI_OK)
        step = 4;
    else if (status.position[1] != 10.0 || (status.flags & APCI_MOTION_IDLE) == 0)
        step = 5;
    else if (apci_read_segments(board, segments, 4, &count) != APCI_OK || count != 2)
        step = 6;
    else if (segments[1].kind != APCI_SEGMENT_ARC || segments[1].ccw != 1 || segments[1].tag != 2)
        step = 7;
    else if (strcmp(apci_segment_role_name(segments[1].role), "uncompensated") != 0)
        step = 8;
    apci_close(board);
    return step;
}
