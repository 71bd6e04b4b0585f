"""What the registry says is what every command prints (issue 38): a code's severity, in `plx lint`,
`plx check` and the language server, and which of two findings of one fault on a line stands (`owns`).

Each test changes one entry of the registry (a rule raised by the model, one raised by check's
evaluation, one in the module form) and reads what the surfaces print."""

from __future__ import annotations

from dataclasses import replace

import pytest

from plxtools.diagnostics import Severity
from plxtools.ide import AnalysisHost
from plxtools.rules import registry
from tests.conftest import plx_here

REAL_FOR_INT = "A is Physics3D.Bodies.RigidBody:\n    count is Int: 2.5\n"
TWO_MATES = """Car is Physics3D.System:
    chassis is Physics3D.Bodies.RigidBody:
        inertia.mass: 1
        left is Physics3D.Interactions.MateConnector
        right is Physics3D.Interactions.MateConnector
    left_wheel is Physics3D.Bodies.RigidBody:
        inertia.mass: 1
        connector is Physics3D.Interactions.MateConnector
    right_wheel is Physics3D.Bodies.RigidBody:
        inertia.mass: 1
        connector is Physics3D.Interactions.MateConnector
    left_hinge is Physics3D.Interactions.Hinge:
        connectors: [chassis.left, right_wheel.connector]
    right_hinge is Physics3D.Interactions.Hinge:
        connectors: [chassis.right, right_wheel.connector]
"""
NO_VALUE = """const Sizes:
    radius is Real

Scene is Physics3D.System:
    ball is Physics3D.Bodies.RigidBody:
        inertia.mass: 1
        geometry is Physics3D.Geometries.Sphere:
            radius: Sizes.radius
"""


def set_severity(monkeypatch, code: str, severity: Severity) -> None:
    rule = registry.get(code)
    assert rule is not None and rule.severity is not severity
    monkeypatch.setitem(registry.RULES, code, replace(rule, severity=severity))


def reported(out: str, code: str) -> set[str]:
    return {line.split()[1] for line in out.splitlines() if f" {code} " in line and line.split()[1:2]}


def server_severities(path, text: str, code: str) -> set[Severity]:
    host = AnalysisHost()
    host.open_document(str(path), text, 1)
    try:
        return {d.severity for d in host.state(str(path)).diagnostics if d.code == code}
    finally:
        host.close_document(str(path))


@pytest.mark.parametrize("code, text", [("T002", REAL_FOR_INT), ("A043", TWO_MATES)], ids=["model", "module"])
def test_lint_and_server_print_the_registry_severity(monkeypatch, tmp_path, code, text):
    path = tmp_path / "m.openplx"
    path.write_text(text, encoding="utf-8")
    before = registry.get(code).severity
    assert reported(plx_here("lint", "--no-cache", str(path)).stdout, code) == {before.value}
    assert server_severities(path, text, code) == {before}
    after = Severity.INFO if before is not Severity.INFO else Severity.ERROR
    set_severity(monkeypatch, code, after)
    assert reported(plx_here("lint", "--no-cache", str(path)).stdout, code) == {after.value}
    assert server_severities(path, text, code) == {after}


@pytest.mark.parametrize("code, text", [
    ("T002", REAL_FOR_INT),  # a fact of the model (model/facts.py) reported by rules/types/real_for_int.py
    ("M001", "A is Physics3D.Bodies.RigidBody:\n    is_dynamic is Bool: true\n"),  # rules/structure/
    ("N004", "A is Physics3D.Bodies.RigidBody:\n    m is Real: inertia.mass.x\n"),  # rules/names/
], ids=["T002", "M001", "N004"])
def test_a_moved_rule_prints_the_registry_severity_in_lint_check_and_the_server(monkeypatch, tmp_path, code, text):
    """The model records a fact and a rule module reports it: the severity is the registry's
    alone, in `plx lint`, `plx check` and the server alike."""
    path = tmp_path / "m.openplx"
    path.write_text(text, encoding="utf-8")
    before = registry.get(code).severity
    assert registry.get(code).module is not None
    assert reported(plx_here("lint", "--no-cache", str(path)).stdout, code) == {before.value}
    assert reported(plx_here("check", str(path)).stdout, code) == {before.value}
    assert server_severities(path, text, code) == {before}
    after = Severity.INFO if before is not Severity.INFO else Severity.ERROR
    set_severity(monkeypatch, code, after)
    assert reported(plx_here("lint", "--no-cache", str(path)).stdout, code) == {after.value}
    assert reported(plx_here("check", str(path)).stdout, code) == {after.value}
    assert server_severities(path, text, code) == {after}


def test_check_prints_the_registry_severity(monkeypatch, tmp_path):
    path = tmp_path / "m.openplx"
    path.write_text(NO_VALUE, encoding="utf-8")
    assert reported(plx_here("check", str(path)).stdout, "A004") == {"error"}
    set_severity(monkeypatch, "A004", Severity.WARNING)
    r = plx_here("check", str(path))
    assert reported(r.stdout, "A004") == {"warning"}
    assert "Found 1 error" not in r.stdout


def test_a_code_another_owns_is_not_reported_on_its_line(monkeypatch):
    """connectors.openplx line 32: check's A013 (the mate has one connector) beside lint's A043 (its
    connector is another mate's). Two faults, so both stand; once the registry says A043 owns A013,
    only A043 is reported there, and A013 elsewhere is untouched."""
    case = "tests/cases/check/connectors.openplx"
    on_32 = lambda out: {ln.split()[2] for ln in out.splitlines() if ln.startswith(f"{case}:32:")}  # noqa: E731
    before = plx_here("check", case).stdout
    assert on_32(before) == {"A013", "A043"}, before
    rule = registry.get("A043")
    monkeypatch.setitem(registry.RULES, "A043", replace(rule, owns=rule.owns + ("A013",)))
    after = plx_here("check", case).stdout
    assert on_32(after) == {"A043"}, after
    assert len(after.splitlines()) == len(before.splitlines()) - 2  # the A013 line and its help line


def test_an_owner_stands_only_when_at_least_as_grave():
    """S003 owns A004 (a block that did not parse explains a missing value), but a tab's warning on
    the declaration's line does not hide the missing value's error; the tab's error form does."""
    from plxtools.diagnostics import EMPTY_SPAN, Diagnostic
    from plxtools.rules.consequences import drop_owned

    def on_line(code: str, severity: Severity) -> Diagnostic:
        return Diagnostic(code, "", EMPTY_SPAN, severity, file="m.openplx")

    assert "A004" in registry.get("S003").owns
    missing = on_line("A004", Severity.ERROR)
    assert missing in drop_owned([on_line("S003", Severity.WARNING), missing])
    assert missing not in drop_owned([on_line("S003", Severity.ERROR), missing])
