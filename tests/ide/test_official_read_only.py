"""An official bundle file opened in the editor (go-to-definition) is a read-only member of the
project's model: editing its buffer never changes what the user's files resolve to."""

from __future__ import annotations

from pathlib import Path

from plxtools.ide.host import AnalysisHost
from tests.conftest import bundle_root


def test_editing_an_official_bundle_buffer_does_not_change_the_model(tmp_path):
    host = AnalysisHost()
    scene = str(tmp_path / "scene.openplx")
    host.open_document(scene, "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n", 1)
    assert [d.code for d in host.state(scene).diagnostics if d.severity.value == "error"] == []
    official = str((bundle_root() / "Physics3D" / "Bodies" / "RigidBody.openplx").resolve())
    text = Path(official).read_text(encoding="utf-8")
    host.open_document(official, text, 1)
    assert host.is_official(official)
    host.update_document(official, text.replace("RigidBody", "RenamedBody"), 2)
    host.state(official)
    assert [d.code for d in host.state(scene).diagnostics if d.severity.value == "error"] == []
