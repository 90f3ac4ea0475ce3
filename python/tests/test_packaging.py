# SPDX-License-Identifier: MIT
"""The package as Python's tools see it: its metadata, and what `from apci import *` brings."""

import builtins
import importlib.metadata
import importlib.util
import shutil

import pytest

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


def load_installed_hil_example(tmp_path, monkeypatch, source_dir):
    """examples/python/test_hil.py where python3-apci installs it: /usr/share/doc/python3-apci/
    examples/python, with no examples/ of a source tree beside it (here under tmp_path)."""
    beside = tmp_path / "usr/share/doc/python3-apci/examples/python"
    beside.mkdir(parents=True)
    shutil.copy(source_dir / "examples/python/test_hil.py", beside)
    monkeypatch.delenv("APCI_SOURCE_DIR", raising=False)
    spec = importlib.util.spec_from_file_location("installed_test_hil", beside / "test_hil.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_installed_hil_example_finds_the_program_apci_tools_installs(tmp_path, monkeypatch,
                                                                     source_dir):
    hil = load_installed_hil_example(tmp_path, monkeypatch, source_dir)
    # apci-tools' examples (/usr/share/doc/apci-tools/examples), staged under tmp_path.
    tools_examples = tmp_path / "usr/share/doc/apci-tools/examples"
    (tools_examples / "tools").mkdir(parents=True)
    shutil.copy(source_dir / "examples/wr_quad_disc.nc", tools_examples)
    shutil.copy(source_dir / "examples/tools/wr_quad_disc.tools", tools_examples / "tools")
    monkeypatch.setattr(hil, "INSTALLED_EXAMPLES", tools_examples)
    assert hil.find_example("wr_quad_disc.nc") == tools_examples / "wr_quad_disc.nc"
    assert (hil.find_example("tools", "wr_quad_disc.tools")
            == tools_examples / "tools" / "wr_quad_disc.tools")


def test_installed_hil_example_without_apci_tools_says_to_install_it(tmp_path, monkeypatch,
                                                                     source_dir):
    hil = load_installed_hil_example(tmp_path, monkeypatch, source_dir)
    monkeypatch.setattr(hil, "INSTALLED_EXAMPLES", tmp_path / "usr/share/doc/apci-tools/examples")
    with pytest.raises(pytest.fail.Exception, match="install apci-tools"):
        hil.find_example("wr_quad_disc.nc")
