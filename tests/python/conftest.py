"""The Python module's tests (run by ctest as `python_module`, or by hand:
PYTHONPATH=build/python LANTERN_BINARY=build/lantern python3 -m pytest tests/python)."""
import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE_DIR


@pytest.fixture(scope="session")
def lantern_binary():
    path = os.environ.get("LANTERN_BINARY", str(SOURCE_DIR / "build" / "lantern"))
    if not os.access(path, os.X_OK):
        pytest.fail(f"the lantern command is not built at {path} (set LANTERN_BINARY)")
    return path


@pytest.fixture(scope="session")
def cornell_box():
    import lantern

    return lantern.load_scene(str(SOURCE_DIR / "scenes" / "cornell-box.pbrt"))
