# SPDX-License-Identifier: MIT
"""The package as Python's tools see it: its metadata, and what `from apci import *` brings."""

import builtins
import importlib.metadata

import apci


def test_importlib_metadata_knows_the_package_and_its_version():
    assert importlib.metadata.version("apci") == apci.__version__
    meta = importlib.metadata.metadata("apci")
    assert meta["Name"] == "apci"
    assert "APCI-8001/8008" in meta["Summary"]


def test_star_import_does_not_shadow_the_builtin_open():
    namespace = {}
    exec("from apci import *", namespace)
    assert "open" not in namespace
    assert namespace.get("open", builtins.open) is builtins.open
    # The rest of the public names come along, and apci.open stays.
    for name in ("Board", "run", "Status", "UnknownNameError", "RunResult"):
        assert name in namespace, name
    assert callable(apci.open)
    # No other public name is a built-in's either (id, input, filter, ...).
    assert sorted(set(apci.__all__) & set(dir(builtins))) == []
    assert sorted(set(namespace) - {"__builtins__"}) == sorted(apci.__all__)


def test_unknown_name_suggests_the_index_typed_without_brackets():
    with apci.open() as board:
        try:
            board.read("tc.group2.radius")
        except apci.UnknownNameError as e:
            assert e.suggestions == ["tc.group[2].radius"]
        else:
            raise AssertionError("tc.group2.radius was read")
