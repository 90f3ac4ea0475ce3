# SPDX-License-Identifier: MIT
"""Where the tests find the source tree (examples) and the build tree (apcictl, rwmos-emu).

ctest (python/CMakeLists.txt) sets APCI_SOURCE_DIR, APCI_BUILD_DIR and PYTHONPATH=BUILD/python;
run by hand from the top of the checkout, they default to . and ./build.
"""

import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("APCI_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
BUILD_DIR = pathlib.Path(os.environ.get("APCI_BUILD_DIR", SOURCE_DIR / "build"))


@pytest.fixture
def source_dir() -> pathlib.Path:
    return SOURCE_DIR


@pytest.fixture
def apcictl() -> pathlib.Path:
    path = BUILD_DIR / "bin" / "apcictl"
    assert path.exists(), f"{path} is not built (cmake --build build --target apcictl)"
    return path


@pytest.fixture
def board():
    import apci
    with apci.open("emu:") as b:
        yield b
