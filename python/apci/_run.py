# SPDX-License-Identifier: MIT
"""apci.run(): an NC program on a board as `apcictl run` runs it, the result as NumPy arrays."""

from __future__ import annotations

import dataclasses
import os
import warnings

import numpy as np

from . import _apci
from ._board import Board
from ._errors import MotionClaimedError, ProgramError, RunError, error_class
from ._status import GroupStatus, TcError, decode_status

# The segment kinds and roles by their numbers in RunResult.segments["kind"] / ["role"]: the
# names `apcictl run --json` writes ("rapid", "line", "arc"; "contour", "transition", ...).
SEGMENT_KINDS = tuple(_apci.run_kind_names())
SEGMENT_ROLES = tuple(_apci.run_role_names())

# One executed segment of the tool centre path, in program coordinates X, Y, Z (mm).
SEGMENT_DTYPE = np.dtype([
    ("block", "<i8"),         # N number of the block it came from; -1: the block has none
    ("line", "<u8"),          # source line of a block without N (0: not known)
    ("kind", "u1"),           # index into SEGMENT_KINDS
    ("role", "u1"),           # index into SEGMENT_ROLES
    ("start", "<f8", (3,)),   # X, Y, Z
    ("end", "<f8", (3,)),
    ("center", "<f8", (3,)),  # arcs: the centre (third axis: the start's); else 0
    ("ccw", "?"),             # arcs: counter-clockwise seen from the plane's third axis
    ("plane", "<i4"),         # arcs: 17 X-Y, 18 Z-X, 19 Y-Z
    ("start_cycle", "<u8"),   # the interpolation cycles it ran in: (start_cycle, end_cycle]
    ("end_cycle", "<u8"),
])

_SELF_APPROACH = ("warn", "error", "off")

# The most interpolation cycles a run samples by default: 2 million cycles (33 minutes at 1 ms)
# of 8 axes hold 160 MB. A move may take up to 10^9 cycles (docs/nc-programs.md, "Limits").
DEFAULT_MAX_SAMPLES = 2_000_000


@dataclasses.dataclass(frozen=True)
class RunIssue:
    """An error, warning or notice of a run: where (N number, source line) and what."""

    block: int     # N number, -1 when the block has none
    line: int      # source line, 0 when not known
    code: str      # "KorrError", "InvalidValue", "SelfApproach", ...
    message: str
    where: str     # "line 4 (N60)", "N60", "line 4" or "-"

    def __str__(self) -> str:
        return f"{self.where}: {self.code}: {self.message}"


@dataclasses.dataclass
class RunResult:
    """What apci.run() returns: the executed path, the sampled axes and the summary.

    segments      structured array (SEGMENT_DTYPE), one row per executed segment, in order;
                  e.g. ``segments["end"]`` is (N, 3)
    programmed    the program's moves as the executor sent them (absolute, before
                  compensation; every move of the program, also after an error), same dtype
    axes          (M, 8) float64: every axis of the board after each interpolation cycle
                  (empty with samples=False); ``xyz`` the X, Y, Z columns of it
    cycle, time   (M,): the clock value after each sampled cycle, and its time in s
    samples_dropped  cycles beyond max_samples that were run but not kept (0: every cycle)
    """

    file: str
    blocks: int
    blocks_executed: int
    path_length: float
    rapid_length: float
    cycles: int
    cycle_seconds: float
    segments: np.ndarray
    programmed: np.ndarray
    axes: np.ndarray
    cycle: np.ndarray
    time: np.ndarray
    axis_names: list[str]
    axis_numbers: list[int]
    plot_plane: int
    tc_present: bool
    errors: list[RunIssue]
    warnings: list[RunIssue]
    notices: list[RunIssue]
    registers: dict[int, GroupStatus]
    variables: dict[str, float]
    samples_dropped: int = 0
    summary_text: str = dataclasses.field(repr=False, default="")

    @property
    def ok(self) -> bool:
        """True when the program ran to its end without an error."""
        return not self.errors

    @property
    def duration(self) -> float:
        """The time the run took on the board, in seconds."""
        return self.cycles * self.cycle_seconds

    @property
    def xyz(self) -> np.ndarray:
        """(M, 3): the sampled positions of the board axes that are X, Y and Z."""
        return self.axes[:, self.axis_numbers]

    def kind_names(self) -> list[str]:
        return [SEGMENT_KINDS[k] for k in self.segments["kind"]]

    def role_names(self) -> list[str]:
        return [SEGMENT_ROLES[r] for r in self.segments["role"]]

    def summary(self) -> str:
        """The summary `apcictl run` prints: blocks, path, time, errors, warnings, notices."""
        return self.summary_text


def _checked_path(path, what: str):
    """A path as the C library takes it: one holding a NUL byte would end there (a different
    file), so it is refused, as os.open refuses it."""
    if ("\0" if isinstance(path, str) else b"\0") in path:
        raise ValueError(f"{what} path {path!r} holds a NUL byte (embedded null byte); a path "
                         f"cannot")
    return path


def _source(value, what: str):
    """(text_or_path, is_text) for a program or tool list given as text, str path or PathLike.

    A str holding a line break is the text itself; any other str, and any os.PathLike, names
    a file.
    """
    if isinstance(value, os.PathLike):
        return _checked_path(os.fspath(value), what), False
    if isinstance(value, str):
        if "\n" in value or "\r" in value:
            return value, True
        return _checked_path(value, what), False
    raise TypeError(f"{what} must be a str (text with line breaks, or a path) or a path-like "
                    f"object, not {type(value).__name__}")


def _path(value, what: str):
    if value is None:
        return None
    if isinstance(value, (str, os.PathLike)):
        return _checked_path(os.fspath(value), what)
    raise TypeError(f"{what} must be a path, not {type(value).__name__}")


def _issues(items) -> list[RunIssue]:
    return [RunIssue(i["block"], i["line"], i["code"], i["message"], i["where"]) for i in items]


def _segments(columns: dict) -> np.ndarray:
    out = np.zeros(len(columns["block"]), dtype=SEGMENT_DTYPE)
    for name in SEGMENT_DTYPE.names:
        out[name] = columns[name]
    return out


def _result(raw: dict) -> RunResult:
    samples = raw["samples"]
    return RunResult(
        file=raw["file"], blocks=raw["blocks"], blocks_executed=raw["blocks_executed"],
        path_length=raw["path_length"], rapid_length=raw["rapid_length"], cycles=raw["cycles"],
        cycle_seconds=raw["cycle_seconds"], segments=_segments(raw["segments"]),
        programmed=_segments(raw["programmed"]),
        axes=samples["axes"], cycle=samples["cycle"], time=samples["time"],
        axis_names=list(raw["axis_names"]), axis_numbers=list(raw["axis_numbers"]),
        plot_plane=raw["plot_plane"], tc_present=raw["tc_present"],
        errors=_issues(raw["errors"]), warnings=_issues(raw["warnings"]),
        notices=_issues(raw["notices"]),
        registers={r["group"]: decode_status(r["error"], r["status"], r["group"])
                   for r in raw["registers"] if r["readable"]},
        variables=dict(raw["variables"]), samples_dropped=raw["samples_dropped"],
        summary_text=raw["summary"])


def run(program, tools=None, device="emu:", *, name: str | None = None, corr=None, plc=None,
        self_approach: str = "warn", samples: bool = True,
        max_samples: int = DEFAULT_MAX_SAMPLES, check: bool = True) -> RunResult:
    """Runs an NC program on a board as ``apcictl run`` does and returns a RunResult.

    program        the program's text (a str with line breaks) or its path (str or PathLike)
    tools          the tool list (wz[i].field value): text or path; None: no tools (D n with
                   n > 0 is then refused)
    device         a device URI ("emu:", a fresh embedded board; "unix:PATH", ...), opened and
                   closed by the call, or an open apci.Board (left open; its state counts)
    name           the program's name in messages when it is given as text ("<text>")
    corr, plc      paths of a correction table (--corr) and a scripted PLC (--plc)
    self_approach  "warn" (default), "error" or "off", as --self-approach
    samples        record the axes of every interpolation cycle (RunResult.axes); False saves
                   8 floats per cycle on long runs
    max_samples    keep at most this many cycles (the first ones; default 2 million, 160 MB);
                   beyond it the run goes on, the rest is counted in samples_dropped and a
                   RuntimeWarning says so
    check          raise RunError when the board stopped the run with an error (the partial
                   result is its .result); False: return the result with .errors

    Raises ProgramError when the program (or a file it needs) cannot be used, and
    MotionClaimedError when another program holds the board's motion (the run claims it for
    itself while it runs, as apcictl run does; docs/motion-claim.md); nothing ran then. Raises
    TransportError when the device does not open or its link is lost before the run (the
    message ends with what to do: "apci.open() opens the board again"); a link lost during the
    run is the run's error (RunError, or .errors with check=False), in the same words.
    """
    text, is_text = _source(program, "program")
    tools_text, tools_is_text = (None, False) if tools is None else _source(tools, "tools")
    if self_approach not in _SELF_APPROACH:
        raise ValueError(f"self_approach must be one of {', '.join(_SELF_APPROACH)}, not "
                         f"{self_approach!r}")
    label = name if name is not None else "<text>"
    if isinstance(max_samples, bool) or not isinstance(max_samples, int) or max_samples < 0:
        raise ValueError(f"max_samples must be an int >= 0, not {max_samples!r}")
    if isinstance(device, Board):
        raw = _apci.run_program(device._board(), text, is_text, label, tools_text, tools_is_text,
                                _path(corr, "corr"), _path(plc, "plc"), self_approach,
                                bool(samples), max_samples)
    elif isinstance(device, str):
        with Board(device) as board:
            raw = _apci.run_program(board._board(), text, is_text, label, tools_text,
                                    tools_is_text, _path(corr, "corr"), _path(plc, "plc"),
                                    self_approach, bool(samples), max_samples)
    else:
        raise TypeError(f"device must be a URI (str) or an apci.Board, not "
                        f"{type(device).__name__}")
    if "claimed" in raw:
        raise MotionClaimedError(raw["claimed"], raw["status"])
    if "board_error" in raw:
        raise error_class(raw["status"])(raw["board_error"], raw["status"])
    if "diagnostic" in raw:
        raise ProgramError(raw["diagnostic"])
    result = _result(raw)
    if result.samples_dropped:
        warnings.warn(f"run {result.file}: kept the first {len(result.axes)} cycles of "
                      f"{len(result.axes) + result.samples_dropped} (max_samples="
                      f"{max_samples}); pass a larger max_samples, or samples=False",
                      RuntimeWarning, stacklevel=2)
    if check and result.errors:
        first = result.errors[0]
        bits = int(TcError[first.code]) if first.code in TcError.__members__ else 0
        raise RunError(f"run {result.file}: stopped at {first.where}: {first.code}: "
                       f"{first.message}", result, bits)
    return result
