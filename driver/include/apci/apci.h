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
 * docs/c-api.md documents this API with the TC initialisation sequence of
 * [APCI-TC] section 2.5 (docs/references.md) as a worked example.
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
#define APCI_VERSION_MINOR 2
#define APCI_VERSION_PATCH 0

/* "0.2.0": the version of the library actually loaded. */
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
#define APCI_MOTION_CLAIMED      ((apci_status)0x0F000011u) /* another handle holds the motion (apci_claim_motion) */
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
#define APCI_STATUS_COUNT 23

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
 *   "unix:PATH"           the emulator daemon (rwmos-emu --socket PATH)
 *   "shm:PATH"            the dual-port RAM file rwmos-emu --shm PATH serves
 *   "pci:DOMAIN:BUS:DEV.FN"  a board's dual-port RAM through its PCI BAR
 *                         (sysfs resourceN; options bar=N, offset=BYTES, uio)
 *   "usb:" / "usb:BUS:ADDR"  the first USB board, or the one at BUS:ADDR
 *                         (options pid=0xNNNN)
 * Every transport but emu: takes "?timeout=MS" (default 2000): the longest
 * one request waits for its reply (see apci_set_timeout()). docs/transports.md
 * describes each one; apcictl list prints the URIs of the boards found.
 *
 * Errors: APCI_INVALID_ARGUMENT (out is NULL; unknown scheme or option;
 * malformed URI), APCI_NOT_SUPPORTED (transport not built in), transport
 * errors (APCI_TRANSPORT_ERROR: no such socket, file, board; no permission).
 * On failure *out is set to NULL and apci_last_error(NULL) says why.
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

/*
 * The board's own words for the last call on `board` if it was a spool,
 * direct command or SSF call the board refused: the reason its firmware gave
 * ("element is too short for the corner at its start: its offset would
 * reverse"), which
 * apci_last_error() also contains among the call's name and status. "" when
 * the last call succeeded, was another call, or the board gave no reason (and
 * for board == NULL). Valid until the next call on the board. Never NULL.
 */
APCI_API const char* apci_last_board_message(const apci_board* board) APCI_NOEXCEPT;

/* ---- The link to the board ---------------------------------------------- */

/*
 * Timeout: the longest one request (read, write, ...) waits for the board's
 * answer before it fails with APCI_TIMEOUT, in milliseconds (1 .. 3600000;
 * default 2000, or the URI's ?timeout=MS). After a timeout the board may
 * still act on the request; its late reply is recognised and dropped.
 * The embedded emulator never waits and keeps the value only to report it.
 * Errors: APCI_INVALID_ARGUMENT (board NULL, milliseconds 0 or too large).
 */
APCI_API apci_status apci_set_timeout(apci_board* board, uint32_t milliseconds) APCI_NOEXCEPT;
APCI_API apci_status apci_get_timeout(const apci_board* board, uint32_t* milliseconds) APCI_NOEXCEPT;

/*
 * 1 while the link to the board works, 0 once it is known to be lost (the
 * daemon closed the socket or stopped, the dual-port RAM's board stopped or
 * restarted, the USB board was unplugged; or board is NULL). A daemon that
 * closed its socket (its idle timeout, a shutdown) is seen without a request;
 * the next request still fails, with the daemon's words. A lost link is
 * not reopened behind the caller's back: every call answers
 * APCI_TRANSPORT_ERROR, apci_last_error() saying what happened, until
 * apci_reconnect() succeeds. Non-blocking.
 */
APCI_API int apci_is_connected(const apci_board* board) APCI_NOEXCEPT;

/*
 * What ended the board's link, in words, without what to do about it: "usb:1:4 was unplugged
 * (port 1-2)", "daemon /run/user/1000/rwmos-emu.sock closed the connection: shutting down
 * (SIGTERM)". apci_last_error() of a call that found the link lost says this, then how
 * apci_reconnect() opens it again; a program that opens links in its own way (a tool, a shell)
 * can give its own hint after it. Written as snprintf writes: at most size - 1 bytes and a NUL
 * (nothing where text is NULL or size 0). Returns the whole length: 0 while the link works (or
 * before a request found it lost), for the embedded emulator, or where board is NULL.
 */
APCI_API size_t apci_link_lost(const apci_board* board, char* text, size_t size) APCI_NOEXCEPT;

/*
 * Closes the link and opens it again to the same device: the same socket or
 * file, the same PCI function, the USB board on the same port (for "usb:",
 * the first board found). The board's own state is what the board kept (a
 * re-plugged board or a restarted daemon starts afresh: zero the handles of
 * your descriptors). The embedded emulator has no link: APCI_OK, state kept.
 * Errors: as apci_open(); on failure the link stays closed.
 */
APCI_API apci_status apci_reconnect(apci_board* board) APCI_NOEXCEPT;

/* ---- Exclusive use of the board's motion ------------------------------------ */

/*
 * A handle that claims the board's motion holds it until it releases it, closes, reconnects or
 * its process ends (as libusb_claim_interface holds an interface, or flock a file). While one
 * handle holds it, every other handle's request that starts or changes motion or takes from the
 * holder's record -- object writes, profiles, direct and SSF commands, stepping or running the
 * clock, trace on/off, reading samples or segments -- is refused with APCI_MOTION_CLAIMED and
 * changes nothing; apci_last_error() names the holder ("the board's motion is held by pid 4242
 * (apcictl) since 2024-05-01 12:00:00 UTC"). Object reads and apci_motion_status_get stay open
 * to every handle. A board nobody claims serves every handle as before. docs/motion-claim.md
 * says what each transport can do: the daemon keeps the claim per connection (unix:) and per
 * process (shm:, and pci: through a bridge that serves it); emu: boards are each handle's own;
 * usb: is the opening handle's alone already (the interface claim).
 */

/*
 * Claims the board's motion for `board`.
 * Errors: APCI_INVALID_ARGUMENT (board NULL); APCI_MOTION_CLAIMED (another handle holds it:
 * apci_last_error() names it; nothing changed); APCI_WRONG_DEVICE_STATE (this handle holds it
 * already: a claim is not counted, so a second would be released by the first release);
 * APCI_NOT_SUPPORTED (the board does not serve claims); transport errors.
 */
APCI_API apci_status apci_claim_motion(apci_board* board) APCI_NOEXCEPT;

/*
 * Releases the claim `board` holds. The handle no longer holds it afterwards, whatever the
 * board answered (a lost link has ended it on the board's side).
 * Errors: APCI_INVALID_ARGUMENT (board NULL); APCI_WRONG_DEVICE_STATE (this handle holds no
 * claim); transport errors.
 */
APCI_API apci_status apci_release_motion(apci_board* board) APCI_NOEXCEPT;

/* Who holds the board's motion (apci_motion_claim_get). */
typedef struct apci_motion_claim {
    int32_t held;      /* 1: a handle holds the motion */
    int32_t yours;     /* 1: it is this handle */
    int32_t pid;       /* the holder's process id; 0 when the board does not know it */
    uint32_t reserved; /* 0 */
    uint64_t since_ms; /* when it claimed, milliseconds since 1970-01-01 UTC; 0 if unknown */
    char name[16];     /* the holder's command name, NUL-terminated; "" if unknown */
} apci_motion_claim;

/* Asks the board who holds its motion, changing nothing.
 * Errors: APCI_INVALID_ARGUMENT (board or claim NULL); APCI_NOT_SUPPORTED; transport errors. */
APCI_API apci_status apci_motion_claim_get(apci_board* board, apci_motion_claim* claim) APCI_NOEXCEPT;

/* The holder of `claim` named as libapci names it in a refusal: "pid 4242 (apcictl) since
 * 2024-05-01 12:00:00 UTC", "pid 4242", "another host", a host's name; "" when nobody holds it
 * (claim NULL, or held 0). Writes at most `size` bytes, the NUL included, into `text` (which
 * may be NULL when size is 0) and returns the length of the whole name, as snprintf does: a
 * result of `size` or more means it was cut short. */
APCI_API size_t apci_motion_claim_holder(const apci_motion_claim* claim, char* text,
                                         size_t size) APCI_NOEXCEPT;

/* ---- Finding boards ------------------------------------------------------- */

/* Called once per board found: its device URI (for apci_open) and one line
 * describing it. Both strings are valid during the call only. */
typedef void (*apci_found_fn)(const char* uri, const char* description, void* user);

/*
 * Lists the boards this machine can reach: USB boards (libusb: ADDI-DATA
 * vendor IDs 0x15B8 and 0x10E8 with the frame interface), PCI boards (sysfs)
 * and running emulator daemons (their sockets and dual-port RAM files), in
 * that order, calling `found` for each. A kind of board that cannot be
 * enumerated is skipped; apci_last_error(NULL) then names it, and the call
 * still answers APCI_OK. Errors: APCI_INVALID_ARGUMENT (found is NULL).
 * Blocking: enumeration of the buses and one connect per emulator socket.
 */
APCI_API apci_status apci_list_devices(apci_found_fn found, void* user) APCI_NOEXCEPT;

/* ---- Objects ------------------------------------------------------------ */

/*
 * An object descriptor. Set bus, device, index, subindex and handle = 0; the
 * first successful access fills in the handle and later accesses use it.
 * Rule of [APCI-TC] Table 2, "Clean": writing TC Clean
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

/* ---- TC module (bus 1300): the names of the APCI-8001 TC document [APCI-TC] */

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

/* [APCI-TC] name of ERROR / STATUS bit number `bit` (0 = least significant):
 * "InitError", ..., "Run", "ProfMarked"; NULL for a bit [APCI-TC] does not define. */
APCI_API const char* apci_tc_error_bit_name(int bit) APCI_NOEXCEPT;
APCI_API const char* apci_tc_status_bit_name(int bit) APCI_NOEXCEPT;

/* ---- Motion: profiles, direct and SSF commands, clock, trace ----------- */
/*
 * The board moves APCI_AXIS_COUNT axes along spooled profiles (docs/motion.md).
 * Positions are in interpolation units, feeds in interpolation units per
 * minute (F of DIN 66025), time in interpolation cycles (board object
 * InterpolationCycle, bus 1000, default 1 ms). The embedded emulator runs in
 * virtual time: nothing moves until the clock is advanced (apci_step,
 * apci_run_until_idle), and the same calls give the same results bit for bit.
 *
 * Rules of [APCI-TC] section 1: while a TC group
 * compensates, one profile is held back (STATUS bit ProfMarked); the next
 * profile releases it corrected, with the transition between them; writing
 * STATUS = 0 or sending SSF command 2001 releases the last one; a direct
 * command (JA, JS) discards the spooler and the held profile; a G00 profile
 * is never compensated nor rotated, and the next G01/G02/G03 approaches the
 * compensated path anew. On a TC error nothing moves incorrectly: the
 * spooler holds, Run clears, and the ERROR bit stays until ERROR is written.
 *
 * Blocking: as the object accessors; a clock call returns when the clock
 * has run. Every call answers APCI_NOT_SUPPORTED on a transport without
 * motion support; a refused call changes nothing.
 */

#define APCI_AXIS_COUNT 8

/* Profile kinds: the G codes. */
#define APCI_PROFILE_RAPID 0   /* G00: point to point, never compensated or rotated */
#define APCI_PROFILE_LINE 1    /* G01 */
#define APCI_PROFILE_ARC_CW 2  /* G02 */
#define APCI_PROFILE_ARC_CCW 3 /* G03 */
#define APCI_PROFILE_TRAVERSE 4 /* G00 on the compensated path: compensated and rotated as a
                                   G01 at `feed` (0 = the rapid feed); a rapid for everything
                                   else (OTC wears nothing on it). An extension (docs/motion.md) */

/* One motion profile (one NC block's move). Unnamed axes keep their position. */
typedef struct apci_profile {
    uint8_t kind;        /* APCI_PROFILE_* */
    uint8_t axes;        /* bit i set: axis i is named and moves to target[i] */
    uint8_t arc_axes[2]; /* arcs: the axes the arc is named in, first and second;
                            once a TC object was accessed the arc runs in the
                            active plane (TcPlane) and must be named in its axes */
    uint32_t tag;        /* the NC block number, carried into every executed segment */
    double feed;         /* units per minute, > 0; G00 and traverse: 0 = the board's rapid feed */
    double target[APCI_AXIS_COUNT]; /* absolute targets (program coordinates) */
    double center[2];    /* arcs: centre on arc_axes[0], arc_axes[1], absolute */
} apci_profile;

/* What a motion call set on the TC module besides its status. */
typedef struct apci_motion_result {
    int32_t group;  /* TC group whose ERROR got `errors` and whose Run cleared; 0: none */
    int32_t errors; /* ERROR bits (APCI_TC_ERROR_*) this call set */
    uint32_t tag;   /* the block (profile tag) at fault */
} apci_motion_result;

/*
 * Spools one profile. `result` may be NULL; it is filled whenever the board
 * answered. APCI_BUSY: the spooler cannot take the moves the profile yields;
 * nothing was taken: advance the clock and spool it again.
 * APCI_WRONG_DEVICE_STATE with result->errors != 0: a TC error (the spooler
 * holds until ERROR is written); with errors == 0: the spooler already holds,
 * or an arc lies outside the active plane and no group is there to record it.
 * Range and value errors name the bad field in apci_last_error().
 */
APCI_API apci_status apci_spool_profile(apci_board* board, const apci_profile* profile,
                                        apci_motion_result* result) APCI_NOEXCEPT;

/* Direct commands ([APCI-TC] names JA and JS; their meaning is this project's). */
#define APCI_DIRECT_JA 1 /* jog absolute: the named axes move to target at feed (0: rapid) */
#define APCI_DIRECT_JS 2 /* jog stop: every axis stops where it is; axes must be 0 */

typedef struct apci_direct_command {
    uint16_t code; /* APCI_DIRECT_* */
    uint8_t axes;  /* JA: the axes to move (bit i = axis i) */
    double feed;   /* JA: units per minute, 0 = rapid feed */
    double target[APCI_AXIS_COUNT]; /* JA: absolute targets of the named axes */
} apci_direct_command;

/* Discards the spooler content and the held profile, then acts. */
APCI_API apci_status apci_direct_command_send(apci_board* board,
                                              const apci_direct_command* command) APCI_NOEXCEPT;

/* SSF command 2001 to the axes of a compensation group releases its held profile. */
#define APCI_SSF_RELEASE_HELD_PROFILE 2001

/* Sends SSF `command` to the axes in `axes` (bit i = axis i). `result` may be NULL. */
APCI_API apci_status apci_ssf_command(apci_board* board, uint8_t axes, int32_t command,
                                      apci_motion_result* result) APCI_NOEXCEPT;

/* Flags of apci_motion_status.flags. */
#define APCI_MOTION_IDLE 0x01u         /* nothing moves: spooler empty, or held */
#define APCI_MOTION_HELD 0x02u         /* the spooler holds after a TC error */
#define APCI_MOTION_PROFILE_HELD 0x04u /* the compensating group holds a profile */
#define APCI_MOTION_TRACING 0x08u      /* per-cycle samples are recorded */

typedef struct apci_motion_status {
    uint64_t now;        /* interpolation cycles since the board started */
    uint64_t ran;        /* cycles the call that filled this advanced the clock */
    uint32_t flags;      /* APCI_MOTION_* */
    uint32_t fill;       /* moves in the spooler (the one under way included) */
    uint32_t capacity;   /* the most moves the spooler takes */
    int32_t compensating_group; /* 0: no compensation under way */
    uint64_t trace_pending, trace_lost;       /* samples waiting / dropped unread */
    uint64_t segments_pending, segments_lost; /* executed segments waiting / dropped */
    double position[APCI_AXIS_COUNT];         /* axis positions now */
} apci_motion_status;

/*
 * Advances the clock by exactly `cycles` cycles. `status` may be NULL.
 * The board advances at most 2^20 cycles per request; these two calls send
 * as many requests as it takes (a daemon serves its other clients in
 * between), and status->ran is the sum. On a failure part-way the clock may
 * have advanced by whole requests; apci_motion_status_get tells where it is.
 */
APCI_API apci_status apci_step(apci_board* board, uint64_t cycles,
                               apci_motion_status* status) APCI_NOEXCEPT;
/* Advances until nothing moves, at most `max_cycles`; status->ran says how far. */
APCI_API apci_status apci_run_until_idle(apci_board* board, uint64_t max_cycles,
                                         apci_motion_status* status) APCI_NOEXCEPT;
/* The motion status without advancing the clock. */
APCI_API apci_status apci_motion_status_get(apci_board* board,
                                            apci_motion_status* status) APCI_NOEXCEPT;
/* Spooler fill level and capacity (the bus 1000 objects SpoolerFill, SpoolerCapacity). */
APCI_API apci_status apci_spooler_fill(apci_board* board, uint32_t* fill,
                                       uint32_t* capacity) APCI_NOEXCEPT;

/*
 * Per-cycle samples: capacity > 0 turns them on with a ring of `capacity`
 * samples (at most 2^24; the oldest unread ones are dropped and counted when
 * it is full); 0 turns them off. Either drops the samples not yet read.
 * A daemon gives the trace at most its --trace-memory (64 MiB, 932067
 * samples, unless set): a larger ring is refused with APCI_NO_MEMORY.
 * With samples off the emulator runs through a move at no cost per cycle.
 */
APCI_API apci_status apci_trace_enable(apci_board* board, uint32_t capacity) APCI_NOEXCEPT;

typedef struct apci_trace_sample {
    uint64_t cycle;                   /* clock value after the cycle (1 = the first) */
    double position[APCI_AXIS_COUNT]; /* axis positions after it */
} apci_trace_sample;

/* Moves up to `max` of the oldest samples into `out`; *count says how many. */
APCI_API apci_status apci_read_trace(apci_board* board, apci_trace_sample* out, size_t max,
                                     size_t* count) APCI_NOEXCEPT;

/* Executed segment kinds and roles (docs/design.md section 7, `run --json`). */
#define APCI_SEGMENT_LINE 0
#define APCI_SEGMENT_ARC 1
#define APCI_ROLE_CONTOUR 0       /* a compensated G01/G02/G03 element */
#define APCI_ROLE_TRANSITION 1    /* corner transition (tag: the element before the corner) */
#define APCI_ROLE_APPROACH 2      /* onto the compensated path (tag: the first element) */
#define APCI_ROLE_DEPARTURE 3     /* back to the programmed end (tag: the last element) */
#define APCI_ROLE_UNCOMPENSATED 4 /* a G01/G02/G03 element without compensation */
#define APCI_ROLE_RAPID 5         /* a G00 profile, or a JA move (tag 0) */

/* One executed segment in machine coordinates (after rotation and compensation). */
typedef struct apci_segment {
    uint32_t tag;        /* block number of the profile it came from */
    uint8_t kind;        /* APCI_SEGMENT_* */
    uint8_t role;        /* APCI_ROLE_* */
    uint8_t ccw;         /* arcs: 1 counter-clockwise (G03 sense), 0 clockwise */
    uint8_t interrupted; /* 1: cut short by a direct command; end is where it stopped */
    uint8_t plane_axes[2]; /* arcs: the board axes of the arc's plane, first and second */
    uint8_t traverse;    /* 1: from an APCI_PROFILE_TRAVERSE profile (a G00 on the compensated
                            path: a rapid move) */
    int32_t plane;       /* arcs: 17, 18, 19 when those are a TC plane's axes, else 0 */
    double start[APCI_AXIS_COUNT];
    double end[APCI_AXIS_COUNT];
    double center[APCI_AXIS_COUNT]; /* arcs: centre on plane_axes, start on the others */
    double feed;                    /* units per minute */
    uint64_t start_cycle, end_cycle;
    /* The tool length compensation the board added in start and in end, per axis (the tool
       length on the length axis while it acts, 0 elsewhere; an interrupted segment's end: where
       it stopped). The tool centre point is the position less these. */
    double length_start[APCI_AXIS_COUNT];
    double length_end[APCI_AXIS_COUNT];
} apci_segment;

/* Moves up to `max` of the oldest executed segments into `out`; *count says how many. */
APCI_API apci_status apci_read_segments(apci_board* board, apci_segment* out, size_t max,
                                        size_t* count) APCI_NOEXCEPT;

/* "contour", "transition", "approach", "departure", "uncompensated", "rapid"; NULL otherwise. */
APCI_API const char* apci_segment_role_name(int role) APCI_NOEXCEPT;

#ifdef __cplusplus
}
#endif

#endif /* APCI_APCI_H */
