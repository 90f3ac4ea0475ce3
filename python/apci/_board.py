# SPDX-License-Identifier: MIT
"""apci.open() and Board: typed object access whose type follows the object."""

from __future__ import annotations

import dataclasses
import math
import numbers

from . import _apci
from ._errors import Error, MotionClaimedError, ObjectError, TransportError, error_class
from ._status import GroupStatus, Status, TcError, decode_status

_INT32_MIN = -(2**31)
_INT32_MAX = 2**31 - 1

# The TC module (bus 1300): DeviceNumber 1 holds the compensation groups, Index = group (0 =
# the active one), SubIndex 1 ERROR and 3 STATUS ([APCI-TC] Table 3, apci.h).
_TC_BUS = _apci.TC_BUS
_TC_GROUPS = 1
_TC_ERROR = 1
_TC_STATUS = 3


def _int32(name: str, value) -> int:
    """An address part as an int32, or TypeError / ValueError naming it."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an int, not {type(value).__name__} ({value!r})")
    value = int(value)
    if not _INT32_MIN <= value <= _INT32_MAX:
        raise ValueError(f"{name} {value} is outside int32 ({_INT32_MIN} .. {_INT32_MAX})")
    return value


def _address_text(address) -> str:
    return "/".join(str(part) for part in address)


def _as_int32(label: str, value) -> int:
    """The value for an int32 object: an int, or a float that is one; TypeError / ValueError."""
    if not isinstance(value, numbers.Integral):
        value = float(value)
        if not (math.isfinite(value) and value.is_integer()):
            raise TypeError(f"write {label}: object holds an int32, and {value!r} is not "
                            f"integral; give an int")
    if not _INT32_MIN <= value <= _INT32_MAX:
        raise ValueError(f"write {label}: object holds an int32, and {value!r} is outside int32 "
                         f"({_INT32_MIN} .. {_INT32_MAX})")
    return int(value)


@dataclasses.dataclass(frozen=True)
class ObjectInfo:
    """One object of the board's object map (objif/map/objects.h) by its dotted name."""

    name: str        # "tc.group[1].radius"
    bus: int
    device: int
    index: int
    subindex: int
    type: str        # "int" (int32) or "double"
    access: str      # "r", "w" or "r/w"
    readable: bool
    writable: bool
    min: float       # the range a write must lie in (inclusive)
    max: float
    unit: str        # "mm", "deg", "us", "PU", ... or ""
    rule: str        # where its rule comes from ("[APCI-TC] Table 3", ...)
    title: str       # the name its document gives it ("RADIUS")

    @property
    def address(self) -> tuple[int, int, int, int]:
        return (self.bus, self.device, self.index, self.subindex)


class UnknownNameError(ObjectError, LookupError):
    """No object of the map has this name. ``suggestions`` lists the nearest names."""

    def __init__(self, name: str, suggestions: list[str]):
        hint = f"; did you mean {' or '.join(suggestions)}?" if suggestions else \
            "; apci.object_names() lists every name"
        super().__init__(f"no object is named {name!r}{hint}", Status.ObjectMissing)
        self.name = name
        self.suggestions = suggestions


def object_info(*args) -> ObjectInfo | None:
    """The object map's entry for a dotted name, or for bus, device, index, subindex.

    An unknown name raises UnknownNameError with suggestions; an address the map does not
    name answers None.
    """
    if len(args) == 1 and isinstance(args[0], str):
        found = _apci.find_object(args[0])
        if found is None:
            raise UnknownNameError(args[0], _apci.closest_names(args[0], 3))
        return ObjectInfo(**found)
    if len(args) == 4:
        return _object_at(tuple(_int32(n, v) for n, v in
                                zip(("bus", "device", "index", "subindex"), args)))
    raise TypeError(f"object_info() takes a name (str) or bus, device, index, subindex; got "
                    f"{args!r}")


def _object_at(address) -> ObjectInfo | None:
    found = _apci.find_object_at(*address)
    return ObjectInfo(**found) if found is not None else None


def object_names() -> list[str]:
    """Every dotted name of the object map, in map order (docs/object-map.md, "Names")."""
    return _apci.object_names()


@dataclasses.dataclass(frozen=True)
class MotionClaim:
    """Who holds the board's motion (Board.motion_claim(); docs/motion-claim.md).

    ``held``      a program holds it
    ``yours``     this Board holds it
    ``pid``       the holder's process id; 0 when the board does not know it
    ``since_ms``  when it claimed, milliseconds since 1970-01-01 UTC; 0 when not known
    ``name``      the holder's command name; "" when not known
    ``holder``    the holder as a refusal names it ("pid 4242 (apcictl) since 2024-05-01
                  12:00:00 UTC"); "" when nobody holds it
    """

    held: bool
    yours: bool
    pid: int
    since_ms: int
    name: str
    holder: str


class Board:
    """An open board (apci.open()). A context manager: ``with apci.open() as b: ...``.

    Not thread-safe: use a Board from one thread at a time (apci.h, "Threading").
    """

    def __init__(self, uri: str = "emu:"):
        if not isinstance(uri, str):
            raise TypeError(f"uri must be a str such as 'emu:' or 'unix:/path', not "
                            f"{type(uri).__name__}")
        if "\0" in uri:
            # The C library would read the URI only up to it: another socket or file.
            raise ValueError(f"uri {uri!r} holds a NUL byte (embedded null byte); a device URI "
                             f"cannot")
        self._native = _apci.Board(uri)
        if not self._native.is_open:
            # Whatever the cause (no such socket, malformed URI: InvalidArgument, transport
            # not built in: NotSupported), the device could not be reached.
            raise TransportError(self._native.last_error() or _apci.last_open_error(),
                                 self._native.open_status)

    # ---- life cycle

    @property
    def uri(self) -> str:
        return self._native.uri

    @property
    def closed(self) -> bool:
        return not self._native.is_open

    def close(self) -> None:
        """Closes the board; a second close does nothing."""
        self._native.close()

    def __enter__(self) -> "Board":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"<apci.Board {self.uri!r}{' closed' if self.closed else ''}>"

    def _board(self):
        if self.closed:
            raise ValueError(f"board {self.uri!r} is closed; open it again with apci.open()")
        return self._native

    # ---- objects

    def _target(self, args, verb: str):
        """(address, ObjectInfo or None) from a dotted name or bus, device, index, subindex."""
        if len(args) == 1 and isinstance(args[0], str):
            info = object_info(args[0])
            return info.address, info
        if len(args) == 4:
            address = tuple(_int32(n, v) for n, v in zip(("bus", "device", "index", "subindex"),
                                                         args))
            return address, _object_at(address)
        raise TypeError(f"{verb}() takes an object name (str) or bus, device, index, subindex "
                        f"(4 ints); got {len(args)} argument(s): {args!r}")

    def _raise(self, verb: str, address, info, status: int):
        """Raises the Error for a refused access, with the TC ERROR bits it set (if a group)."""
        message = self._native.last_error() or \
            f"{verb} {_address_text(address)}: {_apci.status_name(status)}"
        if info is not None:
            message = f"{info.name}: {message}"
        bits = 0
        bus, device, index, _ = address
        if bus == _TC_BUS and device == _TC_GROUPS and status != Status.TransportError:
            code, value = self._native.read_int(_TC_BUS, _TC_GROUPS, index, _TC_ERROR)
            if code == 0:
                bits = value
                if value:
                    message += f" (group ERROR now: {', '.join(decode_status(value).error_names)})"
        raise error_class(status)(message, status, bits)

    def read(self, *args):
        """read(name) or read(bus, device, index, subindex) -> int or float, as the object's
        type is (the object map's, objif/names.h; the board's for an address it does not name).

        Raises ObjectError (no such object or name, write-only, ...) or TransportError.
        """
        address, info = self._target(args, "read")
        board = self._board()
        if info is not None:
            read = board.read_double if info.type == "double" else board.read_int
            status, value = read(*address)
        else:
            status, value = board.read_int(*address)
            if status == Status.TypeMismatch:  # a double object: nothing was read or changed
                status, value = board.read_double(*address)
        if status != 0:
            self._raise("read", address, info, status)
        return value

    def write(self, *args) -> None:
        """write(name, value) or write(bus, device, index, subindex, value).

        The value's type follows the object: an int written to a double object is written as
        that float; a float written to an int object must be integral (2.0), else TypeError.
        bool and non-numbers are a TypeError. A refused write changes nothing on the board.
        """
        if len(args) < 2:
            raise TypeError("write() takes an object name or bus, device, index, subindex, and "
                            "a value")
        address, info = self._target(args[:-1], "write")
        value = args[-1]
        label = _address_text(address) if info is None else \
            f"{info.name} ({_address_text(address)})"
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError(f"write {label}: the value must be an int or a float, not "
                            f"{type(value).__name__} ({value!r})")
        board = self._board()
        if info is not None and info.type == "double":
            status = board.write_double(*address, float(value))
        elif info is not None:
            status = board.write_int(*address, _as_int32(label, value))
        else:
            status = self._write_probing(board, label, address, value)
        if status != 0:
            self._raise("write", address, info, status)

    @staticmethod
    def _write_probing(board, label: str, address, value) -> int:
        """Writes to an object the map does not name: the accessor the value suggests, and on
        the board's TypeMismatch (which changes nothing) the other one, as apcictl write."""
        if isinstance(value, numbers.Integral):
            value = int(value)
            if _INT32_MIN <= value <= _INT32_MAX:
                status = board.write_int(*address, value)
                if status != Status.TypeMismatch:
                    return status
            # A double object (or an int beyond int32, which only a double object can take).
            status = board.write_double(*address, float(value))
            if status == Status.TypeMismatch:
                _as_int32(label, value)  # raises: beyond int32
            return status
        value = float(value)
        status = board.write_double(*address, value)
        if status != Status.TypeMismatch:
            return status
        return board.write_int(*address, _as_int32(label, value))

    # ---- the board's motion (docs/motion-claim.md)

    def claim_motion(self) -> None:
        """Holds the board's motion for this Board until release_motion() or close(): another
        program's moves (another apcictl run, apci.run on another Board) are refused meanwhile;
        apci.run on this Board runs.

        Raises MotionClaimedError naming the holder where another program holds it, ObjectError
        with Status.WrongDeviceState where this Board holds it already, and with
        Status.NotSupported where the board does not serve claims; TransportError when the
        link fails.
        """
        self._motion_answer("claim the board's motion", self._board().claim_motion())

    def release_motion(self) -> None:
        """Ends this Board's claim. ObjectError (Status.WrongDeviceState) where it holds none."""
        self._motion_answer("release the board's motion", self._board().release_motion())

    def motion_claim(self) -> MotionClaim:
        """Who holds the board's motion, changing nothing (a MotionClaim). ObjectError
        (Status.NotSupported) where the board does not serve claims."""
        status, *claim = self._board().motion_claim()
        self._motion_answer("ask who holds the board's motion", status)
        return MotionClaim(*claim)

    def _motion_answer(self, what: str, status: int) -> None:
        if status == 0:
            return
        message = self._native.last_error() or f"{what}: {_apci.status_name(status)}"
        if status == Status.MotionClaimed:
            raise MotionClaimedError(message, status)
        raise error_class(status)(message, status)

    # ---- TC status

    def status(self, group: int = 1) -> GroupStatus:
        """ERROR and STATUS of TC group `group` (1..3; 0 = the active group), decoded."""
        group = _int32("group", group)
        error = self.read(_TC_BUS, _TC_GROUPS, group, _TC_ERROR)
        status = self.read(_TC_BUS, _TC_GROUPS, group, _TC_STATUS)
        return decode_status(error, status, group)


def open(uri: str = "emu:") -> Board:  # noqa: A001 - the package's verb, as apci_open
    """Opens a board by device URI (apci_open): "emu:" (the embedded emulator, a fresh board
    in this process), "unix:PATH" (the rwmos-emu daemon), "shm:PATH", "pci:...", "usb:".

    Raises TransportError with the status when it does not open (e.g. Status.TransportError
    for a socket nobody serves, Status.InvalidArgument for a malformed URI).
    """
    return Board(uri)


__all__ = ["Board", "MotionClaim", "ObjectInfo", "UnknownNameError", "object_info", "object_names",
           "Error", "ObjectError", "TransportError", "TcError"]
