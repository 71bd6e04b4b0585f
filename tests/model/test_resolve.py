"""The one resolver (plxtools/model/resolve.py): class ordering, override rule, deep chains."""

from plxtools.model import resolve
from plxtools.rules.analysis import analyse_file
from plxtools.syntax import parse_text


def analyse(workspace, text: str, name: str):
    tree = parse_text(text, f"/tmp/plx-resolver-tests/{name}.openplx")
    result = analyse_file(workspace, tree)
    return result, result.unit


def model(unit, name):
    return unit.locals[name]


def test_a_deep_chain_inherits_every_member_and_has_no_cycle(workspace):
    n = 3000
    lines = ["A0:", "    x0 is Real: 0"] + [f"A{i} is A{i - 1}:\n    x{i} is Real: {i}" for i in range(1, n)]
    result, unit = analyse(workspace, "\n".join(lines) + "\n", "deep_chain")
    assert [d.code for d in result.diagnostics if d.severity.name == "ERROR"] == []
    p = workspace.program
    last = model(unit, f"A{n - 1}")
    members = p.all_members(last)
    assert len(members) == n
    assert members["x0"].owner is model(unit, "A0")
    assert p.has_cycle(last) is None
    assert len(p.linearize(last)) == n
    assert p.is_subtype(last, model(unit, "A0"))
    assert not p.is_subtype(model(unit, "A0"), last)


def test_a_deep_chain_that_closes_into_a_ring_reports_the_ring_once_per_member(workspace):
    n = 2000
    lines = ["A0 is A1999"] + [f"A{i} is A{i - 1}" for i in range(1, n)] + ["B is A5"]
    result, unit = analyse(workspace, "\n".join(lines) + "\n", "deep_ring")
    cycles = [d for d in result.diagnostics if d.code == "M005"]
    assert len(cycles) == n + 1  # every model of the ring, and B that runs into it
    ring = workspace.program.has_cycle(model(unit, "A7"))
    assert ring[0] is ring[-1] is model(unit, "A7") and len(ring) == n + 1
    into = workspace.program.has_cycle(model(unit, "B"))
    assert into[0] is into[-1] is model(unit, "A5")


SPECIALISE = """
trait Heavy:
    body becomes Physics3D.Bodies.RigidBody

Base:
    body is Physics3D.Bodies.Body

Car is Base:
    with Heavy

Host:
    body is Physics3D.Bodies.Body
    with Heavy
"""


def test_a_trait_becomes_overrides_the_base_and_the_host(workspace):
    result, unit = analyse(workspace, SPECIALISE, "specialise")
    p = workspace.program
    heavy = model(unit, "Heavy")
    # one rule everywhere: a `becomes` is never undone by a plain `is`, whichever layer it is in
    assert p.all_members(model(unit, "Car"))["body"].owner is heavy
    assert p.inherited_members(model(unit, "Car"))["body"].owner is heavy
    assert p.all_members(model(unit, "Host"))["body"].owner is heavy
    names = [m.name for m in p.linearize(model(unit, "Car"))]
    assert names[-2:] == ["Heavy", "Car"] and names.index("Base") < names.index("Heavy")
    assert resolve.replaces("is", "becomes") and resolve.replaces("becomes", "becomes")
    assert not resolve.replaces("becomes", "is")
    assert [d.code for d in result.diagnostics if d.severity.name == "ERROR"] == []


def test_inline_traits_are_later_layers_than_the_type(workspace):
    text = SPECIALISE + "\nScene:\n    c is Base with Heavy\n"
    _result, unit = analyse(workspace, text, "inline")
    p = workspace.program
    c = p.all_members(model(unit, "Scene"))["c"]
    ty = p.member_type(c)
    assert p.members_of(ty)["body"].owner is model(unit, "Heavy")
