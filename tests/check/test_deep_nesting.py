"""A deep hierarchy of distinct models is not a model that contains itself (issue 33, point 7:
reproduction check-a009-false-positive-deep-nesting). A009 names the chain of models that
repeats; a hierarchy beyond plx check's nesting limit gets a message that says it is a limit."""

from __future__ import annotations

import pytest

from plxtools.check.instance import MAX_NESTING
from tests.conftest import run_plx

pytest.importorskip("mujoco")


def _chain(levels: int) -> str:
    """`levels` distinct systems, each holding the previous one; one body at the bottom."""
    lines = ["S0 is Physics3D.System:", "    b is Physics3D.Bodies.RigidBody:", "        inertia.mass: 1"]
    for i in range(1, levels):
        lines += [f"S{i} is Physics3D.System:", f"    inner is S{i - 1}"]
    lines += ["Scene is Physics3D.System:", f"    top is S{levels - 1}"]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("levels", [150, MAX_NESTING - 10])
def test_distinct_models_nested_deep_are_assembled_and_simulated(tmp_path, levels):
    f = tmp_path / "deep.openplx"
    f.write_text(_chain(levels))
    r = run_plx("check", "--simulate", "--duration", "0.05", str(f))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "A009" not in r.stdout and "Scene: 1 body" in r.stdout


def test_beyond_the_nesting_limit_the_message_is_a_limit_not_a_cycle(tmp_path):
    f = tmp_path / "deep.openplx"
    f.write_text(_chain(MAX_NESTING + 100))
    r = run_plx("check", str(f))
    assert r.returncode == 1
    a009 = [line for line in r.stdout.splitlines() if "A009" in line]
    assert len(a009) == 1, r.stdout
    assert f"more than plx check instantiates ({MAX_NESTING}); no model contains itself" in a009[0]
    assert "contains itself (" not in a009[0]


@pytest.mark.parametrize("text, chain", [
    ("Link is Physics3D.System:\n    next is Link\n"
     "Scene is Physics3D.System:\n    top is Link\n", "Link contains itself (Link -> Link)"),
    ("A is Physics3D.System:\n    b is B\nB is Physics3D.System:\n    a is A\n"
     "Scene is Physics3D.System:\n    top is A\n", "A contains itself (A -> B -> A)"),
])
def test_a_model_that_contains_itself_is_named_with_its_chain(tmp_path, text, chain):
    f = tmp_path / "loop.openplx"
    f.write_text(text)
    r = run_plx("check", str(f))
    assert r.returncode == 1
    a009 = [line for line in r.stdout.splitlines() if "error A009" in line]
    assert len(a009) == 1 and chain in a009[0], r.stdout
