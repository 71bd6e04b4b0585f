"""User bundles: namespaces, dependency visibility, and config problems (B rules)."""

from pathlib import Path

from plxtools.lint.runner import lint_file
from plxtools.model.workspace import Workspace


def make_bundle(root: Path, name: str, deps: list[str], files: dict[str, str], raw_config: str | None = None):
    b = root / name
    b.mkdir(parents=True)
    deps_s = ", ".join(f'"{d}"' for d in deps)
    (b / "config.openplx").write_text(raw_config or f'config is BundleConfig:\n    name: "{name}"\n'
                                      f'    version: "0.1.0"\n    dependencies: [{deps_s}]\n')
    for rel, text in files.items():
        f = b / rel
        f.parent.mkdir(parents=True, exist_ok=True)
        f.write_text(text)
    return b


def codes(path, ws):
    return [(d.code, d.span.start.line + 1) for d in lint_file(path, workspace=ws).diagnostics
            if d.severity.value != "info"]


def test_user_bundle_namespaces_and_visibility(tmp_path):
    make_bundle(tmp_path, "Parts", ["Physics3D==0.19.0"], {
        "Wheels/Wheel.openplx": "Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mass: 10\n",
        "Wheels/Big.openplx": "BigWheel is Wheel:\n    inertia.mass: 20\n",
        "Bad.openplx": "Logic is Sensors.LidarLogic\n",
    })
    make_bundle(tmp_path, "Cars", ["Parts"], {
        "Car.openplx": "Car is Physics3D.System:\n    wheel is Parts.Wheels.BigWheel\n    other is Parts.Wheels.Missing\n",
    })
    ws = Workspace([tmp_path])
    assert codes(tmp_path / "Parts" / "Wheels" / "Big.openplx", ws) == []
    assert codes(tmp_path / "Cars" / "Car.openplx", ws) == [("N001", 3)]
    # Sensors is not among Parts' dependencies
    assert codes(tmp_path / "Parts" / "Bad.openplx", ws) == [("B005", 1)]


def test_config_problems(tmp_path):
    make_bundle(tmp_path, "A", ["B", "Nope", "Physics>=1", "0.19.0"], {"X.openplx": "X is Physics3D.System\n"})
    make_bundle(tmp_path, "B", ["A"], {"Y.openplx": "Y is Physics3D.System\n"})
    make_bundle(tmp_path, "C", [], {"Z.openplx": "Z\n"}, raw_config='config is BundleConfig:\n    version: "1"\n')
    ws = Workspace([tmp_path])
    got = sorted(c for c, _ in codes(tmp_path / "A" / "config.openplx", ws))
    assert got == ["B002", "B003", "B004", "B006"]  # "0.19.0" names no bundle; "Physics>=1" a form OpenPLX does not read
    assert [c for c, _ in codes(tmp_path / "C" / "config.openplx", ws)] == ["B001"]


def test_bundle_folder_without_config_is_a_clear_error(tmp_path):
    from tests.conftest import run_plx

    (tmp_path / "empty").mkdir()
    f = tmp_path / "m.openplx"
    f.write_text("M is Physics3D.System\n")
    r = run_plx("lint", str(f), "--bundle-path", str(tmp_path / "empty"))
    assert r.returncode == 2 and "config.openplx" in r.stderr and "Traceback" not in r.stderr
