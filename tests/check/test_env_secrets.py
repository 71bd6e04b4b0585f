"""What a `$"{VAR}"` string expands to never reaches a log unless asked (issue 33, point 4:
reproduction check-prints-env-secret): `plx check` in every output format and `plx lint` name the
expression as written; `plx check --show-env` adds the value."""

from __future__ import annotations

import pytest

from tests.conftest import run_plx

SECRET = "ghp_SUPERSECRET123"
MODEL = """\
import $"{PLX_TEST_TOKEN}/history.obj" as History
Scene is Physics3D.System:
    b is Physics3D.Bodies.RigidBody:
        inertia.mass: 1
        visual is Visuals.Geometries.ExternalTriMeshGeometry:
            path: $"{PLX_TEST_TOKEN}.obj"
"""


@pytest.fixture
def leak(tmp_path):
    f = tmp_path / "leak.openplx"
    f.write_text(MODEL)
    return f


@pytest.mark.parametrize("fmt", ["text", "json", "github", "sarif"])
def test_check_names_the_expression_not_the_value(leak, fmt):
    r = run_plx("check", "--output-format", fmt, str(leak), env={"PLX_TEST_TOKEN": SECRET})
    assert r.returncode == 1, r.stderr
    out = r.stdout + r.stderr
    assert SECRET not in out
    assert "A031" in out and "N006" in out  # the findings are still reported, by their expression
    if fmt == "text":
        assert 'warning A031 file $"{PLX_TEST_TOKEN}.obj" does not exist' in out
        assert 'error N006 imported file $"{PLX_TEST_TOKEN}/history.obj" does not exist' in out


def test_lint_names_the_expression_not_the_value(leak):
    r = run_plx("lint", "--no-cache", str(leak), env={"PLX_TEST_TOKEN": SECRET})
    assert r.returncode == 1 and SECRET not in r.stdout + r.stderr
    assert 'imported file $"{PLX_TEST_TOKEN}/history.obj" does not exist' in r.stdout


def test_show_env_shows_the_value_when_asked(leak):
    r = run_plx("check", "--show-env", str(leak), env={"PLX_TEST_TOKEN": SECRET})
    assert f"warning A031 file '{SECRET}.obj' (from $\"{{PLX_TEST_TOKEN}}.obj\") does not exist" in r.stdout
