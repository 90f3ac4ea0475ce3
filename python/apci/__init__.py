# SPDX-License-Identifier: MIT
"""apci: ADDI-DATA APCI-8001/8008 boards, their emulator and NC runs from Python.

    import apci
    with apci.open("emu:") as board:          # the embedded emulator; "unix:PATH": a daemon
        board.write(1300, 1, 1, 8, 5)         # group 1 WKZINDEX (int object)
        board.write(1300, 1, 1, 7, 2.5)       # group 1 RADIUS (double object)
        board.read(1300, 1, 1, 7)             # 2.5
        board.read("tc.group[1].radius")      # the same object by its name: 2.5
        board.status(1)                       # ERROR and STATUS decoded: .KorrError, .Run, ...
    result = apci.run("examples/wr_quad_disc.nc", tools="examples/tools/wr_quad_disc.tools")
    result.segments["end"]                    # (N, 3) end points of the executed segments
    result.axes                               # (M, 8) axis positions of every cycle

docs/python.md documents the package; it is a layer over libapci (apci.h) and the executor of
`apcictl run`.
"""

from ._apci import version as _library_version
from ._board import (Board, MotionClaim, ObjectInfo, UnknownNameError, object_info, object_names,
                     open)
from ._errors import (Error, MotionClaimedError, ObjectError, ProgramError, RunError,
                      TransportError)
from ._run import SEGMENT_DTYPE, SEGMENT_KINDS, SEGMENT_ROLES, RunIssue, RunResult, run
from ._status import (GroupStatus, Status, TcError, TcStatus, decode_status, status_message,
                      status_name)

__version__ = _library_version()

# `from apci import *` brings everything but open(), which would shadow the built-in open() of
# the importing module: call it apci.open().
__all__ = [
    "Board", "MotionClaim", "run", "ObjectInfo", "UnknownNameError", "object_info", "object_names",
    "Error", "ObjectError", "TransportError", "ProgramError", "RunError", "MotionClaimedError",
    "Status", "TcError", "TcStatus", "GroupStatus", "decode_status", "status_name",
    "status_message",
    "RunResult", "RunIssue", "SEGMENT_DTYPE", "SEGMENT_KINDS", "SEGMENT_ROLES",
]
