# SPDX-License-Identifier: MIT
"""apci.run(): the same path as `apcictl run --json`/`--csv`, errors with their line."""

import contextlib
import json
import os
import pathlib
import subprocess
import tempfile
import threading
import time

import numpy as np
import pytest

import apci

KORR_PROGRAM = ("N10 F1000 D1\nN40 G41 G1 X0 Y0\nN50 X60\nN60 Y2\nN70 X0\n"
                "N100 G40 G1 X0 Y-20\nN110 M30\n")
TOOL_R5 = "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\nwz[1].laenge 0\n"


def apcictl_run(apcictl, tmp_path, program, tools):
    """`apcictl run PROGRAM --tools TOOLS --json --csv`: (json, csv array, summary, rc)."""
    out_json, out_csv = tmp_path / "run.json", tmp_path / "run.csv"
    done = subprocess.run([str(apcictl), "run", str(program), "--tools", str(tools),
                           "--json", str(out_json), "--csv", str(out_csv)],
                          capture_output=True, text=True, timeout=300, check=False)
    doc = json.loads(out_json.read_text())
    csv = np.loadtxt(out_csv, delimiter=",", skiprows=1, ndmin=2)
    return doc, csv, done.stdout, done.returncode


def test_run_matches_apcictl_json_and_csv(source_dir, apcictl, tmp_path):
    program = source_dir / "examples" / "wr_quad_disc.nc"
    tools = source_dir / "examples" / "tools" / "wr_quad_disc.tools"
    doc, csv, summary, rc = apcictl_run(apcictl, tmp_path, program, tools)
    assert rc == 0, summary

    result = apci.run(program, tools=tools)
    assert result.ok and result.errors == [] and doc["errors"] == []

    # Segments: the same blocks, kinds, roles and points as the JSON, number for number (the
    # JSON writes the shortest text that reads back exactly).
    want = doc["segments"]
    got = result.segments
    assert got.dtype == apci.SEGMENT_DTYPE
    assert len(got) == len(want) > 0
    assert list(got["block"]) == [s["block"] for s in want]
    assert result.kind_names() == [s["kind"] for s in want]
    assert result.role_names() == [s["role"] for s in want]
    np.testing.assert_array_equal(got["start"], np.array([s["start"] for s in want]))
    np.testing.assert_array_equal(got["end"], np.array([s["end"] for s in want]))
    arcs = [i for i, s in enumerate(want) if s["kind"] == "arc"]
    assert arcs, "the example has arcs (its corner transitions)"
    np.testing.assert_array_equal(got["center"][arcs], np.array([want[i]["center"] for i in arcs]))
    assert list(got["ccw"][arcs]) == [want[i]["ccw"] for i in arcs]
    assert list(got["plane"][arcs]) == [want[i]["plane"] for i in arcs]
    # Segments follow one another, and their cycles too.
    np.testing.assert_array_equal(got["start"][1:], got["end"][:-1])
    assert np.all(got["end_cycle"] > got["start_cycle"])
    assert got["end_cycle"][-1] == result.cycles

    # Sampled axes: the CSV's rows (cycle, time, 8 axes), every cycle of the run; the CSV
    # writes the shortest text that reads back exactly, so the numbers are equal.
    assert result.axes.shape == (result.cycles, 8) == (csv.shape[0], csv.shape[1] - 2)
    np.testing.assert_array_equal(result.cycle, csv[:, 0].astype(np.uint64))
    np.testing.assert_array_equal(result.time, csv[:, 1])
    np.testing.assert_array_equal(result.axes, csv[:, 2:])
    # The axes are where the board's axes stand: the last segment's end in the plane, and in Z
    # shifted by the tool length (D1: 50 mm), which the segments' tool centre point is not.
    np.testing.assert_allclose(result.xyz[-1], got["end"][-1] + [0, 0, 50], rtol=0, atol=1e-9)
    assert result.axis_names[:3] == ["X", "Y", "Z"]

    # The summary: apcictl's text, and the counts in it.
    assert result.summary() == summary
    assert summary.startswith(f"{program}: 11 blocks, 11 sent to the board, {len(want)} segments executed\n")
    assert result.blocks == 11 and result.blocks_executed == 11
    assert f"path {result.path_length:.3f} mm" in summary
    assert f"({result.cycles} cycles of 1 ms)" in summary
    assert sorted(result.registers) == [1, 2, 3]
    for group, status in result.registers.items():
        assert int(status.error) == doc["registers"][str(group)]["ERROR"]
        assert int(status.status) == doc["registers"][str(group)]["STATUS"]


# One program, run three ways: `apcictl run --json`, `apcictl diff --json` (the --device board's
# run) and apci.run(). All three build the run in one place (apci::run::ProgramRun), so their
# segments agree bit for bit: the two JSON files byte for byte, Python's arrays number for
# number with the JSON (which writes the shortest text that reads back exactly).
THREE_WAY_RUNS = [
    ("wr_quad_disc.nc", "tools/wr_quad_disc.tools", None, None),
    ("otc/wr_quad_disc.nc", "tools/wr_quad_disc.tools", None, "otc/plc/wr_quad_disc.plc"),
    ("3d_correction_table.h", "tools/3d_tools.tools", "tools/3d_corrections.corr", None),
    ("linuxcnc/qpocket_qpex.nc", "linuxcnc/qpocket.tools", None, None),
]


@pytest.mark.parametrize("program,tools,corr,plc", THREE_WAY_RUNS,
                         ids=[r[0] for r in THREE_WAY_RUNS])
def test_run_diff_and_python_give_the_same_segments_bit_for_bit(source_dir, apcictl, tmp_path,
                                                                 program, tools, corr, plc):
    examples = source_dir / "examples"
    inputs = ["--tools", str(examples / tools)]
    if corr:
        inputs += ["--corr", str(examples / corr)]
    if plc:
        inputs += ["--plc", str(examples / plc)]
    run_json, diff_json = tmp_path / "run.json", tmp_path / "diff.json"
    for command, out in (["run"], run_json), (["diff", "--against", "emu:"], diff_json):
        done = subprocess.run([str(apcictl), *command, str(examples / program), *inputs,
                               "--json", str(out)],
                              capture_output=True, text=True, timeout=300, check=False)
        assert done.returncode == 0, done.stdout + done.stderr
    assert run_json.read_bytes() == diff_json.read_bytes()

    result = apci.run(examples / program, tools=examples / tools,
                      corr=examples / corr if corr else None,
                      plc=examples / plc if plc else None, samples=False)
    want = json.loads(run_json.read_text())["segments"]
    got = result.segments
    assert len(got) == len(want) > 0
    assert list(got["block"]) == [s["block"] for s in want]
    assert result.kind_names() == [s["kind"] for s in want]
    assert result.role_names() == [s["role"] for s in want]
    for field in ("start", "end"):
        assert [tuple(float(v).hex() for v in p) for p in got[field]] == \
            [tuple(float(v).hex() for v in s[field]) for s in want]
    arcs = [i for i, s in enumerate(want) if s["kind"] == "arc"]
    assert [tuple(float(v).hex() for v in got["center"][i]) for i in arcs] == \
        [tuple(float(v).hex() for v in want[i]["center"]) for i in arcs]


def test_a_program_as_text_with_tools_as_text():
    result = apci.run("N10 G1 X3 Y4 F600\nM30\n", name="line.nc")
    assert result.file == "line.nc"
    assert len(result.segments) == 1
    s = result.segments[0]
    assert (s["block"], apci.SEGMENT_KINDS[s["kind"]], apci.SEGMENT_ROLES[s["role"]]) == \
        (10, "line", "uncompensated")
    np.testing.assert_array_equal(s["end"], [3.0, 4.0, 0.0])
    # The programmed move is the same line (no compensation here).
    assert len(result.programmed) == 1
    p = result.programmed[0]
    assert p["block"] == 10 and apci.SEGMENT_KINDS[p["kind"]] == "line"
    np.testing.assert_array_equal(p["end"], [3.0, 4.0, 0.0])
    assert result.path_length == pytest.approx(5.0)
    assert result.cycles == 500  # 5 mm at 600 mm/min
    assert result.axes.shape == (500, 8)

    compensated = apci.run("N10 F1000 D1\nN20 G41 G1 X10\nN30 X20\nN40 G40 X30\nM30\n",
                           tools=TOOL_R5, samples=False)
    assert compensated.axes.shape == (0, 8)
    assert "contour" in compensated.role_names()
    # The programmed contour lies on Y = 0; the compensated path (G41: left of it) at Y = 5.
    contour = compensated.segments[compensated.segments["block"] == 30]
    assert len(contour) == 1
    np.testing.assert_allclose(contour["end"][0], [20.0, 5.0, 0.0], atol=1e-9)
    programmed = compensated.programmed[compensated.programmed["block"] == 30]
    np.testing.assert_array_equal(programmed["end"][0], [20.0, 0.0, 0.0])


def test_a_program_that_does_not_parse_raises_with_its_line_and_runs_nothing(tmp_path):
    with pytest.raises(apci.ProgramError) as caught:
        apci.run("N10 G1 X1 F100\nN20 G1 X\nM30\n", name="bad.nc")
    e = caught.value
    assert isinstance(e, apci.Error)
    assert (e.file, e.line, e.block, e.kind) == ("bad.nc", 2, 20, "Syntax")
    assert e.column > 0
    assert str(e).startswith("bad.nc:2:")

    path = tmp_path / "bad.nc"
    path.write_text("N10 G1 X1 F100\nN20 G1 X\nM30\n")
    with pytest.raises(apci.ProgramError) as caught:
        apci.run(path)
    assert caught.value.line == 2 and caught.value.file == str(path)

    with pytest.raises(apci.ProgramError) as caught:
        apci.run(tmp_path / "missing.nc")
    assert caught.value.kind == "Io" and caught.value.line == 0

    with pytest.raises(apci.ProgramError, match="no tools given"):
        apci.run("N10 D1\nM30\n")
    with pytest.raises(apci.ProgramError) as caught:
        apci.run("N10 D1\nM30\n", tools="wz[1].radius 5\nwz[1].typ 9\n")
    assert caught.value.file == "<tools>" and caught.value.line == 2


def test_a_board_error_raises_with_the_line_and_the_partial_result():
    with pytest.raises(apci.RunError) as caught:
        apci.run(KORR_PROGRAM, tools=TOOL_R5, name="korr.nc")
    e = caught.value
    assert (e.line, e.block, e.code) == (4, 60, "KorrError")
    assert e.error_bits == apci.TcError.KorrError
    assert "stopped at line 4 (N60): KorrError: element is too short for the corner" in str(e)
    # The board holds: nothing spooled after the error ran.
    assert np.all(e.result.segments["block"] < 70)
    assert "errors: 1 (KorrError 1)\n  line 4 (N60): KorrError: " in e.result.summary()
    # The programmed contour goes on to its end (for a plot of where the run stopped).
    assert list(e.result.programmed["block"]) == [40, 50, 60, 70, 100]
    assert e.result.registers[1].KorrError

    result = apci.run(KORR_PROGRAM, tools=TOOL_R5, check=False)
    assert not result.ok
    assert [(i.line, i.block, i.code) for i in result.errors] == [(4, 60, "KorrError")]


def test_a_run_on_an_open_board_keeps_its_state(board):
    result = apci.run("N10 G1 X3 Y4 F600\nM30\n", device=board)
    assert result.ok
    assert not board.closed
    assert board.read(1000, 0, 10, 0) == 3.0  # axis 0 position: where the program left it
    again = apci.run("N10 G1 X5 F600\nM30\n", device=board)
    np.testing.assert_array_equal(again.segments["start"][0], [3.0, 4.0, 0.0])


def test_bad_arguments_are_named():
    with pytest.raises(ValueError, match="self_approach"):
        apci.run("M30\n", self_approach="maybe")
    with pytest.raises(TypeError, match="device must be"):
        apci.run("M30\n", device=3)
    with pytest.raises(TypeError, match="program must be"):
        apci.run(b"M30\n")
    with pytest.raises(apci.TransportError):
        apci.run("M30\n", device="unix:/nonexistent/apci-test.sock")


def test_a_path_with_a_nul_byte_is_refused_not_cut_short(source_dir, tmp_path):
    # The C library reads a path up to its first NUL byte: "p.nc\0.bak" would run p.nc.
    program = source_dir / "examples" / "wr_quad_disc.nc"
    for bad in (str(program) + "\0.bak", pathlib.Path(str(program) + "\0.bak")):
        with pytest.raises(ValueError, match="NUL byte"):
            apci.run(bad, samples=False)
    tools = source_dir / "examples" / "tools" / "wr_quad_disc.tools"
    for argument in ("tools", "corr", "plc"):
        with pytest.raises(ValueError, match=f"{argument} path .* holds a NUL byte"):
            apci.run(program, **{argument: str(tools) + "\0x"}, samples=False)
    with pytest.raises(ValueError, match="NUL byte"):
        apci.run("M30\n", device="unix:" + str(tmp_path / "a.sock") + "\0b")
    with pytest.raises(ValueError, match="NUL byte"):
        apci.open("emu:\0")
    # A program's text may hold one (it is text, not a path): the program's own error.
    with pytest.raises(apci.ProgramError):
        apci.run("G1 X1\0 F100\nM30\n")


def test_a_closed_board_is_refused(board):
    board.close()
    with pytest.raises(ValueError, match="closed"):
        apci.run("M30\n", device=board)


def test_the_path_type_does_not_matter(source_dir):
    program = source_dir / "examples" / "wr_quad_disc.nc"
    tools = source_dir / "examples" / "tools" / "wr_quad_disc.tools"
    a = apci.run(str(program), tools=str(tools), samples=False)
    b = apci.run(pathlib.Path(program), tools=tools, samples=False)
    np.testing.assert_array_equal(a.segments, b.segments)


def test_a_board_running_a_program_refuses_other_threads(board):
    # 30 s of moves at one sample a cycle: long enough to be caught running.
    done = threading.Event()
    outcome = {}

    def run():
        try:
            outcome["result"] = apci.run("N10 G1 X300 F600\nM30\n", device=board)
        finally:
            done.set()

    worker = threading.Thread(target=run)
    worker.start()
    refused = None
    while not done.is_set() and refused is None:
        try:
            board.read(1300, 1, 1, 7)
        except RuntimeError as e:
            refused = e
    worker.join()
    assert refused is not None, "the run ended before another thread was seen refused"
    assert "in use by another thread" in str(refused)
    # The run itself was not disturbed, and the board serves again after it.
    assert outcome["result"].ok and outcome["result"].cycles == 30000
    assert board.read(1000, 0, 10, 0) == 300.0


def test_samples_beyond_max_samples_are_counted_not_kept():
    with pytest.warns(RuntimeWarning, match=r"kept the first 100 cycles of 500 \(max_samples=100\)"):
        result = apci.run("N10 G1 X3 Y4 F600\nM30\n", max_samples=100)
    assert result.ok and result.cycles == 500
    assert result.axes.shape == (100, 8) and result.samples_dropped == 400
    assert list(result.cycle[[0, -1]]) == [1, 100]
    np.testing.assert_array_equal(result.segments["end"][0], [3.0, 4.0, 0.0])
    with pytest.raises(ValueError, match="max_samples must be an int >= 0"):
        apci.run("M30\n", max_samples=-1)


@contextlib.contextmanager
def _daemon_process(apcictl):
    """The daemon of the build tree on a socket of its own (a short directory: a socket path
    holds at most 107 bytes, a build tree's may not): its path and process, until the block
    ends (stopped then, if the block has not stopped it)."""
    with tempfile.TemporaryDirectory(prefix="apci-") as short:
        sock = pathlib.Path(short) / "d.sock"
        daemon = subprocess.Popen([str(apcictl.parent / "rwmos-emu"), "--socket", str(sock),
                                   "--log-level", "error"])
        try:
            deadline = time.monotonic() + 10
            while not sock.exists() and time.monotonic() < deadline:
                time.sleep(0.01)
            yield sock, daemon
        finally:
            if daemon.poll() is None:
                daemon.terminate()
            daemon.wait(timeout=10)


@contextlib.contextmanager
def _daemon(apcictl):
    """_daemon_process's socket path."""
    with _daemon_process(apcictl) as (sock, _):
        yield sock


SPIKE = ("N10 G17 G90 G26 D1 F600\nN20 G0 X-74.257 Y-49.657\nN30 G42 G1 X-35.095 Y-27.491\n"
         "N50 G1 X-4.063 Y-82.318\nN60 G1 X-4.273 Y-81.223\nN70 G1 X-34.475 Y-136.512\n"
         "N80 G1 X-50 Y-150\nN90 G40 G1 X-73.967 Y-114.939\nN100 M30\n")


def test_self_approach_error_on_a_daemon_refuses_by_a_dry_run_before_anything_moves(apcictl):
    """On a board that moves a machine, a finding of the check as an error comes from a dry
    run on the embedded emulator, as a ProgramError: the daemon's board never moves."""
    with _daemon(apcictl) as sock:
        def where():
            with apci.open(f"unix:{sock}?timeout=10000") as b:
                return [b.read(f"board.position[{i}]") for i in range(3)]
        assert where() == [0.0, 0.0, 0.0]
        with pytest.raises(apci.ProgramError, match="found by a dry run") as refused:
            apci.run(SPIKE, tools=TOOL_R5, device=f"unix:{sock}", self_approach="error")
        assert refused.value.block == 50
        assert where() == [0.0, 0.0, 0.0]
        # Only warned, it runs on the daemon's board and warns.
        done = apci.run(SPIKE, tools=TOOL_R5, device=f"unix:{sock}")
        assert any(w.code == "SelfApproach" for w in done.warnings)
        assert where() != [0.0, 0.0, 0.0]


def test_a_board_holds_the_motion_for_its_runs_and_another_program_is_refused(apcictl):
    """Board.claim_motion(): the board's motion is this Board's; its runs run, another Board's
    claim and run are refused naming the holder, and release_motion() (or close) ends it."""
    with _daemon(apcictl) as sock:
        uri = f"unix:{sock}"
        with apci.open(uri) as mine, apci.open(uri) as other:
            assert mine.motion_claim() == apci.MotionClaim(False, False, 0, 0, "", "")
            mine.claim_motion()
            own = mine.motion_claim()
            assert own.held and own.yours and own.pid == os.getpid()
            assert own.holder.startswith(f"pid {os.getpid()} (") and " since 20" in own.holder
            seen = other.motion_claim()
            assert seen.held and not seen.yours and seen.since_ms == own.since_ms
            assert seen.holder == own.holder
            with pytest.raises(apci.ObjectError) as twice:
                mine.claim_motion()
            assert twice.value.status == apci.Status.WrongDeviceState
            with pytest.raises(apci.MotionClaimedError,
                               match=rf"the board's motion is held by pid {os.getpid()} \("):
                other.claim_motion()
            with pytest.raises(apci.MotionClaimedError) as refused:
                apci.run("N10 G1 X3 Y4 F600\nM30\n", device=other)
            assert refused.value.status == apci.Status.MotionClaimed
            assert other.read(1000, 0, 10, 0) == 0.0  # axis 0 did not move
            # The holder's own runs run, and it still holds the motion after them.
            assert apci.run("N10 G1 X3 Y4 F600\nM30\n", device=mine).ok
            assert mine.motion_claim().yours
            mine.release_motion()
            assert not other.motion_claim().held
            with pytest.raises(apci.ObjectError) as none:
                mine.release_motion()
            assert none.value.status == apci.Status.WrongDeviceState
            other.claim_motion()
        # Closed, the claim is gone with the Board.
        with apci.open(uri) as after:
            assert not after.motion_claim().held


def test_a_run_on_a_board_another_program_holds_is_refused_and_moves_nothing(tmp_path, apcictl):
    # The daemon, a holder of its motion (libapci's own claim call, through ctypes: a C
    # program's claim, beside Board.claim_motion() above), and a run that must not move the
    # board meanwhile.
    import ctypes
    build_dir = apcictl.parent.parent
    # A short directory: a socket path holds at most 107 bytes, and pytest's tmp_path for a
    # test of this name is longer once pytest has numbered a hundred of its runs.
    short = tempfile.TemporaryDirectory(prefix="apci-")
    sock = pathlib.Path(short.name) / "emu.sock"
    daemon = subprocess.Popen([str(build_dir / "bin" / "rwmos-emu"), "--socket", str(sock)],
                              stderr=subprocess.DEVNULL,
                              env={**os.environ, "APCI_RUNTIME_DIR": str(tmp_path)})
    try:
        for _ in range(500):
            if sock.exists():
                break
            time.sleep(0.01)
        # The very libapci the module runs on (a build tree may hold an older SONAME's too).
        maps = pathlib.Path("/proc/self/maps").read_text().splitlines()
        lib = ctypes.CDLL(next(line.split()[-1] for line in maps if "/libapci.so" in line))
        holder = ctypes.c_void_p()
        assert lib.apci_open(f"unix:{sock}".encode(), ctypes.byref(holder)) == 0
        assert lib.apci_claim_motion(holder) == 0
        with pytest.raises(apci.MotionClaimedError,
                           match=rf"the board's motion is held by pid {os.getpid()} \(") as caught:
            apci.run("N10 G1 X3 Y4 F600\nM30\n", device=f"unix:{sock}")
        assert caught.value.status == apci.Status.MotionClaimed
        with apci.open(f"unix:{sock}") as board:
            assert board.read(1000, 0, 10, 0) == 0.0  # axis 0 did not move
        lib.apci_close(holder)
        # Released (closed), the same run runs.
        assert apci.run("N10 G1 X3 Y4 F600\nM30\n", device=f"unix:{sock}").ok
    finally:
        daemon.terminate()
        daemon.wait(timeout=10)
        short.cleanup()


def test_a_lost_link_says_how_a_python_program_opens_the_board_again(apcictl):
    """The daemon stops under a run, then under a run about to start: the run's error (during
    the run) and the TransportError (its claim, before) name what ended the link and then what
    a Python program does, apci.open(); not apcictl's next command, nor libapci's
    apci_reconnect() (a C function Python does not offer)."""
    hint = "; apci.open() opens the board again"
    with _daemon_process(apcictl) as (sock, daemon):
        uri = f"unix:{sock}"
        # Long enough to be under way for seconds over the socket.
        program = "N1 G1 F60000\n" + "X1\nX0\n" * 50000 + "M30\n"
        outcome = {}

        def run():
            try:
                outcome["result"] = apci.run(program, device=uri, samples=False, check=False)
            except apci.Error as e:  # pragma: no cover - named by the assert below
                outcome["raised"] = e

        with apci.open(uri) as watcher:
            thread = threading.Thread(target=run)
            thread.start()
            # The run holds the board's motion once it is under way.
            deadline = time.monotonic() + 30
            while not watcher.motion_claim().held and time.monotonic() < deadline:
                time.sleep(0.001)
            daemon.terminate()
            assert daemon.wait(timeout=10) == 0
            thread.join(timeout=120)
            assert not thread.is_alive()
            assert "raised" not in outcome, outcome.get("raised")
            result = outcome["result"]
            assert not result.ok and result.errors, "the run went on without its board"
            first = result.errors[0]
            assert first.code == "TransportError", first
            assert "shutting down (SIGTERM)" in first.message, first.message
            assert hint in first.message, first.message
            assert "apci_reconnect" not in first.message, first.message
            assert "next command" not in first.message, first.message
            # A run about to start on a board whose link is lost: its claim says so.
            with pytest.raises(apci.TransportError) as lost:
                apci.run("N10 G1 X1 F600\nM30\n", device=watcher)
            said = str(lost.value)
            assert said.startswith("claim the board's motion: "), said
            assert said.endswith(hint), said
            assert lost.value.status == apci.Status.TransportError
