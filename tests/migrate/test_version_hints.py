"""An unknown name that exists in another official version says so (issue 12 item 6)."""

from __future__ import annotations

import json

from plxtools.model.apiindex import where_defined
from tests.conftest import run_plx


def test_a_type_of_an_older_version_names_the_versions_that_have_it(tmp_path):
    f = tmp_path / "old.openplx"
    f.write_text("Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n"
                 "        geometry is Physics3D.Charges.Box:\n            size: {1, 1, 1}\n", encoding="utf-8")
    [d] = json.loads(run_plx("lint", "--output-format", "json", str(f)).stdout)
    assert d["code"] == "N001"
    have = where_defined("Physics3D.Charges.Box")
    assert have and "0.19.0" not in have  # the index says it was removed before 0.19.0
    assert f"exists in OpenPLX {have[0]}-" in d["help"] and "plx migrate --explain" in d["help"]
    assert have[-1] in d["help"]


def test_a_plain_typo_gets_no_version_note(tmp_path):
    f = tmp_path / "typo.openplx"
    f.write_text("Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBdy\n", encoding="utf-8")
    [d] = json.loads(run_plx("lint", "--output-format", "json", str(f)).stdout)
    assert d["code"] == "N001" and "exists in OpenPLX" not in (d["help"] or "")
