"""Self-reference, cycles through traits and becomes, deep inheritance: diagnostics, never a crash."""

from plxtools.config import Config
from plxtools.rules.analysis import analyse_tree
from plxtools.syntax import parse_text


def lint(text, ws):
    return analyse_tree(parse_text(text, "/tmp/pathological.openplx"), Config(), ws)


def test_self_inheritance(workspace):
    d = lint("A is A\nScene is Physics3D.System:\n    a is A\n", workspace)
    assert "M005" in [x.code for x in d]


def test_trait_cycle(workspace):
    d = lint("trait T is U\ntrait U is T\nM is Physics3D.System:\n    with T\n", workspace)
    assert "M005" in [x.code for x in d]


def test_becomes_to_self_and_reference_cycle(workspace):
    text = ("Link is Physics3D.Bodies.RigidBody:\n    other is Link\n    inertia becomes Link\n"
            "Scene is Physics3D.System:\n    link is Link\n")
    d = lint(text, workspace)
    assert "M003" in [x.code for x in d]


def test_hundred_deep_inheritance(workspace):
    lines = ["M0 is Physics3D.System:\n    x0 is Real: 0\n"]
    for i in range(1, 101):
        lines.append(f"M{i} is M{i-1}:\n    x{i} is Real: x{i-1} + 1\n")
    lines.append("Scene is M100\n")
    d = lint("".join(lines), workspace)
    assert [x for x in d if x.severity.value == "error"] == []


def test_self_referencing_default(workspace):
    d = lint("Scene is Physics3D.System:\n    a is Real: a + 1\n", workspace)
    assert [x.code for x in d] == ["M006"]
