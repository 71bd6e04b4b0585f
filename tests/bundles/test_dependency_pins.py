"""Only a version written in a dependency selects official bundles; a bundle's own `version:` is its
own (issue 29, point 1). The same answer however the bundle was found, in the CLI and the server."""

from __future__ import annotations

import json
from pathlib import Path

from tests.conftest import run_plx
from tests.lsp.rawclient import RawServer

# a valid file under 0.19.0 that 0.17.26 does not know (Geometries came with 0.18.11)
BOX_FILE = "Crate is Physics3D.Bodies.RigidBody:\n    inertia.mass: 2\n    shape is Physics3D.Geometries.Box:\n" \
           "        size: Math.Vec3.from_xyz(1, 1, 1)\n"


def _write(p: Path, text: str) -> Path:
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text, encoding="utf-8")
    return p


def _test_bundle(folder: Path, deps: str) -> Path:
    """A project's own test bundle whose own version happens to look like a release number."""
    _write(folder / "config.openplx", 'config is BundleConfig:\n    name: "TestBundle"\n'
                                      f'    version: "0.17.26"\n    dependencies: [{deps}]\n')
    _write(folder / "Test.openplx", BOX_FILE)
    return folder


def _errors(stdout: str) -> list[dict]:
    return [d for d in json.loads(stdout) if d["severity"] == "error"]


def test_a_bundles_own_version_is_not_a_pin(tmp_path):
    proj = tmp_path / "proj"
    tb = _test_bundle(proj / "TestBundle", '"Physics3D"')
    _write(proj / "models" / "crate.openplx", BOX_FILE)
    folder = run_plx("lint", str(proj), "--output-format", "json", cwd=proj)
    assert folder.returncode == 0 and _errors(folder.stdout) == [], folder.stdout + folder.stderr
    assert "using openplx-bundles" not in folder.stderr
    one = run_plx("lint", "Test.openplx", "--output-format", "json", cwd=tb)  # a file inside the bundle
    assert one.returncode == 0 and _errors(one.stdout) == [], one.stdout + one.stderr
    s = run_plx("lint", str(proj), "--show-settings", cwd=proj)
    first = s.stdout.splitlines()[0]
    assert "the installed openplx-bundles package: no dependency selects a version" in first, s.stdout
    assert "0.17.26" not in first


def test_a_version_in_a_dependency_pins_however_the_bundle_is_found(tmp_path, fetched):
    fetched("0.17.26")
    lib = tmp_path / "lib"
    tb = _test_bundle(lib / "TestBundle", '"Physics3D==0.17.26"')
    scene = _write(tmp_path / "proj" / "scene.openplx", BOX_FILE)
    for how in ([str(tb)], [str(scene), "--bundle-path", str(tb)]):
        r = run_plx("lint", *how)
        assert "using openplx-bundles 0.17.26 (pinned by" in r.stderr, r.stderr
        assert f"{tb / 'config.openplx'}:4:20: dependency \"Physics3D==0.17.26\"" in r.stderr, r.stderr
        j = run_plx("lint", *how, "--output-format", "json")
        assert any(d["code"] == "N001" and "Geometries" in d["message"] for d in _errors(j.stdout)), j.stdout


def test_a_dependency_form_openplx_does_not_read_is_a_warning_and_pins_nothing(tmp_path):
    tb = _test_bundle(tmp_path / "TestBundle", '"Physics3D>=0.17.26", "Math"')
    r = run_plx("lint", str(tb), "--output-format", "json")
    diags = json.loads(r.stdout)
    b006 = [d for d in diags if d["code"] == "B006"]
    assert len(b006) == 1 and b006[0]["severity"] == "warning" and "Physics3D>=0.17.26" in b006[0]["message"]
    assert b006[0]["range"]["start"]["line"] == 4 and "Physics3D==0.19.0" in b006[0]["help"], b006
    assert _errors(r.stdout) == [] and "using openplx-bundles" not in r.stderr


def test_the_server_gives_the_folder_answer_from_any_workspace_root(tmp_path):
    proj = tmp_path / "proj"
    tb = _test_bundle(proj / "TestBundle", '"Physics3D"')
    f = tb / "Test.openplx"
    for root in (proj, tb, tmp_path):
        s = RawServer(env={"OPENPLX_BUNDLE_PATH": ""})
        try:
            s.request("initialize", {"processId": None, "rootUri": root.as_uri(), "initializationOptions": {
                "diagnosticMode": "push"}, "capabilities": {}}, timeout=60)
            s.notify("initialized", {})
            s.open(f.as_uri(), f.read_text())
            diags = s.notification("textDocument/publishDiagnostics", where=lambda p: p["uri"] == f.as_uri())
            assert [d for d in diags["diagnostics"] if d.get("severity") == 1] == [], (root, diags)
            assert s.close() == 0
        finally:
            if s.proc.poll() is None:
                s.proc.kill()
