"""Plugin imports through `plx check` (and `plx lint`/`plx fmt` on the same fixtures): what plx reads
(an .obj mesh: a visual mesh with the file's extents) and what it cannot (an .agx archive, a URDF:
said once as A042 info, nothing inside reported)."""

from __future__ import annotations

import json
import shutil

from tests.conftest import CASES, REPO, run_plx

IMPORTS = CASES / "check" / "imports"


def _check_json(*files: str, extra=()):
    r = run_plx("check", "--output-format", "json", *extra, *files)
    assert "Traceback" not in r.stderr, r.stderr
    return r, json.loads(r.stdout)


def _codes(doc, name: str) -> list[tuple[str, int, str]]:
    return sorted((d["code"], d["range"]["start"]["line"], d["severity"]) for d in doc["diagnostics"]
                  if d["file"].endswith(name))


def test_opaque_agx_root_says_once_what_it_cannot_analyse():
    r, doc = _check_json(str((IMPORTS / "pendulum_from_agx.openplx").relative_to(REPO)))
    assert r.returncode == 0, r.stdout
    # no "mass 0" (A033), "not owned by a system" (A039), unknown attribute or root-not-system cascades
    assert _codes(doc, "pendulum_from_agx.openplx") == [("A042", 3, "info")]
    [d] = doc["diagnostics"]
    assert "InvertedPendulum is built from @\"inverted_pendulum.agx\"" in d["message"]
    assert "not analysed" in d["message"]


def test_scene_with_agx_urdf_and_obj_imports():
    r, doc = _check_json(str((IMPORTS / "scene.openplx").relative_to(REPO)))
    got = _codes(doc, "scene.openplx")
    # one A042 per unreadable import (both objects built from the .agx named in one message), the
    # overlap a collision mesh's .obj extents reveal, and the .obj that has no vertices
    assert got == [("A030", 27, "error"), ("A037", 20, "warning"), ("A042", 1, "info"), ("A042", 2, "info")]
    msgs = {d["code"] + str(d["range"]["start"]["line"]): d["message"] for d in doc["diagnostics"]}
    assert msgs["A0421"].startswith("pendulum, second are built from @\"inverted_pendulum.agx\"")
    assert msgs["A0422"].startswith("arm is built from @\"arm.urdf\"")
    assert "overlaps ground (by 0.2 m)" in msgs["A03720"]
    assert "'empty.obj' cannot be used: no vertices" in msgs["A03027"]
    assert r.returncode == 1


def test_imported_obj_is_a_visual_mesh(tmp_path):
    xml = tmp_path / "scene.xml"
    src = IMPORTS / "visual_mesh.openplx"
    r = run_plx("check", "--export-mjcf", str(xml), str(src.relative_to(REPO)))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "All checks passed" in r.stdout
    text = xml.read_text()
    assert 'file="' + str(IMPORTS / "rock.obj") + '" scale="0.5 0.5 0.5"' in text
    geom = next(line for line in text.splitlines() if '<geom name="decoration"' in line)
    assert 'type="mesh"' in geom and 'contype="0"' in geom and 'conaffinity="0"' in geom  # visual only


def test_missing_import_is_an_error_at_the_import_line(tmp_path):
    folder = tmp_path / "m"
    folder.mkdir()
    (folder / "scene.openplx").write_text(
        'import @"arm.urdf" as Arm\n\nScene is Physics3D.System:\n    arm is Arm:\n        base.mass: 3\n',
        encoding="utf-8")
    r = run_plx("lint", "scene.openplx", cwd=folder)
    assert r.returncode == 1
    assert r.stdout.splitlines()[0] == "scene.openplx:1:8: error N006 imported file 'arm.urdf' does not exist"
    assert "N002" not in r.stdout and "M007" not in r.stdout  # the name is still bound: no cascades
    # the result cache keys on the imported file: creating it clears the error
    shutil.copy(IMPORTS / "arm.urdf", folder / "arm.urdf")
    r = run_plx("lint", "scene.openplx", cwd=folder)
    assert r.returncode == 0, r.stdout
    r = run_plx("check", "scene.openplx", cwd=folder)
    assert "info A042 arm is built from @\"arm.urdf\"" in r.stdout and "error" not in r.stdout


def test_a_missing_empty_or_folder_import_is_one_n006_each_also_in_check(tmp_path):
    (tmp_path / "parts").mkdir()
    (tmp_path / "scene.openplx").write_text(
        'import @"gone.agx" as Gone\nimport @"" as Nothing\nimport @"parts" as Parts\n\n'
        'Scene is Physics3D.System:\n    a is Gone\n    b is Nothing\n    c is Parts\n', encoding="utf-8")
    r = run_plx("check", "--output-format", "json", "scene.openplx", cwd=tmp_path)
    assert "Traceback" not in r.stderr, r.stderr
    doc = json.loads(r.stdout)
    found = [(d["code"], d["range"]["start"]["line"], d["message"]) for d in doc["diagnostics"]
             if d["code"] in ("N006", "A031")]
    # lint owns a missing import (N006); check does not add its own A031 for the same file
    assert found == [("N006", 1, "imported file 'gone.agx' does not exist"),
                     ("N006", 2, "the import names no file (an empty path)"),
                     ("N006", 3, "imported file 'parts' is a folder, not a file")], found


def test_env_path_import(tmp_path):
    (tmp_path / "models").mkdir()
    shutil.copy(IMPORTS / "arm.urdf", tmp_path / "models" / "arm.urdf")
    src = tmp_path / "scene.openplx"
    src.write_text('import $"{PLX_TEST_MODELS}/arm.urdf" as model.arm\n\n'
                   'Scene is Physics3D.System:\n    arm is model.arm\n', encoding="utf-8")
    r = run_plx("lint", "--no-cache", str(src), env={"PLX_TEST_MODELS": str(tmp_path / "models")})
    assert r.returncode == 0, r.stdout
    r = run_plx("lint", "--no-cache", str(src), env={"PLX_TEST_MODELS": str(tmp_path / "nowhere")})
    # named as written: the expansion would print an environment value (issue 33)
    assert '1:8: error N006 imported file $"{PLX_TEST_MODELS}/arm.urdf" does not exist' in r.stdout
    assert str(tmp_path / "nowhere") not in r.stdout
    r = run_plx("check", str(src))  # the variable is not set: lint cannot know, check says so
    assert "1:8: warning A007 environment variable PLX_TEST_MODELS" in r.stdout and "N006" not in r.stdout
    r = run_plx("check", str(src), env={"PLX_TEST_MODELS": str(tmp_path / "models")})
    assert "A042" in r.stdout and "error" not in r.stdout


def test_import_lines_are_byte_stable_in_fmt(tmp_path):
    text = ('import @"inverted_pendulum.agx"\n'
            'import @"rock.obj" as Rock  # a boulder\n'
            'import $"{HOME}/robots/arm.urdf" as robots.arm\n'
            '\n'
            'Scene is Physics3D.System:\n'
            '    rock is Rock\n')
    src = tmp_path / "scene.openplx"
    src.write_text(text, encoding="utf-8")
    r = run_plx("fmt", "--check", "--no-cache", str(src))
    assert r.returncode == 0, r.stdout + r.stderr
    src.write_text(text.replace("import @\"rock.obj\" as Rock", "import   @\"rock.obj\"   as  Rock"), encoding="utf-8")
    r = run_plx("fmt", "--no-cache", str(src))
    assert r.returncode == 0 and src.read_text(encoding="utf-8") == text
    r = run_plx("fmt", "--check", "--no-cache", str(src))
    assert r.returncode == 0


def test_names_from_an_agx_archive_are_opaque_not_unknown(tmp_path):
    """`ExtendedRod is PendulumScene_rod` after `import @"pendulum.agx"` (issue 29, point 3): the
    name can only come from the archive, so it is not N001; check says what it does not analyse."""
    shutil.copy(IMPORTS / "inverted_pendulum.agx", tmp_path / "pendulum.agx")
    f = tmp_path / "rod.openplx"
    f.write_text('import @"pendulum.agx"\n\nExtendedRod is PendulumScene_rod:\n    tip is Physics3D.Bodies.RigidBody\n\n'
                 "Scene is Physics3D.System:\n    rod is ExtendedRod\n    floor is Physics3D.Bodies.RigidBody:\n"
                 "        inertia.mass: 1\n        is_dynamic: false\n", encoding="utf-8")
    r, doc = _check_json(str(f))
    assert r.returncode == 0, r.stdout
    got = _codes(doc, "rod.openplx")
    assert ("N008", 3, "info") in got and not [c for c in got if c[0] == "N001" or c[2] == "error"], got
    [a042] = [d for d in doc["diagnostics"] if d["code"] == "A042"]
    assert a042["message"].startswith('rod is built from @"pendulum.agx"'), a042
    lint = run_plx("lint", str(f))
    assert lint.returncode == 0 and "N001" not in lint.stdout and "C003" not in lint.stdout, lint.stdout
