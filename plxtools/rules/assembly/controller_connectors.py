"""A controller (a motor, range or spring: any `Physics.Interactions.Interaction1DOF`) names the
connectors of a mate that another controller of its kind already drives, while a mate of the same
kind in the same block has none (A046, at the controller whose name is closer to the idle mate,
with that mate's connectors as the fix). And a mate or a 1-DOF controller that does not have
exactly two MateConnectors (A013): `plx lint` reports one declared with no `connectors` at all, at
its declaration, with the connectors of the mate in its block whose name is closest; `plx check`
reports the other counts.

## Why it matters

Both slips load and run without an error: a hinge with two motors is driven twice as hard (or the
two fight), the hinge that was meant to be driven turns freely, and a controller without
connectors drives nothing. The truck then pulls to one side or does not move, and nothing says why.

## Example

```openplx
    front_left_motor is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: front_left_hinge.connectors
    front_right_motor is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: front_left_hinge.connectors
```

## Use instead

```openplx
    front_left_motor is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: front_left_hinge.connectors
    front_right_motor is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: front_right_hinge.connectors
```
"""

from __future__ import annotations

import bisect
import difflib

from plxtools.diagnostics import Severity
from plxtools.model.symbols import ModelSym
from plxtools.rules.blocks import declaration_blocks, likeliest_meant
from plxtools.syntax import ast

OTHER_MATE, COUNT = "controller-on-other-mate", "connector-count"
CONTROLLER = ("Physics", "Interactions", "Interaction1DOF")
MATE = ("Physics3D", "Interactions", "Mate")


def check(facts, report) -> None:
    """A declaration with an error in its block (a misspelt or renamed `connectors`) is not also
    said to have none."""
    program, unit = facts.program, facts.unit
    found = list(facts.tree.diagnostics) + list(facts.analysis.diagnostics)
    if unit.official:
        return
    controller = program.lookup_outside_visibility(list(CONTROLLER))
    mate = program.lookup_outside_visibility(list(MATE))
    if not isinstance(controller, ModelSym) or not isinstance(mate, ModelSym):
        return
    assigned = facts.table_of_statements("assigned connectors", _assigned_connectors)
    errors = sorted(d.span.start.offset for d in found if d.severity is Severity.ERROR)
    out = report
    for _owner, body in declaration_blocks(facts.judged):
        _one_block(program, unit, controller, mate, body, assigned, out, errors)


CONNECTOR_ATTRS = ("connectors", "charges")  # (`charges` until OpenPLX 0.18)


def _assigned_connectors(top: ast.Stmt) -> set[str]:
    """The names whose `connectors` a top-level statement assigns from outside
    (`motor.connectors: ...`)."""
    out = set()
    for s in ast.walk_statements([top]):
        parts = [p.name for p in s.path.parts] if isinstance(s, (ast.Assignment, ast.Declaration)) else []
        if len(parts) >= 2 and parts[-1] in CONNECTOR_ATTRS:
            out.add(parts[-2])
    return out


def _connectors(stmt: ast.Declaration, attr: str = "connectors"):
    for s in stmt.body or []:
        if isinstance(s, (ast.Assignment, ast.Declaration)) and [p.name for p in s.path.parts] == [attr]:
            return s
    return None


def _text(unit, node) -> str:
    return "".join(unit.tree.text[node.span.start.offset:node.span.end.offset].split())


def family(program, model: ModelSym, controller: ModelSym) -> ModelSym | None:
    """The controller family of `model`: its ancestor right below Interaction1DOF (VelocityMotor,
    RangeInteraction1DOF, SpringInteraction1DOF, TorqueMotor, ...)."""
    chain = [model] + [m for m in program.ancestors(model) if isinstance(m, ModelSym)]
    for m in chain:
        base = program.base_of(m)
        if base is not None and base.model is controller:
            return m
    return None


def _connectors_attr(program, model: ModelSym) -> str | None:
    """What the bundles in use call `model`'s connectors: `connectors`, or `charges` before 0.18."""
    layers = program.linearize(model)
    return next((a for a in CONNECTOR_ATTRS if any(a in layer.members for layer in layers)), None)


def _sets_connectors(program, model: ModelSym, attr: str) -> bool:
    for layer in program.linearize(model):
        if attr in layer.members and layer.members[attr].value is not None:
            return True
        for a in layer.assignments:
            if a.path.parts and a.path.parts[0].name == attr:
                return True
    return False


def _one_block(program, unit, controller, mate, body, assigned, out, errors) -> None:
    mates: dict[str, tuple[ast.Declaration, ModelSym, str]] = {}  # name -> (stmt, model, connectors text)
    ctrls: list[tuple[ast.Declaration, ModelSym, object]] = []
    for s in body:
        if not isinstance(s, ast.Declaration) or s.keyword != "is" or len(s.path.parts) != 1 or s.type is None:
            continue
        ty = program.resolve_type_expr(s.type, unit)
        model = ty.model
        if model is None or ty.array:
            continue
        is_mate = program.is_subtype(model, mate)
        is_ctrl = not is_mate and program.is_subtype(model, controller)
        if not (is_mate or is_ctrl):
            continue
        attr = _connectors_attr(program, model)
        if attr is None:
            continue
        conn = _connectors(s, attr)
        name = s.path.parts[0].name
        if conn is None and name not in assigned and not _has_error(s, errors) and not _sets_connectors(program, model, attr):
            _no_connectors(out, s, name, is_ctrl, mates, attr)
            continue
        if is_mate:
            mates[name] = (s, program.concrete(model), _text(unit, conn.value) if conn and conn.value else "")
        elif conn is not None and conn.value is not None:
            ctrls.append((s, family(program, model, controller), conn, program.concrete(model).name))
    _shared(unit, mates, ctrls, out)


def _has_error(s, errors: list[int]) -> bool:
    i = bisect.bisect_left(errors, s.span.start.offset)
    return i < len(errors) and errors[i] <= s.span.end.offset


def _no_connectors(report, s, name: str, is_ctrl: bool, mates, attr: str = "connectors") -> None:
    what = "controller" if is_ctrl else "mate"
    if is_ctrl and mates:
        near = max(mates, key=lambda m: difflib.SequenceMatcher(None, name, m).ratio())
        help_ = f"give it the connectors of the mate it drives: {attr}: {near}.{attr}"
    elif is_ctrl:
        help_ = f"give it the connectors of the mate it drives: {attr}: some_hinge.{attr}"
    else:
        help_ = f"give it one connector on each of the two bodies it joins: {attr}: [a.connector, b.connector]"
    report(f"{what} '{name}' has no connectors, so it {'drives' if is_ctrl else 'joins'} nothing", s.header,
           help=help_, rule=COUNT)


def _mate_of(unit, conn, mates) -> str | None:
    """The mate whose connectors a controller's `connectors:` names (`hinge.connectors` or the list)."""
    v = conn.value
    if isinstance(v, ast.Member) and v.name.name == "connectors" and isinstance(v.obj, ast.Name):
        return v.obj.ident.name if v.obj.ident.name in mates else None
    text = _text(unit, v)
    for name, (_s, _m, ctext) in mates.items():
        if ctext and (ctext == text or sorted(ctext.strip("[]").split(",")) == sorted(text.strip("[]").split(","))):
            return name
    return None


def _shared(unit, mates, ctrls, out) -> None:
    on: dict[tuple[int, str], list] = {}  # (family, mate) -> [(stmt, conn)]
    names: dict[int, str] = {}
    for s, fam, conn, kind_name in ctrls:
        m = _mate_of(unit, conn, mates)
        if m is not None and fam is not None:
            on.setdefault((id(fam), m), []).append((s, conn))
            names[id(s)] = kind_name
    for (fam, m), uses in on.items():
        if len(uses) < 2:
            continue
        kind = mates[m][1]
        idle = [n for n, (_s, k, _t) in mates.items() if k is kind and (fam, n) not in on]
        if not idle:
            continue
        s, conn, meant = _blame(uses, m, idle)
        other = next(o for o, _c in uses if o is not s)
        line = other.header.start.line + 1
        fam_name = names[id(s)]
        help_ = (f"did you mean connectors: {meant}.connectors? (no {fam_name} drives '{meant}')"
                 if meant else f"give it the connectors of the mate it should drive (no {fam_name} drives "
                               f"{', '.join(idle)})")
        idle_text = f"'{meant}'" if meant else ", ".join(f"'{n}'" for n in idle)
        out(f"'{s.path.text}' drives '{m}', which '{other.path.text}' (line {line}) already drives, while "
            f"{idle_text} {'gets' if meant or len(idle) == 1 else 'get'} no {fam_name}", conn.value.span, help=help_,
            related=[(unit.path, other.header, f"'{other.path.text}' also drives '{m}'")], rule=OTHER_MATE)


def _blame(uses, mate: str, idle: list[str]):
    found = likeliest_meant(uses, mate, idle)
    if found is not None:
        (s, conn), meant = found
        return s, conn, meant
    s, conn = uses[-1]
    return s, conn, idle[0] if len(idle) == 1 else None
