"""An expression deeper than the parser's limit is a located S007 in every command, never an
internal error (issue 33, point 6: reproduction lint-unary-minus-recursion); one at the limit is
checked as usual."""

from __future__ import annotations

import pytest

from plxtools.syntax.depth import MAX_EXPR_DEPTH
from tests.conftest import run_plx

HEAD = "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: "
DEEP = {
    "unary minus": "-" * 20000 + "1",
    "a long sum": "+".join(["1"] * 20000),
    "minus inside brackets": "(" * 150 + "-" * 20000 + "1" + ")" * 150,
}


@pytest.mark.parametrize("what", sorted(DEEP))
def test_a_deep_expression_is_a_located_error_in_lint_check_and_fmt(tmp_path, what):
    f = tmp_path / "deep.openplx"
    f.write_text(HEAD + DEEP[what] + "\n")
    expected = f"{f}:3:9: error S007 expression nested more than {MAX_EXPR_DEPTH} levels deep"
    lint = run_plx("lint", "--no-cache", str(f))
    assert lint.returncode == 1 and expected in lint.stdout, lint.stdout + lint.stderr
    check = run_plx("check", str(f))
    assert check.returncode == 1 and expected in check.stdout, check.stdout + check.stderr
    fmt = run_plx("fmt", "--check", str(f))
    assert fmt.returncode == 2 and f"{f}:3:9: error S007" in fmt.stderr
    for r in (lint, check, fmt):
        assert "internal error" not in r.stdout + r.stderr and "Recursion" not in r.stdout + r.stderr


def test_an_expression_at_the_limit_is_checked_as_usual(tmp_path):
    f = tmp_path / "deep.openplx"
    signs = MAX_EXPR_DEPTH - 1 if MAX_EXPR_DEPTH % 2 else MAX_EXPR_DEPTH - 2  # even: the mass is +1
    f.write_text(HEAD + "-" * signs + "1\n" + "    c is Real: " + "+".join(["1"] * (MAX_EXPR_DEPTH - 2)) + "\n")
    lint = run_plx("lint", "--no-cache", "--select", "S,A,E,M", str(f))
    assert lint.returncode == 0, lint.stdout + lint.stderr
    check = run_plx("check", str(f))
    assert check.returncode == 0 and "1 body" in check.stdout, check.stdout + check.stderr
    fmt = run_plx("fmt", str(f))
    assert fmt.returncode == 0 and "reformatted" in fmt.stderr, fmt.stderr
    assert run_plx("lint", "--no-cache", "--select", "S,A,E,M", str(f)).returncode == 0
