"""Choosing the bundle set: bundle paths replace official bundles, versions, pins, discovery, settings."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from tests.bundles.conftest import offline_env
from tests.conftest import bundle_root, run_plx


def _write(p: Path, text: str) -> Path:
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text, encoding="utf-8")
    return p


def _bundle(folder: Path, name: str, extra: str = '    dependencies: ["Physics3D"]\n') -> Path:
    _write(folder / "config.openplx", f'config is BundleConfig:\n    name: "{name}"\n    version: "1.0.0"\n{extra}')
    return folder


def _settings(stdout: str) -> dict[str, list[str]]:
    rows = {}
    for ln in stdout.splitlines():
        parts = ln.split()
        if len(parts) >= 3 and not ln.startswith(("official", "bundle folder", "bundle ", "note")):
            rows[parts[0]] = parts[1:]
    return rows


def test_a_copy_of_the_official_bundles_lints_clean_without_configuration(tmp_path):
    copy = tmp_path / "agx" / "bundles"
    shutil.copytree(bundle_root(), copy, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
    r = run_plx("lint", str(copy), "--output-format", "json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    diags = json.loads(r.stdout)
    assert [d for d in diags if d["severity"] == "error"] == []
    s = run_plx("lint", str(copy), "--show-settings", cwd=tmp_path)
    rows = _settings(s.stdout)
    assert rows["Physics3D"][1] == str(copy.resolve() / "Physics3D"), s.stdout
    assert "replaces the official bundle" in s.stdout


def test_bundle_path_in_config_replaces_the_official_bundle(tmp_path):
    agx = tmp_path / "agx"
    shutil.copytree(bundle_root() / "Math", agx / "Math")
    proj = tmp_path / "proj"
    _write(proj / "plx.toml", f'bundle-path = ["{agx.as_posix()}"]\n')
    _write(proj / "m.openplx", "V is Math.Vec3:\n    x: 1\n")
    s = run_plx("lint", str(proj), "--show-settings")
    assert s.returncode == 0, s.stderr
    rows = _settings(s.stdout)
    assert rows["Math"][1] == str((agx / "Math").resolve())
    assert "bundle-path in" in s.stdout and rows["Physics"][1] != str(agx / "Physics")
    r = run_plx("lint", str(proj))
    assert r.returncode == 0, r.stdout + r.stderr


def test_openplx_version_in_config_and_flag(tmp_path, fetched):
    fetched("0.15.0")
    _write(tmp_path / "plx.toml", 'openplx-version = "0.15.0"\n')
    m = _write(tmp_path / "m.openplx", "B is Physics3D.Bodies.RigidBody\n")
    s = run_plx("lint", str(m), "--show-settings")
    assert "official bundles: 0.15.0" in s.stdout and "openplx-version in" in s.stdout, s.stdout + s.stderr
    assert _settings(s.stdout)["Physics3D"][0] == "0.15.0"
    s2 = run_plx("lint", str(m), "--show-settings", "--openplx-version", "0.19.0")
    assert "official bundles: 0.19.0" in s2.stdout and "(--openplx-version)" in s2.stdout


def test_a_user_bundle_pin_picks_the_version_and_says_so(tmp_path, fetched):
    fetched("0.15.0")
    bot = _bundle(tmp_path / "MyBot", "MyBot", '    dependencies: ["Physics3D@0.15.0"]\n')
    _write(bot / "Arm.openplx", "Arm is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n")
    r = run_plx("lint", str(tmp_path))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "using openplx-bundles 0.15.0 (pinned by" in r.stderr and "config.openplx:4:" in r.stderr
    s = run_plx("lint", str(tmp_path), "--show-settings")
    assert _settings(s.stdout)["Physics3D"][0] == "0.15.0"
    assert _settings(s.stdout)["MyBot"][1] == str(bot.resolve())


def test_configuration_beats_a_pin(tmp_path):
    bot = _bundle(tmp_path / "MyBot", "MyBot", '    dependencies: ["Physics3D@0.15.0"]\n')
    _write(bot / "Arm.openplx", "Arm is Physics3D.Bodies.RigidBody\n")
    _write(tmp_path / "plx.toml", 'openplx-version = "0.19.0"\n')
    s = run_plx("lint", str(tmp_path), "--show-settings")
    assert "official bundles: 0.19.0" in s.stdout, s.stdout


def test_unknown_name_of_a_nearby_bundle_gets_a_help_line(tmp_path):
    parts = _bundle(tmp_path / "MyParts", "MyParts")
    _write(parts / "Wheel.openplx", "Wheel is Physics3D.Bodies.RigidBody\n")
    scene = _write(tmp_path / "models" / "scene.openplx", "Scene is Physics3D.System:\n    w is MyParts.Wheel\n")
    r = run_plx("lint", str(scene), "--output-format", "json")
    diags = json.loads(r.stdout)
    n001 = [d for d in diags if d["code"] == "N001"]
    assert n001 and "--bundle-path" in (n001[0].get("help") or ""), diags
    assert str(parts.resolve()) in n001[0]["help"]
    # and loading it as the help says makes the error go away
    r2 = run_plx("lint", str(scene), "--bundle-path", str(parts))
    assert r2.returncode == 0, r2.stdout + r2.stderr


def test_a_bundle_in_the_linted_tree_is_found_without_configuration(tmp_path):
    parts = _bundle(tmp_path / "MyParts", "MyParts")
    _write(parts / "Wheel.openplx", "Wheel is Physics3D.Bodies.RigidBody\n")
    _write(tmp_path / "models" / "scene.openplx", "Scene is Physics3D.System:\n    w is MyParts.Wheel\n")
    r = run_plx("lint", str(tmp_path))
    assert r.returncode == 0, r.stdout + r.stderr


def test_two_versions_in_one_process(fetched, tmp_path):
    from plxtools.model.versions import cache_dir, resolve_bundle_set
    from plxtools.model.workspace import workspace_for_set
    from plxtools.syntax import parse_text

    fetched("0.15.0")
    old = workspace_for_set(resolve_bundle_set([], cli_version="0.15.0", discover=False, use_config=False))
    new = workspace_for_set(resolve_bundle_set([], cli_version="0.19.0", discover=False, use_config=False))
    assert old is not new and old.program is not new.program
    src = "B is Physics3D.Bodies.RigidBody:\n    geometry is Physics3D.Geometries.Box\n"
    t_old = parse_text(src, str(tmp_path / "a.openplx"))
    t_new = parse_text(src, str(tmp_path / "b.openplx"))
    # (through the one analysis path: the model's facts are reported there)
    from plxtools.rules.analysis import analyse_file

    assert any(d.code == "N001" for d in analyse_file(old, t_old).diagnostics)  # Geometries came after 0.15
    assert not [d for d in analyse_file(new, t_new).diagnostics if d.severity.value == "error"]
    assert old.bundles["Physics3D"].version == "0.15.0" and new.bundles["Physics3D"].version == "0.19.0"
    programs = list((cache_dir() / "programs").glob("*"))
    assert len(programs) >= 2  # one cache per bundle set, both kept


def test_a_native_function_with_another_signature_is_reported_not_a_crash(tmp_path):
    """A bundle version whose `fn` differs from what plxtools implements natively: a diagnostic, no traceback."""
    agx = tmp_path / "agx"
    shutil.copytree(bundle_root() / "Math", agx / "Math")
    vec3 = agx / "Math" / "Vec3.openplx"
    text = vec3.read_text(encoding="utf-8")
    assert "    fn length() -> Real" in text
    vec3.write_text(text.replace("    fn length() -> Real", "    fn length(scale: Real) -> Real"), encoding="utf-8")
    scene = _write(tmp_path / "scene.openplx",
                   "Scene is Physics3D.System:\n    v is Math.Vec3:\n        x: 3\n"
                   "    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: v.length(2)\n"
                   "        geometry is Physics3D.Geometries.Sphere:\n            radius: 0.1\n")
    r = run_plx("check", str(scene), "--bundle-path", str(agx), "--output-format", "json")
    assert r.returncode in (0, 1) and "Traceback" not in r.stderr and "internal error" not in r.stderr, r.stderr
    found = [d for d in json.loads(r.stdout)["diagnostics"] if d["code"] in ("A003", "A008")]
    assert found and "Math.Vec3.length" in found[0]["message"], r.stdout


def test_the_language_server_entry_uses_the_same_order(tmp_path, fetched):
    """workspace_for_folder: what the server calls per workspace folder; same set, same Workspace object."""
    from plxtools.config import _config_for_dir
    from plxtools.model.workspace import describe_bundle_set, workspace_for_folder

    fetched("0.15.0")
    parts = _bundle(tmp_path / "lib" / "MyParts", "MyParts")
    _write(parts / "Wheel.openplx", "Wheel is Physics3D.Bodies.RigidBody\n")
    _write(tmp_path / "plx.toml", 'openplx-version = "0.15.0"\n')
    ws = workspace_for_folder(tmp_path)
    rows = {r["name"]: r for r in describe_bundle_set(ws)}
    assert rows["Physics3D"]["version"] == "0.15.0" and "openplx-version in" in rows["Physics3D"]["why"]
    assert rows["MyParts"]["why"] == "found in the workspace" and not rows["MyParts"]["official"]
    assert workspace_for_folder(tmp_path) is ws  # unchanged config: the loaded set is reused
    (tmp_path / "plx.toml").write_text('openplx-version = "0.19.0"\n', encoding="utf-8")
    _config_for_dir.cache_clear()  # the server clears it when a config file changes
    ws2 = workspace_for_folder(tmp_path)
    assert ws2 is not ws and ws2.bundles["Physics3D"].version == "0.19.0"


def test_unknown_name_of_a_missing_dependency_gets_a_help_line(tmp_path):
    bot = _bundle(tmp_path / "MyBot", "MyBot", '    dependencies: ["Physics3D", "Gears"]\n')
    _write(bot / "Arm.openplx", "Arm is Gears.Spur\n")
    r = run_plx("lint", str(bot / "Arm.openplx"), "--output-format", "json")
    n001 = [d for d in json.loads(r.stdout) if d["code"] == "N001"]
    assert n001 and "'Gears' is a dependency in" in (n001[0].get("help") or ""), r.stdout
