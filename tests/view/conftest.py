import shutil
from pathlib import Path

import pytest

from plxtools.view.keys import KeyboardCallback

VIEWER = Path(__file__).resolve().parents[2] / "examples" / "viewer"


@pytest.fixture
def truck(tmp_path) -> Path:
    """A copy of the viewer example (model, meshes, key table, controller) to edit."""
    for f in VIEWER.iterdir():
        if f.is_file():
            shutil.copy(f, tmp_path / f.name)
    return tmp_path / "truck.openplx"


@pytest.fixture(autouse=True)
def no_bindings_left():
    KeyboardCallback.clear()
    yield
    KeyboardCallback.clear()
