// SPDX-License-Identifier: MIT
/*
 * pcap_tc_init: a PCAP-style C program that initialises and uses the tool
 * radius compensation of an APCI-8001/8008 board, following the APCI-8001 TC
 * document, [APCI-TC] section 2.5 "Verwendung von TC" (docs/references.md):
 *
 *   initialisation: RESET; compensation plane (XAxis, YAxis, ZAxis);
 *                   tool table: for each tool WKZINDEX, then RADIUS
 *   use:            select WKZINDEX; Left or Right; STATUS = 1;
 *                   (spool and run profiles); read STATUS and ERROR back;
 *                   STATUS = 0
 *
 * then shows the Clean rule (Table 2, "Clean"): after Clean the board refuses
 * the old handles; zeroed descriptors work again.
 *
 * Usage: pcap_tc_init [URI]   (default: the embedded emulator, emu:)
 * Exit status 0 when every step answered as [APCI-TC] says, 1 otherwise.
 */
#include <stdio.h>
#include <stdlib.h>

#include "apci/apci.h"

#define GROUP 1 /* compensation group (Index); the user's choice, 1..3 */

static apci_object_descriptor tc_group_object(int32_t subindex) {
    apci_object_descriptor o = {APCI_TC_BUS, APCI_TC_DEVICE_GROUP, GROUP, subindex, 0};
    return o;
}

/* Reports a failed call and says which step it was. */
static int check(apci_board* board, apci_status status, const char* step) {
    if (status == APCI_OK) return 1;
    fprintf(stderr, "pcap_tc_init: %s failed: %s\n", step, apci_last_error(board));
    return 0;
}

static void print_error_register(int32_t value) {
    printf("  ERROR  0x%02X", (unsigned)value);
    if (value == 0) printf(" none");
    for (int bit = 0; bit < 32; ++bit) {
        if (((uint32_t)value & (1u << bit)) == 0) continue;
        const char* name = apci_tc_error_bit_name(bit);
        if (name != NULL) printf(" %s", name); else printf(" bit%d", bit);
    }
    printf("\n");
}

static void print_status_register(int32_t value) {
    printf("  STATUS 0x%02X", (unsigned)value);
    for (int bit = 0; apci_tc_status_bit_name(bit) != NULL; ++bit)
        printf(" %s=%s", apci_tc_status_bit_name(bit),
               ((uint32_t)value & (1u << bit)) ? "on" : "off");
    printf("\n");
}

struct tool {
    int32_t index; /* WKZINDEX, 0..1023 */
    double radius; /* in the unit selected by PU */
};

int main(int argc, char** argv) {
    const char* uri = argc > 1 ? argv[1] : "emu:";
    static const struct tool tools[] = {{1, 2.5}, {2, 5.0}, {7, 0.8}};
    const int32_t selected_tool = 2;

    apci_board* board = NULL;
    if (!check(NULL, apci_open(uri, &board), "open")) return 1;
    printf("board %s, libapci %s\n", uri, apci_version());

    /* One descriptor per object, kept for the whole program: the handle the
     * board fills in on first access is reused on every later access. */
    apci_object_descriptor reset = tc_group_object(APCI_TC_GROUP_RESET);
    apci_object_descriptor x_axis = tc_group_object(APCI_TC_XAXIS);
    apci_object_descriptor y_axis = tc_group_object(APCI_TC_YAXIS);
    apci_object_descriptor z_axis = tc_group_object(APCI_TC_ZAXIS);
    apci_object_descriptor wkzindex = tc_group_object(APCI_TC_WKZINDEX);
    apci_object_descriptor radius = tc_group_object(APCI_TC_RADIUS);
    apci_object_descriptor left = tc_group_object(APCI_TC_LEFT);
    apci_object_descriptor status = tc_group_object(APCI_TC_STATUS);
    apci_object_descriptor error = tc_group_object(APCI_TC_ERROR);
    apci_object_descriptor clean = {APCI_TC_BUS, APCI_TC_DEVICE_INIT, APCI_TC_CLEAN, 0, 0};

    int ok = 1;
    int32_t value = 0;
    double r = 0.0;

    /* Initialisation. */
    ok = ok && check(board, apci_write_int(board, &reset, 0), "RESET");
    ok = ok && check(board, apci_write_int(board, &x_axis, 0), "XAxis = 0");
    ok = ok && check(board, apci_write_int(board, &y_axis, 1), "YAxis = 1");
    ok = ok && check(board, apci_write_int(board, &z_axis, 2), "ZAxis = 2");
    if (ok) printf("group %d: RESET, plane XAxis 0, YAxis 1, ZAxis 2\n", GROUP);
    for (size_t i = 0; ok && i < sizeof tools / sizeof tools[0]; ++i) {
        ok = check(board, apci_write_int(board, &wkzindex, tools[i].index), "WKZINDEX") &&
             check(board, apci_write_double(board, &radius, tools[i].radius), "RADIUS") &&
             check(board, apci_read_double(board, &radius, &r), "read RADIUS");
        if (ok) printf("tool %d: RADIUS %g\n", (int)tools[i].index, r);
        if (ok && r != tools[i].radius) {
            fprintf(stderr, "pcap_tc_init: tool %d reads back RADIUS %g, wrote %g\n",
                    (int)tools[i].index, r, tools[i].radius);
            ok = 0;
        }
    }

    /* Use: select the tool, the side, activate. */
    ok = ok && check(board, apci_write_int(board, &wkzindex, selected_tool), "select WKZINDEX");
    ok = ok && check(board, apci_write_int(board, &left, 1), "Left");
    ok = ok && check(board, apci_write_int(board, &status, 1), "STATUS = 1");
    if (ok) printf("compensation on: tool %d, left\n", (int)selected_tool);
    /* (Here a PCAP program spools its profiles and runs them.) */
    ok = ok && check(board, apci_read_int(board, &status, &value), "read STATUS");
    if (ok) {
        print_status_register(value);
        if (!(value & APCI_TC_STATUS_RUN)) {
            fprintf(stderr, "pcap_tc_init: STATUS says Run off after STATUS = 1\n");
            ok = 0;
        }
    }
    ok = ok && check(board, apci_read_int(board, &error, &value), "read ERROR");
    if (ok) {
        print_error_register(value);
        if (value != 0) {
            fprintf(stderr, "pcap_tc_init: ERROR is set after activation\n");
            ok = 0;
        }
    }
    ok = ok && check(board, apci_write_int(board, &status, 0), "STATUS = 0");
    ok = ok && check(board, apci_read_int(board, &status, &value), "read STATUS");
    if (ok) {
        printf("compensation off:\n");
        print_status_register(value);
    }

    /* The Clean rule: every TC handle becomes stale; zeroed ones work again. */
    ok = ok && check(board, apci_write_int(board, &clean, 1), "Clean");
    if (ok) {
        const apci_status refused = apci_read_int(board, &status, &value);
        if (refused == APCI_STALE_HANDLE) {
            printf("after Clean, the old STATUS handle is refused: %s\n", apci_last_error(board));
        } else {
            fprintf(stderr, "pcap_tc_init: after Clean the old handle answered %s, not "
                    "StaleHandle\n", apci_status_name(refused));
            ok = 0;
        }
    }
    if (ok) {
        status.handle = 0;
        ok = check(board, apci_read_int(board, &status, &value), "read STATUS with zeroed handle");
        if (ok) {
            printf("with the handle zeroed, STATUS reads again:\n");
            print_status_register(value);
        }
    }

    apci_close(board);
    printf("%s\n", ok ? "done" : "FAILED");
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
