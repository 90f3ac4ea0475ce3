# SPDX-License-Identifier: MIT
"""The hardware-in-the-loop pattern with pytest: one NC program on two devices, the same path.

The reference is the embedded emulator (emu:); the device under test is another board: here
the emulator daemon rwmos-emu, which this test starts on a socket of its own; on a rig, the
URI of the board (pci:..., usb:...). Every executed segment and every sampled cycle must
agree. Run it with

    PYTHONPATH=build/python python3 -m pytest -q examples/python/test_hil.py

with the daemon found as $APCI_RWMOS_EMU, build/bin/rwmos-emu ($APCI_BUILD_DIR/bin) or on
PATH; APCI_HIL_DEVICE=URI tests that device instead of starting a daemon. The NC program and its
tool list come from examples/ of the source tree, or, installed from the Debian packages, from
apci-tools' /usr/share/doc/apci-tools/examples (this file is in python3-apci's documentation):

    pytest /usr/share/doc/python3-apci/examples/python/test_hil.py

docs/python.md, "The HIL pattern".
"""

import os
import pathlib
import shutil
import signal
import subprocess
import time

import numpy as np
import pytest

import apci

HERE = pathlib.Path(__file__).resolve().parent
SOURCE_DIR = pathlib.Path(os.environ.get("APCI_SOURCE_DIR", HERE.parents[1]))
BUILD_DIR = pathlib.Path(os.environ.get("APCI_BUILD_DIR", SOURCE_DIR / "build"))
# Where the example NC programs are: the source tree's examples/ (this file is in
# examples/python/), else the ones apci-tools installs.
INSTALLED_EXAMPLES = pathlib.Path("/usr/share/doc/apci-tools/examples")


def find_example(*parts: str) -> pathlib.Path:
    for examples in (SOURCE_DIR / "examples", HERE.parent, INSTALLED_EXAMPLES):
        candidate = examples.joinpath(*parts)
        if candidate.is_file():
            return candidate
    pytest.fail(f"{pathlib.Path(*parts)} not found in {SOURCE_DIR / 'examples'}, {HERE.parent} "
                f"or {INSTALLED_EXAMPLES}: set APCI_SOURCE_DIR to a checkout, or install "
                "apci-tools (the Debian package with the example programs)")


PROGRAM = None
TOOLS = None


@pytest.fixture(scope="module")
def example_program():
    global PROGRAM, TOOLS
    PROGRAM = find_example("wr_quad_disc.nc")
    TOOLS = find_example("tools", "wr_quad_disc.tools")


def find_daemon() -> str:
    for candidate in (os.environ.get("APCI_RWMOS_EMU"), BUILD_DIR / "bin" / "rwmos-emu",
                      shutil.which("rwmos-emu")):
        if candidate and pathlib.Path(candidate).is_file():
            return str(candidate)
    pytest.fail("rwmos-emu not found: build it (cmake --build build --target rwmos-emu) or "
                "set APCI_RWMOS_EMU=/path/to/rwmos-emu")


@pytest.fixture
def device(tmp_path_factory):
    """The device under test: APCI_HIL_DEVICE, or a fresh daemon for each test (stopped
    after it), so that no test sees the board another one left."""
    if os.environ.get("APCI_HIL_DEVICE"):
        yield os.environ["APCI_HIL_DEVICE"]
        return
    run_dir = tmp_path_factory.mktemp("hil")
    socket = run_dir / "emu.sock"
    # Its registry entry goes into the test's directory too (docs/rwmos-emu.md, "Finding running daemons").
    env = dict(os.environ, APCI_RUNTIME_DIR=str(run_dir))
    daemon = subprocess.Popen([find_daemon(), "--socket", str(socket), "--log-level", "warn"],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 10.0
        while not socket.exists():
            if daemon.poll() is not None:
                pytest.fail(f"rwmos-emu exited with {daemon.returncode}: "
                            f"{daemon.stderr.read().decode(errors='replace')}")
            if time.monotonic() > deadline:
                pytest.fail(f"rwmos-emu did not create {socket} within 10 s")
            time.sleep(0.05)
        yield f"unix:{socket}"
    finally:
        daemon.send_signal(signal.SIGTERM)
        try:
            daemon.wait(timeout=10)
        except subprocess.TimeoutExpired:
            daemon.kill()
            daemon.wait()
        daemon.stderr.close()


@pytest.fixture(scope="module")
def reference(example_program):
    return apci.run(PROGRAM, tools=TOOLS, device="emu:")


def test_the_device_answers_like_the_emulator(device):
    with apci.open(device) as board, apci.open("emu:") as emu:
        for address in [(1000, 0, 3, 0), (1300, 1, 1, 7), (1300, 0, 12, 0)]:
            assert board.read(*address) == emu.read(*address), address
        assert board.status(1) == emu.status(1)


def test_the_same_program_gives_the_same_path(device, reference):
    under_test = apci.run(PROGRAM, tools=TOOLS, device=device)
    assert reference.ok and under_test.ok
    assert (under_test.blocks, under_test.blocks_executed) == \
        (reference.blocks, reference.blocks_executed)
    # Every executed segment: block, kind, role, points, cycles.
    assert len(under_test.segments) == len(reference.segments) > 0
    for field in ("block", "kind", "role", "ccw", "plane", "start_cycle", "end_cycle"):
        np.testing.assert_array_equal(under_test.segments[field], reference.segments[field],
                                      err_msg=field)
    for field in ("start", "end", "center"):
        np.testing.assert_allclose(under_test.segments[field], reference.segments[field],
                                   rtol=0, atol=1e-9, err_msg=field)
    # Every interpolation cycle.
    assert under_test.axes.shape == reference.axes.shape
    np.testing.assert_allclose(under_test.axes, reference.axes, rtol=0, atol=1e-9)
    assert under_test.registers == reference.registers


def test_the_same_error_at_the_same_line(device):
    program = ("N10 F1000 D1\nN40 G41 G1 X0 Y0\nN50 X60\nN60 Y2\nN70 X0\n"
               "N100 G40 G1 X0 Y-20\nN110 M30\n")
    tools = "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n"
    got = {}
    for uri in ("emu:", device):
        with pytest.raises(apci.RunError) as caught:
            apci.run(program, tools=tools, device=uri)
        got[uri] = (caught.value.line, caught.value.code, caught.value.error_bits,
                    caught.value.result.segments.tobytes())
    assert got["emu:"] == got[device]
    assert got[device][:2] == (4, "KorrError")
