"""Checker messages that must not mislead (issue 16): cascades, misspelt keywords, missing const."""

from plxtools.lint.runner import lint_file
from tests.conftest import run_plx

CASCADE = """\
Wheel is Physics3D.Bodies.RigidBody

Car is Physics3D.System:
    front_left_wheel Wheel
    front_right_wheel is Wheel
    hinge is Physics3D.Interactions.Hinge:
        connectors: [front_left_wheel.kinematics.local_transform]
    front_left_wheel.inertia.mass: 2
    chassis becoms Wheel
"""


def lint_text(tmp_path, text, workspace):
    path = tmp_path / "scene.openplx"
    path.write_text(text)
    return path, lint_file(path, workspace=workspace).diagnostics


def test_a_broken_declaration_is_not_answered_with_a_sibling_name(tmp_path, workspace):
    _path, diags = lint_text(tmp_path, CASCADE, workspace)
    cascades = [d for d in diags if d.code in ("N002", "N003")]
    assert [(d.code, d.span.start.line) for d in cascades] == [("N003", 6), ("N002", 7)]
    for d in cascades:
        assert "front_right_wheel" not in (d.help or "") and d.fix is None
        assert "line 4 has a syntax error" in d.help


def test_a_misspelt_keyword_gets_a_suggestion_and_an_edit(tmp_path, workspace):
    _path, diags = lint_text(tmp_path, CASCADE, workspace)
    (d,) = [d for d in diags if d.span.start.line == 8]
    assert d.code == "S011" and d.help == "did you mean 'becomes'?"
    (edit,) = d.fix.edits
    assert CASCADE[edit.start:edit.end] == "becoms" and edit.text == "becomes"


def test_an_unknown_attribute_still_gets_did_you_mean_as_an_edit(tmp_path, workspace):
    text = "Car is Physics3D.System:\n    body is Physics3D.Bodies.RigidBody\n    bodi.kinematics: 1\n"
    _path, diags = lint_text(tmp_path, text, workspace)
    (d,) = [d for d in diags if d.code == "N002"]
    assert d.help == "did you mean 'body'?"
    (edit,) = d.fix.edits
    assert text[edit.start:edit.end] == "bodi" and edit.text == "body"


CONST = """\
Steel is Physics.Geometries.Material

Car is Physics3D.System:
    body is Physics3D.Bodies.RigidBody
    mat is Physics.Geometries.Material: Steel
"""


def test_a_model_used_as_a_value_asks_for_const_and_the_fix_adds_it(tmp_path, workspace):
    path, diags = lint_text(tmp_path, CONST, workspace)
    (d,) = [d for d in diags if d.code == "T001"]
    assert "must be declared 'const'" in d.message and "is a type" not in d.message
    (edit,) = d.fix.edits
    assert (edit.start, edit.end, edit.text) == (0, 0, "const ")
    r = run_plx("lint", "--fix", "--unsafe-fixes", str(path))
    assert path.read_text().startswith("const Steel is")
    r = run_plx("lint", str(path))
    assert r.returncode == 0, r.stdout


def test_check_says_const_too_not_an_internal_class_name(tmp_path):
    path = tmp_path / "scene.openplx"
    path.write_text(CONST)
    r = run_plx("check", str(path))
    assert "TypeObj" not in r.stdout + r.stderr
    assert "'const'" in r.stdout
