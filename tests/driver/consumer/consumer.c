/* SPDX-License-Identifier: MIT */
#include <stdio.h>

#include <apci/apci.h>

int main(void) {
    apci_board* board = NULL;
    if (apci_open("emu:", &board) != APCI_OK) {
        fprintf(stderr, "%s\n", apci_last_error(NULL));
        return 1;
    }
    apci_object_descriptor plane = {APCI_TC_BUS, APCI_TC_DEVICE_INIT, APCI_TC_PLANE, 0, 0};
    int32_t v = 0;
    const apci_status s = apci_read_int(board, &plane, &v);
    printf("TcPlane %d (%s)\n", (int)v, apci_status_name(s));
    apci_close(board);
    return s == APCI_OK ? 0 : 1;
}
