/* SPDX-License-Identifier: MIT */
/*
 * apci.h - the whole C API of libapci, the userspace driver for ADDI-DATA
 * APCI-8001/8008 motion-control boards running RWMOS.ELF.
 *
 * A PCAP program opens a board by device URI, then reads and writes typed
 * objects of the universal object interface, each addressed by an object
 * descriptor (BusNumber, DeviceNumber, Index, SubIndex) whose handle the
 * board fills in on first access. Plain C11; usable from C++ as is.
 *
 * Conventions
 *  - Every function that can fail returns an apci_status: APCI_OK (0) or one
 *    of the APCI_* codes below. No function aborts, throws or crashes on bad
 *    input: NULL pointers and malformed URIs answer APCI_INVALID_ARGUMENT.
 *  - A failed call changes nothing: output parameters are left untouched.
 *  - apci_last_error() says in words what the last call on a board did wrong,
 *    naming the object, e.g.
 *      "write 1300/1/1/4 = 2: WrongDeviceState (not possible in the present device state)".
 *
 * Threading
 *  - A board handle is NOT internally locked: use it from one thread at a
 *    time (any thread, but not concurrently; serialise with your own mutex if
 *    several threads share one board). Distinct boards are independent and
 *    may be used concurrently from different threads.
 *  - apci_status_name(), apci_status_message(), apci_tc_*_bit_name() and
 *    apci_version() are pure and may be called from any thread at any time.
 *
 * docs/c-api.md documents this API with the TC initialisation sequence of the
 * seed (APCI-8001 TC document, section 2.5) as a worked example.
 */
#ifndef APCI_APCI_H
#define APCI_APCI_H

#include <stddef.h>
#include <stdint.h>

#if defined(APCI_BUILDING_LIBRARY)
#define APCI_API __attribute__((visibility("default")))
#else
#define APCI_API
#endif

/* C++ callers see that no function of this API throws. */
#ifdef __cplusplus
#define APCI_NOEXCEPT noexcept
#else
#define APCI_NOEXCEPT
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Version ---------------------------------------------------------- */

#define APCI_VERSION_MAJOR 0
#define APCI_VERSION_MINOR 1
#define APCI_VERSION_PATCH 0

/* "0.1.0": the version of the library actually loaded. */
APCI_API const char* apci_version(void) APCI_NOEXCEPT;

/* ---- Status codes ----------------------------------------------------- */

/*
 * A status is a 32-bit code. The values are those of the object interface
 * (CANopen SDO abort codes where one fits; 0x0F00xxxx are board- and
 * transport-specific) and are the same on every transport and in the
 * emulator. Codes not listed here may appear in later versions;
 * apci_status_name() answers "Unknown" for them.
 */
typedef uint32_t apci_status;

#define APCI_OK                  ((apci_status)0x00000000u)
/* Addressing, checked in this order: bus/device, index, subindex, handle. */
#define APCI_NO_SUCH_DEVICE      ((apci_status)0x06020001u) /* bus/device absent (e.g. no optionTC) */
#define APCI_OBJECT_MISSING      ((apci_status)0x06020000u) /* no object with this index */
#define APCI_SUB_MISSING         ((apci_status)0x06090011u) /* no such subindex */
#define APCI_STALE_HANDLE        ((apci_status)0x0F000001u) /* handle discarded (TC Clean): zero it */
#define APCI_HANDLE_MISMATCH     ((apci_status)0x0F000002u) /* handle names another object */
/* Access. */
#define APCI_READ_ONLY           ((apci_status)0x06010002u)
#define APCI_WRITE_ONLY          ((apci_status)0x06010001u)
/* Type and range. */
#define APCI_TYPE_MISMATCH       ((apci_status)0x06070010u) /* int accessor on a double object or v.v. */
#define APCI_VALUE_TOO_HIGH      ((apci_status)0x06090031u)
#define APCI_VALUE_TOO_LOW       ((apci_status)0x06090032u)
#define APCI_INVALID_VALUE       ((apci_status)0x06090030u) /* NaN, infinity, not a permitted value */
/* State. */
#define APCI_WRONG_DEVICE_STATE  ((apci_status)0x08000022u) /* e.g. XAxis written while compensation runs */
#define APCI_BUSY                ((apci_status)0x0F000010u) /* spooler full, nothing taken: retry */
#define APCI_GENERAL_ERROR       ((apci_status)0x08000000u)
/* Frames and transports. */
#define APCI_BAD_FRAME           ((apci_status)0x0F000100u)
#define APCI_UNKNOWN_OPCODE      ((apci_status)0x0F000101u)
#define APCI_TRANSPORT_ERROR     ((apci_status)0x0F000200u) /* link to the board failed */
#define APCI_TIMEOUT             ((apci_status)0x05040000u)
#define APCI_NOT_SUPPORTED       ((apci_status)0x0F000300u) /* device or transport cannot do this */
#define APCI_INVALID_ARGUMENT    ((apci_status)0x0F000301u) /* NULL pointer, malformed URI, ... */
#define APCI_NO_MEMORY           ((apci_status)0x0F000302u)

/* Number of codes listed above. */
#define APCI_STATUS_COUNT 22

/* "TypeMismatch" for APCI_TYPE_MISMATCH; "Unknown" for a code not listed. Never NULL. */
APCI_API const char* apci_status_name(apci_status status) APCI_NOEXCEPT;
/* One line of English for a user. Never NULL. */
APCI_API const char* apci_status_message(apci_status status) APCI_NOEXCEPT;

/* ---- Boards ------------------------------------------------------------- */

/* An open board. Opaque; created by apci_open(), destroyed by apci_close(). */
typedef struct apci_board apci_board;

/*
 * Opens the board named by `uri` and stores its handle in *out.
 *
 *   NULL, "" or "emu:"    the embedded emulator: a fresh RWMOS board inside
 *                         this process (virtual time, no daemon needed).
 *   "emu:?no-option-tc"   the embedded emulator without the firmware option
 *                         optionTC: the TC module (bus 1300) is absent and
 *                         every access to it answers APCI_NO_SUCH_DEVICE.
 *                         Options follow '?' and are separated by '&';
 *                         "option-tc" (the default) turns it back on.
 *   "unix:PATH"           the emulator daemon's socket         } answer
 *   "shm:PATH"            a dual-port RAM image / mailbox file  } APCI_NOT_SUPPORTED
 *   "pci:DOMAIN:BUS:DEV.FN"  a board's PCI BAR                  } in this version
 *   "usb:[BUS:ADDR]"      a board on USB                        }
 *
 * Errors: APCI_INVALID_ARGUMENT (out is NULL; unknown scheme or option;
 * malformed URI), APCI_NOT_SUPPORTED (transport not available), transport
 * errors. On failure *out is set to NULL and apci_last_error(NULL) says why.
 * Blocks until the board answers (the embedded emulator answers at once).
 */
APCI_API apci_status apci_open(const char* uri, apci_board** out) APCI_NOEXCEPT;

/* Closes the board and frees its handle. NULL is accepted and ignored. */
APCI_API void apci_close(apci_board* board) APCI_NOEXCEPT;

/*
 * What the last call on `board` did wrong, in one line naming the operation
 * and the object ("read 1300/1/9/3: ObjectMissing (object index does not
 * exist)"), or "" if that call succeeded. Each call on the board replaces it.
 * With board == NULL: the last failed apci_open() or call with a NULL board
 * on the calling thread. The text stays valid until the next call on the same
 * board (or, for NULL, on the same thread). Never NULL.
 */
APCI_API const char* apci_last_error(const apci_board* board) APCI_NOEXCEPT;

/* ---- Objects ------------------------------------------------------------ */

/*
 * An object descriptor. Set bus, device, index, subindex and handle = 0; the
 * first successful access fills in the handle and later accesses use it.
 * Seed rule (APCI-8001 TC document, Table 2, "Clean"): writing TC Clean
 * (1300/0/1/0) discards every TC object; a descriptor that still carries an
 * old handle is refused with APCI_STALE_HANDLE. Zero the handle of every TC
 * descriptor after Clean. Changing bus/device/index/subindex without zeroing
 * the handle answers APCI_HANDLE_MISMATCH.
 */
typedef struct apci_object_descriptor {
    int32_t bus;       /* BusNumber, e.g. 1300 for the TC module */
    int32_t device;    /* DeviceNumber */
    int32_t index;     /* Index */
    int32_t subindex;  /* SubIndex */
    uint32_t handle;   /* 0 = not yet resolved; filled in by the board */
} apci_object_descriptor;

/*
 * Typed object access. The accessor's type must match the object's (int32 or
 * double), otherwise APCI_TYPE_MISMATCH; doubles must be finite. The checks
 * run in the order bus/device, index, subindex, handle, access, type, range,
 * state; a refused write changes nothing on the board.
 *
 * `board` and `object` must not be NULL (APCI_INVALID_ARGUMENT); reads need a
 * non-NULL `value`, which is written only on APCI_OK. object->handle is
 * filled in on the first access that resolves the object.
 *
 * Blocking: each call returns when the board has answered (in-process:
 * immediately; other transports: one request/reply round trip, bounded by
 * the transport's timeout, then APCI_TIMEOUT).
 */
APCI_API apci_status apci_read_int(apci_board* board, apci_object_descriptor* object,
                                   int32_t* value) APCI_NOEXCEPT;
APCI_API apci_status apci_write_int(apci_board* board, apci_object_descriptor* object,
                                    int32_t value) APCI_NOEXCEPT;
APCI_API apci_status apci_read_double(apci_board* board, apci_object_descriptor* object,
                                      double* value) APCI_NOEXCEPT;
APCI_API apci_status apci_write_double(apci_board* board, apci_object_descriptor* object,
                                       double value) APCI_NOEXCEPT;

/* ---- TC module (bus 1300): seed names, APCI-8001 TC document ------------ */

#define APCI_TC_BUS 1300
#define APCI_TC_DEVICE_INIT 0  /* Table 2: initialisation */
#define APCI_TC_DEVICE_GROUP 1 /* Table 3: compensation groups, Index = group 1..3, 0 = active */

/* DeviceNumber 0, Index (Table 2; 13 and 14 are this project's numbers for ReInit and Reset). */
#define APCI_TC_CLEAN 1
#define APCI_TC_AXIS_NR 11 /* SubIndex 0,1,2: X/Y/Z-Axis-Nr */
#define APCI_TC_PLANE 12   /* TcPlane: 17 X-Y, 18 Z-X, 19 Y-Z */
#define APCI_TC_REINIT 13
#define APCI_TC_RESET 14
#define APCI_TC_ROT_ANGLE 20    /* double, degrees */
#define APCI_TC_ROT_CENTER_X 21 /* double */
#define APCI_TC_ROT_CENTER_Y 22 /* double */

/* DeviceNumber 1, SubIndex (Table 3). */
#define APCI_TC_ERROR 1
#define APCI_TC_GROUP_RESET 2
#define APCI_TC_STATUS 3
#define APCI_TC_XAXIS 4
#define APCI_TC_YAXIS 5
#define APCI_TC_RADIUS 7 /* double */
#define APCI_TC_WKZINDEX 8
#define APCI_TC_LEFT 9
#define APCI_TC_RIGHT 10
#define APCI_TC_ZAXIS 11
#define APCI_TC_WKZLEN 12 /* double */

/* ERROR bits (Table 4). */
#define APCI_TC_ERROR_INIT 0x01u   /* InitError */
#define APCI_TC_ERROR_KORR 0x02u   /* KorrError: compensation impossible */
#define APCI_TC_ERROR_CALC 0x04u   /* CalcError */
#define APCI_TC_ERROR_PLANE 0x08u  /* PlaneError */
#define APCI_TC_ERROR_CENTER 0x10u /* CenterError */
/* STATUS bits (Table 5). */
#define APCI_TC_STATUS_RUN 0x01u         /* Run */
#define APCI_TC_STATUS_PROF_MARKED 0x02u /* ProfMarked: a profile is held back */

/* Seed name of ERROR / STATUS bit number `bit` (0 = least significant):
 * "InitError", ..., "Run", "ProfMarked"; NULL for a bit the seed does not define. */
APCI_API const char* apci_tc_error_bit_name(int bit) APCI_NOEXCEPT;
APCI_API const char* apci_tc_status_bit_name(int bit) APCI_NOEXCEPT;

#ifdef __cplusplus
}
#endif

#endif /* APCI_APCI_H */
