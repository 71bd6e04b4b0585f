"""Shared set-up of the signal tests: the example BoxTruck copied into a temporary folder."""

from __future__ import annotations

import shutil
from pathlib import Path

from tests.conftest import REPO

BOXTRUCK = REPO / "examples" / "boxtruck"
RIGHT_HUB = """    front_right_hub is Physics3D.Interactions.MateConnector:
        position: {-hub_offset.x, hub_offset.y, -hub_offset.z}
        main_axis: {0, 1, 0}"""


def boxtruck_copy(tmp: Path, wrong_sign: bool = False) -> Path:
    """The example folder (model and scenario) in ``tmp``; ``wrong_sign`` flips the front right hub's axis."""
    for f in ("boxtruck.openplx", "drive.scenario.toml"):
        shutil.copy(BOXTRUCK / f, tmp / f)
    if wrong_sign:
        model = tmp / "boxtruck.openplx"
        text = model.read_text(encoding="utf-8")
        assert RIGHT_HUB in text
        model.write_text(text.replace(RIGHT_HUB, RIGHT_HUB.replace("{0, 1, 0}", "{0, -1, 0}")), encoding="utf-8")
    return tmp


def scenario(tmp: Path, body: str, name: str = "case") -> Path:
    """A scenario file for the BoxTruck copy in ``tmp`` (``model =`` line first, then ``body``)."""
    p = tmp / f"{name}.scenario.toml"
    p.write_text('model = "boxtruck.openplx"\n' + body, encoding="utf-8")
    return p
