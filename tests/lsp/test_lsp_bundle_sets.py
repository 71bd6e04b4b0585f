"""The server chooses the workspace folder's bundle set as the CLI does, and chooses again when a
config file changes (issue 12, the server part)."""

from __future__ import annotations

from pathlib import Path

from tests.lsp.rawclient import RawServer


def _write(p: Path, text: str) -> Path:
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text, encoding="utf-8")
    return p


def _codes(params: dict) -> list[str]:
    return [d["code"] for d in params["diagnostics"]]


def _start(root: Path, options: dict | None = None) -> RawServer:
    s = RawServer(env={"OPENPLX_BUNDLE_PATH": ""})
    s.request("initialize", {"processId": None, "rootUri": root.as_uri(), "initializationOptions": {
        "diagnosticMode": "push", **(options or {})}, "capabilities": {
        "workspace": {"didChangeWatchedFiles": {"dynamicRegistration": True}}}}, timeout=60)
    s.notify("initialized", {})
    return s


def test_a_config_file_change_chooses_the_bundle_set_again(tmp_path):
    parts = tmp_path / "lib" / "MyParts"
    _write(parts / "config.openplx", 'config is BundleConfig:\n    name: "MyParts"\n    version: "1.0.0"\n'
                                     '    dependencies: ["Physics3D"]\n')
    _write(parts / "Wheel.openplx", "Wheel is Physics3D.Bodies.RigidBody\n")
    proj = tmp_path / "proj"
    scene = _write(proj / "scene.openplx", "Scene is Physics3D.System:\n    w is MyParts.Wheel\n")
    uri = scene.as_uri()
    s = _start(proj)
    try:
        # the server asked to hear about config files (the editor watches them for it)
        reg = s.notification_request("client/registerCapability")
        globs = [w["globPattern"] for r in reg["registrations"] for w in r["registerOptions"]["watchers"]]
        assert "**/plx.toml" in globs and "**/*.openplx" in globs
        s.open(uri, scene.read_text())
        first = s.notification("textDocument/publishDiagnostics", where=lambda p: p["uri"] == uri)
        assert "N001" in _codes(first)  # MyParts is not loaded: an unknown name
        _write(proj / "plx.toml", 'bundle-path = ["../lib/MyParts"]\n')
        s.notify("workspace/didChangeWatchedFiles", {"changes": [{"uri": (proj / "plx.toml").as_uri(), "type": 1}]})
        again = s.notification("textDocument/publishDiagnostics", where=lambda p: p["uri"] == uri)
        assert _codes(again) == [], again
        assert s.close() == 0
    finally:
        if s.proc.poll() is None:
            s.proc.kill()
    assert not [ln for ln in s.stderr if b"Traceback" in ln], s.stderr


def test_a_setup_plx_cannot_use_is_a_message_and_the_official_bundles_still_work(tmp_path):
    proj = tmp_path / "proj"
    _write(proj / "plx.toml", 'bundle-path = ["no/such/folder"]\n')
    scene = _write(proj / "scene.openplx", "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n"
                                            "    typo is Physics3D.Bodies.RigidBdy\n")
    s = _start(proj)
    try:
        s.open(scene.as_uri(), scene.read_text())
        msg = s.notification("window/showMessage")
        assert "no/such/folder" in msg["message"] and "does not exist" in msg["message"], msg
        diags = s.notification("textDocument/publishDiagnostics")
        # official names still resolve: only the typo is reported, with the official suggestion
        assert _codes(diags) == ["N001"] and "RigidBody" in str(diags), diags
        assert s.close() == 0
    finally:
        if s.proc.poll() is None:
            s.proc.kill()
