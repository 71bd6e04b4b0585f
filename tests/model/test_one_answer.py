"""One semantic answer (issue 28, point 2): what lint accepts or rejects about a type is what every
other consumer of plxtools/model sees, and the stored API index orders layers like the resolver.

Each fixture is an in-process OpenPLX text; the expectations stand next to it (`# members: ...`,
`# lint: ...`) so a reader sees the model and the answer together.
"""

from __future__ import annotations

import re
from importlib import metadata

import pytest

from plxtools.model.apiindex import ApiIndex, load, versions
from plxtools.rules.analysis import analyse_file
from plxtools.syntax import parse_text

WITH_A_MODEL = """\
Wheel:
    radius is Real: 1

Extra:
    bonus is Real: 2

trait Shiny:
    gloss is Real: 3

Car:
    a is Wheel with Extra          # lint: N005 | members: radius
    b is Wheel with Shiny          # lint: - | members: gloss radius
    c is Wheel with Extra, Shiny   # lint: N005 | members: gloss radius
    d is Wheel                     # lint: - | members: radius
"""

EXPECT = re.compile(r"^\s+(\w+) is .*# lint: (\S+) \| members: (.*)$")


def analyse(workspace, text: str, name: str):
    tree = parse_text(text, f"/tmp/plx-one-answer-tests/{name}.openplx")
    return analyse_file(workspace, tree)


def expectations(text: str):
    for line_no, line in enumerate(text.splitlines()):
        m = EXPECT.match(line)
        if m:
            yield line_no, m.group(1), m.group(2), m.group(3).split()


def test_a_model_after_with_is_reported_by_lint_and_adds_no_members_anywhere(workspace):
    result = analyse(workspace, WITH_A_MODEL, "with_model")
    p = workspace.program
    car = result.unit.locals["Car"]
    checked = 0
    for line_no, attr, lint, members in expectations(WITH_A_MODEL):
        codes = sorted({d.code for d in result.diagnostics if d.span.start.line == line_no})
        assert codes == ([] if lint == "-" else [lint]), attr
        mem = p.all_members(car)[attr]
        # the member's type as the checker typed it and as Program resolves it from the source
        for ty in (p.member_type(mem), p.resolve_type_expr(mem.stmt.type, result.unit)):
            assert sorted(p.members_of(ty)) == members, attr
            assert all(t.is_trait for t in ty.traits), attr
        checked += 1
    assert checked == 4


# ------------------------------------------------------------------ the API index's layer order

def index(models: dict) -> ApiIndex:
    return ApiIndex({"version": "0.0.1", "models": models})


def attr(type_: str, flags: str = "") -> list:
    return [type_, flags, 1, ""]


def test_the_api_index_lets_a_trait_win_over_the_base():
    idx = index({
        "B": {"k": "m", "a": {"x": attr("Real"), "y": attr("Real")}},
        "T": {"k": "t", "a": {"x": attr("Int")}},
        "M": {"k": "m", "b": "B", "w": ["T"], "a": {"y": attr("Bool")}},
    })
    got = {name: (rec[0], rec[4]) for name, rec in idx.all_attrs("M").items()}
    assert got == {"x": ("Int", "T"), "y": ("Bool", "M")}
    assert idx.linearize("M") == ["B", "T", "M"]
    assert idx.ancestors("M") == ["M", "T", "B"]
    assert idx.declaring("M", "x") == "T"


def test_the_api_index_never_lets_a_plain_is_undo_a_becomes():
    idx = index({
        "B": {"k": "m", "a": {"body": attr("Physics3D.Bodies.Body")}},
        "Heavy": {"k": "t", "a": {"body": attr("Physics3D.Bodies.RigidBody", "b")}},
        "Host": {"k": "m", "b": "B", "w": ["Heavy"], "a": {"body": attr("Physics3D.Bodies.Body")}},
    })
    assert idx.declaring("Host", "body") == "Heavy"


def test_the_api_index_cuts_an_inheritance_cycle():
    idx = index({"A": {"k": "m", "b": "B", "a": {"a": attr("Real")}},
                 "B": {"k": "m", "b": "A", "a": {"b": attr("Real")}}})
    assert set(idx.all_attrs("A")) <= {"a", "b"} and "a" in idx.all_attrs("A")
    assert "B" in idx.ancestors("A")


def test_the_stored_index_of_the_installed_bundles_agrees_with_the_resolver(workspace):
    """Every model of the installed bundles: the index's attributes and where each is declared are
    what Program.all_members (model/resolve.py) computes now from the bundle sources."""
    version = metadata.version("openplx-bundles")
    if version not in versions():
        pytest.skip(f"installed bundles {version} are not indexed")
    idx = load(version)
    p = workspace.program
    compared = 0
    stack = [p.root]
    while stack:
        ns = stack.pop()
        stack.extend(ns.children.values())
        for sym in ns.symbols.values():
            if sym.qname not in idx.models or not hasattr(sym, "members"):
                continue
            fresh = {name: mem.owner.qname for name, mem in p.all_members(sym).items()}
            stored = {name: rec[4] for name, rec in idx.all_attrs(sym.qname).items()}
            assert stored == fresh, sym.qname
            compared += 1
    assert compared > 300
