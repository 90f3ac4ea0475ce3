# SPDX-License-Identifier: MIT
"""The exceptions of the package: apci.Error and its kinds."""

from __future__ import annotations

from ._status import Status, TcError, status_name, status_of

# Codes that say the link to the board (or its opening) failed rather than the object access.
_TRANSPORT_CODES = frozenset(
    int(getattr(Status, name))
    for name in ("TransportError", "Timeout", "BadFrame", "UnknownOpcode")
    if name in Status.__members__)


class Error(Exception):
    """A call libapci refused, or a run that stopped on an error.

    ``status``      the apci status code (an ``apci.Status``; ``.name`` is its name, e.g.
                    "TypeMismatch"); ``Status.Ok`` for errors that carry no board status
    ``status_name`` the same name as a string
    ``error_bits``  the TC ERROR bits the failure set or found (``apci.TcError``; 0 where no
                    TC group is involved)
    ``message``     libapci's words for what was wrong (apci_last_error)
    """

    def __init__(self, message: str, status: int = 0, error_bits: int = 0):
        super().__init__(message)
        self.message = message
        self.status = status_of(status)
        self.status_name = status_name(status)
        self.error_bits = TcError(int(error_bits) & 0xFFFFFFFF)


class TransportError(Error):
    """The board cannot be reached: the device does not open, the link failed or timed out."""


class ObjectError(Error):
    """The board refused an object access: no such object, wrong type, out of range, state."""


class MotionClaimedError(Error):
    """Another program holds the board's motion (apci_claim_motion); nothing ran. ``message``
    names the holder: "... the board's motion is held by pid 4242 (apcictl) since ..."."""


class ProgramError(Error):
    """An NC program (or its tool list, correction table, PLC script) cannot be used: nothing
    ran. ``file``, ``line``, ``column`` (1-based; 0 when the whole file is meant) and ``block``
    (N number, -1 when none) say where; ``kind`` what ("Syntax", "Geometry", "Io", ...)."""

    def __init__(self, diagnostic: dict):
        super().__init__(diagnostic["text"])
        self.kind = diagnostic["kind"]
        self.file = diagnostic["file"]
        self.line = diagnostic["line"]
        self.column = diagnostic["column"]
        self.block = diagnostic["block"]
        self.reason = diagnostic["message"]


class RunError(Error):
    """The board stopped an NC run with an error (KorrError, a refused profile, ...).

    ``errors`` lists every error of the run (``RunIssue``), ``line`` and ``block`` say where
    the first one happened, ``error_bits`` holds its TC ERROR bit (when the code is one) and
    ``result`` is the ``RunResult`` up to the stop (the path executed so far).
    """

    def __init__(self, message: str, result, error_bits: int = 0):
        super().__init__(message, 0, error_bits)
        self.result = result
        self.errors = result.errors
        first = result.errors[0]
        self.line = first.line
        self.block = first.block
        self.code = first.code


def error_class(status: int) -> type[Error]:
    """TransportError for link failures, ObjectError otherwise."""
    return TransportError if int(status) in _TRANSPORT_CODES else ObjectError
