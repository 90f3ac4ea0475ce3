# SPDX-License-Identifier: MIT
"""apci.open(), Board.read/write by address, the type rules, errors with their status."""

import math
import tempfile

import numpy as np
import pytest

import apci

# TC group 1 ([APCI-TC] Table 3): WKZINDEX (int), RADIUS (double), STATUS (int).
WKZINDEX = (1300, 1, 1, 8)
RADIUS = (1300, 1, 1, 7)
FIRMWARE_VERSION = (1000, 0, 1, 0)  # board module, read-only int


def test_open_is_a_context_manager_that_closes(board):
    with apci.open() as b:
        assert not b.closed
        assert b.uri == "emu:"
        b.write(*WKZINDEX, 3)
    assert b.closed
    with pytest.raises(ValueError, match="closed"):
        b.read(*WKZINDEX)
    b.close()  # a second close does nothing


def test_every_emu_open_is_a_fresh_board():
    with apci.open("emu:") as a:
        a.write(*WKZINDEX, 9)
        with apci.open("emu:") as b:
            assert b.read(*WKZINDEX) == 0
        assert a.read(*WKZINDEX) == 9


def test_read_and_write_numeric_addresses(board):
    board.write(*WKZINDEX, 5)
    board.write(*RADIUS, 2.5)
    wkz = board.read(*WKZINDEX)
    radius = board.read(*RADIUS)
    assert wkz == 5 and type(wkz) is int
    assert radius == 2.5 and type(radius) is float


def test_an_int_for_a_double_object_is_written_as_that_float(board):
    board.write(*RADIUS, 3)
    value = board.read(*RADIUS)
    assert value == 3.0 and type(value) is float
    board.write(*RADIUS, np.int64(4))
    assert board.read(*RADIUS) == 4.0


def test_an_integral_float_for_an_int_object_is_written_as_that_int(board):
    board.write(*WKZINDEX, 7.0)
    value = board.read(*WKZINDEX)
    assert value == 7 and type(value) is int
    board.write(*WKZINDEX, np.float64(8.0))
    assert board.read(*WKZINDEX) == 8


def test_a_fractional_float_for_an_int_object_is_a_type_error_and_changes_nothing(board):
    board.write(*WKZINDEX, 4)
    with pytest.raises(TypeError, match=r"1300/1/1/8\): object holds an int32, and 2\.5 is not "
                                        r"integral"):
        board.write(*WKZINDEX, 2.5)
    with pytest.raises(TypeError, match="not integral"):
        board.write(*WKZINDEX, math.nan)
    assert board.read(*WKZINDEX) == 4


@pytest.mark.parametrize("value", ["5", None, True, [1], 1 + 2j])
def test_a_value_that_is_not_a_number_is_a_type_error(board, value):
    with pytest.raises(TypeError, match="must be an int or a float"):
        board.write(*WKZINDEX, value)
    assert board.read(*WKZINDEX) == 0


def test_an_int_beyond_int32_for_an_int_object_is_a_value_error(board):
    with pytest.raises(ValueError, match="outside int32"):
        board.write(*WKZINDEX, 2**40)
    # A double object takes it as a float: the board checks its range then.
    with pytest.raises(apci.ObjectError) as caught:
        board.write(*RADIUS, 2**40)
    assert caught.value.status == apci.Status.ValueTooHigh
    assert "= 1099511627776" in str(caught.value)


def test_address_parts_must_be_int32(board):
    with pytest.raises(TypeError, match="4 ints"):
        board.read(1300, 1, 1)
    with pytest.raises(TypeError, match="index must be an int"):
        board.read(1300, 1, 1.0, 8)
    with pytest.raises(ValueError, match="bus 1099511627776 is outside int32"):
        board.read(2**40, 1, 1, 8)


def test_a_bad_address_raises_an_object_error_with_the_status(board):
    with pytest.raises(apci.ObjectError) as caught:
        board.read(1300, 1, 9, 3)
    e = caught.value
    assert isinstance(e, apci.Error)
    assert e.status == apci.Status.ObjectMissing == 0x06020000
    assert e.status.name == e.status_name == "ObjectMissing"
    assert "1300/1/9/3" in str(e) and "ObjectMissing" in str(e)
    assert e.error_bits == apci.TcError(0)

    with pytest.raises(apci.ObjectError) as caught:
        board.write(1300, 1, 1, 99, 1)
    assert caught.value.status == apci.Status.SubMissing


def test_the_board_refusals_name_their_status(board):
    with pytest.raises(apci.ObjectError) as caught:
        board.write(*FIRMWARE_VERSION, 1)
    assert caught.value.status == apci.Status.ReadOnly
    with pytest.raises(apci.ObjectError) as caught:
        board.write(*RADIUS, math.inf)
    assert caught.value.status == apci.Status.InvalidValue
    assert board.read(*RADIUS) == 0.0


def test_without_option_tc_the_tc_module_is_no_such_device():
    with apci.open("emu:?no-option-tc") as b:
        with pytest.raises(apci.ObjectError) as caught:
            b.read(*WKZINDEX)
    assert caught.value.status == apci.Status.NoSuchDevice


def test_a_device_that_does_not_open_is_a_transport_error():
    # A directory of its own under /tmp: a socket path holds at most 107 bytes, and a build
    # tree's temporary directory (a package build's) may be deeper than that.
    with tempfile.TemporaryDirectory(dir="/tmp") as short, \
            pytest.raises(apci.TransportError) as caught:
        apci.open(f"unix:{short}/nobody.sock")
    assert caught.value.status == apci.Status.TransportError
    assert "nobody.sock" in str(caught.value)
    with pytest.raises(apci.TransportError) as caught:
        apci.open("nosuch:thing")
    assert caught.value.status == apci.Status.InvalidArgument
    with pytest.raises(TypeError, match="uri must be a str"):
        apci.open(5)


def test_status_codes_are_libapcis():
    assert apci.status_name(0x06070010) == "TypeMismatch"
    assert apci.Status.TypeMismatch == 0x06070010
    assert len(apci.Status) == 23
    assert apci.status_name(0x12345678) == "Unknown"
    assert apci.__version__.count(".") == 2


def test_a_lost_link_says_what_ended_it_and_how_python_opens_the_board_again():
    # A daemon stops under an open board: the read fails with what ended the link, followed by
    # the module's hint, not libapci's apci_reconnect() (a C function Python does not offer).
    import pathlib
    import subprocess
    import time

    import apci
    from conftest import BUILD_DIR

    # A socket's path has room for 107 bytes: a short directory, not the build tree's.
    scratch = tempfile.TemporaryDirectory(dir="/tmp", prefix="apci-py-")
    socket = pathlib.Path(scratch.name) / "s.sock"
    daemon = subprocess.Popen([str(BUILD_DIR / "bin" / "rwmos-emu"), "--socket", str(socket)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        for _ in range(500):
            if socket.exists():
                break
            time.sleep(0.01)
        with apci.open(f"unix:{socket}") as b:
            assert b.read(1000, 0, 3, 0) == 8
            daemon.terminate()
            assert daemon.wait(timeout=10) == 0
            with pytest.raises(apci.TransportError) as lost:
                b.read(1000, 0, 3, 0)
            said = str(lost.value)
            assert "closed the connection: shutting down (SIGTERM)" in said, said
            assert "apci_reconnect" not in said, said
            assert said.endswith("; apci.open() opens the board again"), said
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()
        scratch.cleanup()
