# SPDX-License-Identifier: MIT
"""apci.open() and Board: typed object access whose type follows the object."""

from __future__ import annotations

import math
import numbers

from . import _apci
from ._errors import Error, ObjectError, TransportError, error_class
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


class Board:
    """An open board (apci.open()). A context manager: ``with apci.open() as b: ...``.

    Not thread-safe: use a Board from one thread at a time (apci.h, "Threading").
    """

    def __init__(self, uri: str = "emu:"):
        if not isinstance(uri, str):
            raise TypeError(f"uri must be a str such as 'emu:' or 'unix:/path', not "
                            f"{type(uri).__name__}")
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

    def _address(self, args, verb: str):
        """(bus, device, index, subindex) from the arguments of read/write."""
        if len(args) == 4:
            return tuple(_int32(n, v) for n, v in zip(("bus", "device", "index", "subindex"),
                                                      args))
        raise TypeError(f"{verb}() takes bus, device, index, subindex (4 ints); got "
                        f"{len(args)} argument(s): {args!r}")

    def _raise(self, verb: str, address, status: int, extra: str = ""):
        """Raises the Error for a refused access, with the TC ERROR bits it set (if a group)."""
        message = self._native.last_error() or \
            f"{verb} {_address_text(address)}: {_apci.status_name(status)}"
        bits = 0
        bus, device, index, _ = address
        if bus == _TC_BUS and device == _TC_GROUPS and status != Status.TransportError:
            code, value = self._native.read_int(_TC_BUS, _TC_GROUPS, index, _TC_ERROR)
            if code == 0:
                bits = value
                if value:
                    message += f" (group ERROR now: {', '.join(decode_status(value).error_names)})"
        raise error_class(status)(message + extra, status, bits)

    def read(self, *args):
        """read(bus, device, index, subindex) -> int or float, as the object's type is.

        Raises ObjectError (no such object, write-only, ...) or TransportError.
        """
        address = self._address(args, "read")
        board = self._board()
        status, value = board.read_int(*address)
        if status == Status.TypeMismatch:  # a double object: nothing was read or changed
            status, value = board.read_double(*address)
        if status != 0:
            self._raise("read", address, status)
        return value

    def write(self, *args) -> None:
        """write(bus, device, index, subindex, value).

        The value's type follows the object: an int written to a double object is written as
        that float; a float written to an int object must be integral (2.0), else TypeError.
        bool and non-numbers are a TypeError. A refused write changes nothing on the board.
        """
        if len(args) < 1:
            raise TypeError("write() takes bus, device, index, subindex and a value")
        address = self._address(args[:-1], "write")
        value = args[-1]
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError(f"write {_address_text(address)}: the value must be an int or a "
                            f"float, not {type(value).__name__} ({value!r})")
        board = self._board()
        if isinstance(value, numbers.Integral):
            value = int(value)
            if _INT32_MIN <= value <= _INT32_MAX:
                status = board.write_int(*address, value)
                if status != Status.TypeMismatch:
                    return self._check("write", address, status)
            # A double object (or an int beyond int32, which only a double object can take).
            status = board.write_double(*address, float(value))
            if status == Status.TypeMismatch:
                raise ValueError(f"write {_address_text(address)}: object holds an int32, and "
                                 f"{value} is outside int32 ({_INT32_MIN} .. {_INT32_MAX})")
            return self._check("write", address, status)
        value = float(value)
        status = board.write_double(*address, value)
        if status != Status.TypeMismatch:
            return self._check("write", address, status)
        # An int32 object: only an integral float is the same value as an int.
        if not (math.isfinite(value) and value.is_integer()):
            raise TypeError(f"write {_address_text(address)}: object holds an int32, and "
                            f"{value!r} is not integral; give an int")
        if not _INT32_MIN <= value <= _INT32_MAX:
            raise ValueError(f"write {_address_text(address)}: object holds an int32, and "
                             f"{value!r} is outside int32 ({_INT32_MIN} .. {_INT32_MAX})")
        return self._check("write", address, board.write_int(*address, int(value)))

    def _check(self, verb: str, address, status: int) -> None:
        if status != 0:
            self._raise(verb, address, status)

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


__all__ = ["Board", "open", "Error", "ObjectError", "TransportError", "TcError"]
