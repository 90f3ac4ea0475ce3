# SPDX-License-Identifier: MIT
"""TC ERROR and STATUS decoded into the named flags of [APCI-TC] Tables 4 and 5."""

import pytest

import apci

GROUP1 = (1300, 1, 1)
ERROR, STATUS, XAXIS, YAXIS, ZAXIS, LEFT = 1, 3, 4, 5, 11, 9


def test_the_flags_are_libapcis_names_of_the_tables():
    assert [(f.name, int(f)) for f in apci.TcError] == [
        ("InitError", 1), ("KorrError", 2), ("CalcError", 4), ("PlaneError", 8),
        ("CenterError", 16)]
    assert [(f.name, int(f)) for f in apci.TcStatus] == [("Run", 1), ("ProfMarked", 2)]


def test_decode_status_names_every_set_bit():
    s = apci.decode_status(0b10011, 0b10, group=2)
    assert s.group == 2
    assert s.InitError and s.KorrError and s.CenterError
    assert not s.CalcError and not s.PlaneError
    assert s.ProfMarked and not s.Run
    assert s.error == apci.TcError.InitError | apci.TcError.KorrError | apci.TcError.CenterError
    assert s.error_names == ["InitError", "KorrError", "CenterError"]
    assert s.status_names == ["ProfMarked"]
    assert not s.ok
    assert str(s) == ("group 2: ERROR 19 (InitError, KorrError, CenterError), "
                      "STATUS 2 (ProfMarked)")
    # A bit [APCI-TC] does not name is kept and shown by its number.
    assert apci.decode_status(0x40).error_names == ["bit6"]
    with pytest.raises(AttributeError, match="KorrError"):
        s.NoSuchFlag  # noqa: B018


def test_a_fresh_board_has_no_flag_set(board):
    for group in (0, 1, 2, 3):
        s = board.status(group)
        assert s.ok and s.error == 0 and s.status == 0
        assert not s.Run and not s.InitError


def test_a_running_group_shows_run(board):
    board.write(*GROUP1, XAXIS, 0)
    board.write(*GROUP1, YAXIS, 1)
    board.write(*GROUP1, ZAXIS, 2)
    board.write(*GROUP1, LEFT, 1)
    board.write(*GROUP1, STATUS, 1)
    s = board.status(1)
    assert s.Run and s.ok
    assert s.status == apci.TcStatus.Run


def test_a_refused_tc_write_carries_the_error_bits_it_set(board):
    # STATUS = 1 on a group that is not initialised: refused, and ERROR gets InitError
    # ([APCI-TC] Table 3).
    with pytest.raises(apci.ObjectError) as caught:
        board.write(*GROUP1, STATUS, 1)
    e = caught.value
    assert e.status == apci.Status.WrongDeviceState
    assert e.error_bits == apci.TcError.InitError
    assert "InitError" in str(e)
    s = board.status(1)
    assert s.InitError and not s.Run
    # Writing ERROR clears it.
    board.write(*GROUP1, ERROR, 0)
    assert board.status(1).ok


def test_status_of_a_group_that_does_not_exist_raises(board):
    with pytest.raises(apci.ObjectError) as caught:
        board.status(7)
    assert caught.value.status == apci.Status.ObjectMissing
