"""Outputs shown in the docs are produced from the current plx (issue 45: docs that taught an older
plx). Each block between `<!-- output: NAME -->` and `<!-- /output -->` is what a command prints
now, with its timing masked; `PLX_UPDATE_SNAPSHOTS=1` rewrites the blocks (review the diff). The
distances the docs quote for the tutorial's step-11 drive are compared with what it measures."""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import pytest

from tests.conftest import plx_here

REPO = Path(__file__).resolve().parents[2]
DOCS = REPO / "docs"
UPDATE = os.environ.get("PLX_UPDATE_SNAPSHOTS") == "1"

pytest.importorskip("mujoco")


def _flipped_hub(tmp: Path) -> str:
    """The BoxTruck's scenario with the front right hub's axis flipped (docs/testing.md)."""
    for f in (REPO / "examples" / "boxtruck").iterdir():
        shutil.copy(f, tmp / f.name)
    model = tmp / "boxtruck.openplx"
    text = model.read_text(encoding="utf-8")
    hub = text.index("front_right_hub is")
    at = text.index("main_axis: {0, 1, 0}", hub)
    model.write_text(text[:at] + "main_axis: {0, -1, 0}" + text[at + len("main_axis: {0, 1, 0}"):], encoding="utf-8")
    out = plx_here("test", "drive.scenario.toml", cwd=tmp).stdout
    return re.sub(r" in \d+\.\d+s$", " in …s", out.rstrip("\n"), flags=re.M)


OUTPUTS = {"flipped-hub": ("testing.md", _flipped_hub)}


@pytest.mark.parametrize("name", sorted(OUTPUTS))
def test_a_shown_output_is_what_plx_prints(name, tmp_path):
    page, produce = OUTPUTS[name]
    path = DOCS / page
    doc = path.read_text(encoding="utf-8")
    start = f"<!-- output: {name} -->\n```text\n"
    end = "```\n<!-- /output -->"
    i, j = doc.index(start) + len(start), doc.index(end, doc.index(start))
    now = produce(tmp_path) + "\n"
    if UPDATE:
        doc = doc[:i] + now + doc[j:]
        path.write_text(doc, encoding="utf-8")
    assert doc[i:doc.index(end, i)] == now, f"docs/{page}: the output shown as {name!r} is stale"


def test_the_step11_distance_the_docs_quote_is_measured():
    from plxtools.check.api import load

    sim = load(REPO / "examples" / "tutorial" / "step11-controls" / "boxtruck.openplx")
    start = sim.body("boxTruck.chassis").position[0]
    for motor, sign in (("front_left_drive_motor", 1), ("front_right_drive_motor", -1)):
        sim.set(f"boxTruck.{motor}.target_angular_velocity_input", 3.0 * sign)
    sim.step(2.0)
    went = abs(sim.body("boxTruck.chassis").position[0] - start)
    quoted = f"{went:.2f} m"
    assert f"drives {quoted} and comes back" in (DOCS / "examples.md").read_text(encoding="utf-8")
    assert f"# x = -{quoted}" in (DOCS / "testing.md").read_text(encoding="utf-8")
