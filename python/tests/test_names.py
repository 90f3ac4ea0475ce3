# SPDX-License-Identifier: MIT
"""Objects by dotted name (objif/names.h) and the object map's types."""

import pytest

import apci


def test_read_and_write_by_name_reach_the_numbered_objects(board):
    board.write("tc.group[1].wkz_index", 5)
    board.write("tc.group[1].radius", 2.5)
    assert board.read(1300, 1, 1, 8) == 5
    assert board.read(1300, 1, 1, 7) == 2.5
    board.write(1300, 1, 2, 7, 4.0)
    value = board.read("tc.group[2].radius")
    assert value == 4.0 and type(value) is float
    assert board.read("board.axis_count") == board.read(1000, 0, 3, 0) == 8


def test_the_type_rules_hold_by_name(board):
    board.write("tc.group[1].radius", 3)  # an int for a double object
    assert board.read("tc.group[1].radius") == 3.0
    board.write("tc.group[1].wkz_index", 6.0)  # an integral float for an int object
    assert board.read("tc.group[1].wkz_index") == 6
    with pytest.raises(TypeError, match=r"write tc\.group\[1\]\.wkz_index \(1300/1/1/8\): "
                                        r"object holds an int32, and 2\.5 is not integral"):
        board.write("tc.group[1].wkz_index", 2.5)
    with pytest.raises(ValueError, match="outside int32"):
        board.write("tc.group[1].wkz_index", 2**31)
    with pytest.raises(TypeError, match="must be an int or a float"):
        board.write("tc.group[1].radius", "2.5")
    assert board.read("tc.group[1].wkz_index") == 6


def test_an_unknown_name_is_an_object_error_with_suggestions(board):
    with pytest.raises(apci.UnknownNameError) as caught:
        board.read("tc.group[1].radus")
    e = caught.value
    assert isinstance(e, apci.ObjectError) and isinstance(e, LookupError)
    assert e.status == apci.Status.ObjectMissing
    # Only the closest: not the other groups' radius nor names one step further.
    assert e.suggestions == ["tc.group[1].radius"]
    assert "no object is named 'tc.group[1].radus'; did you mean" in str(e)
    with pytest.raises(apci.UnknownNameError):
        board.write("no.such.thing", 1)


def test_a_refused_access_by_name_names_the_object(board):
    with pytest.raises(apci.ObjectError) as caught:
        board.write("tc.group[1].radius", -1.0)
    assert caught.value.status == apci.Status.ValueTooLow
    assert str(caught.value).startswith("tc.group[1].radius: write double 1300/1/1/7 = -1: "
                                        "ValueTooLow")
    with pytest.raises(apci.ObjectError) as caught:
        board.write("board.axis_count", 4)
    assert caught.value.status == apci.Status.ReadOnly


def test_object_info_comes_from_the_map():
    info = apci.object_info("tc.group[1].radius")
    assert info.address == (1300, 1, 1, 7)
    assert (info.type, info.access, info.readable, info.writable) == ("double", "r/w", True, True)
    assert info.title == "RADIUS"
    assert apci.object_info(1300, 1, 1, 7) == info
    assert apci.object_info(1300, 1, 9, 7) is None  # no group 9: the map has no such address
    names = apci.object_names()
    assert "tc.group[1].radius" in names and "board.axis_count" in names
    assert len(names) == len(set(names))


def test_every_readable_object_of_the_map_reads_with_its_type(board):
    # The map's types are those the board serves: each readable named object reads as an int
    # or a float as the map says (a fresh board; objects of absent modules are skipped).
    read = 0
    for name in apci.object_names():
        info = apci.object_info(name)
        if not info.readable:
            continue
        try:
            value = board.read(name)
        except apci.ObjectError as e:
            assert e.status in (apci.Status.NoSuchDevice, apci.Status.WrongDeviceState), \
                f"{name}: {e}"
            continue
        assert type(value) is (float if info.type == "double" else int), name
        read += 1
    assert read > 50
