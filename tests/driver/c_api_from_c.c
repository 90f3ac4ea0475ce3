/* SPDX-License-Identifier: MIT */
/* apci.h compiled as strict C11: the whole C API is usable from C. */
#include "apci/apci.h"

#include <string.h>

/* Opens the embedded board, writes and reads one object of each type.
 * Returns 0 on success, else the number of the failed step. */
int c_api_round_trip(void) {
    apci_board* board = NULL;
    if (apci_open(NULL, &board) != APCI_OK) return 1;
    apci_object_descriptor wkzindex = {APCI_TC_BUS, APCI_TC_DEVICE_GROUP, 1, APCI_TC_WKZINDEX, 0};
    apci_object_descriptor radius = {APCI_TC_BUS, APCI_TC_DEVICE_GROUP, 1, APCI_TC_RADIUS, 0};
    int32_t i = 0;
    double d = 0.0;
    int step = 0;
    if (apci_write_int(board, &wkzindex, 4) != APCI_OK) step = 2;
    else if (apci_read_int(board, &wkzindex, &i) != APCI_OK || i != 4) step = 3;
    else if (apci_write_double(board, &radius, 0.75) != APCI_OK) step = 4;
    else if (apci_read_double(board, &radius, &d) != APCI_OK || d != 0.75) step = 5;
    else if (apci_read_int(board, &radius, &i) != APCI_TYPE_MISMATCH) step = 6;
    else if (strstr(apci_last_error(board), "TypeMismatch") == NULL) step = 7;
    apci_close(board);
    return step;
}
