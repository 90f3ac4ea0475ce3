# SPDX-License-Identifier: MIT
"""Status codes and the TC registers ERROR and STATUS, named as libapci names them.

Every name here comes from libapci itself (apci_status_name, apci_tc_error_bit_name,
apci_tc_status_bit_name), so the package and the C API never disagree.
"""

from __future__ import annotations

import dataclasses
import enum

from . import _apci

# The status codes of apci.h by libapci's names: Status.TypeMismatch == 0x06070010.
Status = enum.IntEnum("Status", _apci.status_codes(), module=__name__)
Status.__doc__ = "A status code of libapci (apci.h), named as apci_status_name() names it."

# The ERROR bits of a TC group ([APCI-TC] Table 4): InitError, KorrError, CalcError,
# PlaneError, CenterError.
TcError = enum.IntFlag("TcError", _apci.tc_error_bits(), module=__name__)
TcError.__doc__ = "The ERROR register of a TC group: the bits of [APCI-TC] Table 4."

# The STATUS bits of a TC group ([APCI-TC] Table 5): Run, ProfMarked.
TcStatus = enum.IntFlag("TcStatus", _apci.tc_status_bits(), module=__name__)
TcStatus.__doc__ = "The STATUS register of a TC group: the bits of [APCI-TC] Table 5."


def status_of(code: int) -> Status | int:
    """The Status member for `code`, or the plain int for a code apci.h does not list."""
    try:
        return Status(code)
    except ValueError:
        return int(code)


def status_name(code: int) -> str:
    """"TypeMismatch" for 0x06070010; "Unknown" for a code apci.h does not list."""
    return _apci.status_name(int(code) & 0xFFFFFFFF)


def status_message(code: int) -> str:
    """One line of English for a user (apci_status_message)."""
    return _apci.status_message(int(code) & 0xFFFFFFFF)


def _flag_names(value: enum.IntFlag) -> list[str]:
    """The names of the set bits, lowest first; bits [APCI-TC] does not name as "bitN"."""
    names = []
    raw = int(value)
    for bit in range(32):
        mask = 1 << bit
        if not raw & mask:
            continue
        try:
            names.append(type(value)(mask).name or f"bit{bit}")
        except ValueError:
            names.append(f"bit{bit}")
    return names


@dataclasses.dataclass(frozen=True)
class GroupStatus:
    """ERROR and STATUS of one TC compensation group, decoded.

    `error` and `status` are the registers as flags; the [APCI-TC] names read as booleans:
    ``s.KorrError``, ``s.Run``, ``s.ProfMarked``; ``s.ok`` is True when no ERROR bit is set.
    """

    group: int
    error: TcError
    status: TcStatus

    @property
    def ok(self) -> bool:
        return int(self.error) == 0

    @property
    def error_names(self) -> list[str]:
        return _flag_names(self.error)

    @property
    def status_names(self) -> list[str]:
        return _flag_names(self.status)

    def __getattr__(self, name: str) -> bool:
        # Only called for names that are not fields: the bit names of Tables 4 and 5.
        if name in TcError.__members__:
            return bool(self.error & TcError[name])
        if name in TcStatus.__members__:
            return bool(self.status & TcStatus[name])
        raise AttributeError(
            f"GroupStatus has no attribute {name!r}; the flags are "
            f"{', '.join([*TcError.__members__, *TcStatus.__members__])}")

    def __str__(self) -> str:
        errors = ", ".join(self.error_names) or "none"
        status = ", ".join(self.status_names) or "none"
        return f"group {self.group}: ERROR {int(self.error)} ({errors}), " \
               f"STATUS {int(self.status)} ({status})"


def decode_status(error: int, status: int = 0, group: int = 0) -> GroupStatus:
    """Decodes the raw ERROR and STATUS registers of a TC group into named flags."""
    return GroupStatus(group=group, error=TcError(int(error) & 0xFFFFFFFF),
                       status=TcStatus(int(status) & 0xFFFFFFFF))
