"""An angle is more than one full turn (2 pi): a number written for any angle-taking function
argument or attribute of the bundles (`Math.Quat.angle_axis(90, ...)`, `from_euler_angles(...)`,
`initial_angle`, a rotational range's ends), reported by `plx lint` at the number; and, by
`plx check`, a computed initial angle or rotational range end. A rotational motor's target speed
above one turn per second is only an info (a wheel of 0.3 m at 10 m/s turns at 33 rad/s). Which
values are angles is read from the bundles (names and documentation); the plausibility model is in
docs/plausibility.md.

## Why it matters

OpenPLX angles are radians. A value such as 90 is likely meant in degrees: as radians it is 14
turns and 116.6 degrees, a pose wrong by an odd amount that looks like another bug (a truck that
starts skewed, a joint that starts beyond its limit). `Math.Functions.deg_to_rad(90)` converts it.

## Example

```openplx
Scene is Physics3D.System:
    box is Physics3D.Bodies.RigidBody:
        kinematics.local_transform.rotation: Math.Quat.angle_axis(90, Math.Vec3.Z_AXIS())
```

## Use instead

```openplx
Scene is Physics3D.System:
    box is Physics3D.Bodies.RigidBody:
        kinematics.local_transform.rotation: Math.Quat.angle_axis(Math.PI / 2, Math.Vec3.Z_AXIS())
```
"""

# Which values are angles (read from the bundle sources, not a list of call sites): a `Real`
# parameter of a function is an angle when the parameter's name says so (`angle`), when the
# function's name does (`from_euler_angles_xyz(alpha, beta, gamma)`, `from_angle(v, ...)`) or when
# its type's does (`AngleValue.create(value)`); a `Real` attribute is an angle when its name says so
# (`initial_angle`, `knuckle_angle`), when its documentation speaks of radians, or when it is the
# `start` or `end` of a range whose type is rotational (`RotationalRange`). Plausibility: more than
# one full turn is suspicious (poses, initial angles and joint limits lie within one turn; 90, 45,
# 180, 360 are the sizes people write in degrees). Only numbers the file writes are judged; a value
# between 1 and 6.28 is a plausible angle in either unit and is left alone.

from __future__ import annotations

import math
import re

from plxtools.diagnostics import Edit, Fix
from plxtools.model.symbols import MemberSym, MethodSym, ModelSym
from plxtools.rules.literals import literal
from plxtools.syntax import ast

FULL_TURN = 2 * math.pi
_ANGLE_WORDS = frozenset({"angle", "angles", "euler", "yaw", "pitch", "roll"})
_RANGE_ENDS = frozenset({"start", "end"})


def words(name: str) -> set[str]:
    """`from_euler_angles_xyzs` -> {from, euler, angles, xyzs}; `AngleValue` -> {angle, value}."""
    return {w.lower() for w in re.findall(r"[A-Z]?[a-z]+|[A-Z]+(?![a-z])|\d+", name)}


def angle_parameter(method: MethodSym, index: int, program) -> bool:
    """Whether the `index`-th parameter of `method` is an angle in radians (its names say so)."""
    params = method.stmt.params
    if index >= len(params) or params[index].type.name.parts[-1].name != "Real" or params[index].type.array:
        return False
    return bool(words(params[index].name.name) & _ANGLE_WORDS or words(method.name) & _ANGLE_WORDS
                or words(method.owner.name) & _ANGLE_WORDS)


def angle_attribute(member: MemberSym, program, block: ModelSym | None = None) -> bool:
    """Whether `member` holds an angle in radians (its name, its documentation or its range says
    so); `block`: the model of the block the value is written in (a RotationalRange's `start`)."""
    ty = program.member_type(member)
    if ty.primitive != "Real" or ty.array:
        return False
    if words(member.name) & _ANGLE_WORDS or "radian" in (member.doc or "").lower():
        return True
    if member.name in _RANGE_ENDS and block is not None:
        return any("rotational" in words(m.name) and "range" in words(m.name)
                   for m in program.linearize(block) if isinstance(m, ModelSym))
    return False


def _targets(occurrences) -> dict:
    return {(o.span.start.offset, o.span.end.offset): o.target for o in occurrences
            if o.kind in ("attribute", "definition", "name")}


def check(facts, report) -> None:
    program = facts.program
    target = None
    models: dict = {}
    for node, block in _walk(facts.judged):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Member):
            big = [(i, a) for i, a in enumerate(node.args) if _too_big(a)]
            if not big:
                continue
            target = target if target is not None else _targets(facts.occurrences)
            meth = target.get((node.func.name.span.start.offset, node.func.name.span.end.offset))
            if isinstance(meth, MethodSym):
                for i, a in big:
                    if angle_parameter(meth, i, program):
                        name = meth.stmt.params[i].name.name
                        _report(report, a, f"argument '{name}' of {meth.owner.name}.{meth.name}")
        elif isinstance(node, (ast.Assignment, ast.Declaration)) and node.value is not None and _too_big(node.value):
            target = target if target is not None else _targets(facts.occurrences)
            last = node.path.parts[-1]
            mem = target.get((last.span.start.offset, last.span.end.offset))
            if isinstance(mem, MemberSym) and angle_attribute(mem, program, _model_of(block, program, facts.unit, models)):
                _report(report, node.value, f"'{node.path.text}'")


def _too_big(expr) -> bool:
    v = literal(expr)
    return isinstance(v, float) and abs(v) > FULL_TURN


def _report(report, expr, what: str) -> None:
    v = literal(expr)
    turns = abs(v) / FULL_TURN
    rad = math.radians(v)
    fix = Fix(f"read {v:g} as degrees", (Edit(expr.span.start.offset, expr.span.end.offset,
                                                f"Math.Functions.deg_to_rad({v:g})"),), safe=False)
    report(f"{what} is {v:g} rad ({turns:.1f} turns): angles are in radians, so {v:g} looks like degrees",
           expr.span, help=f"if it is {v:g} degrees, write Math.Functions.deg_to_rad({v:g}) (= {rad:.4g} rad)", fix=fix)


def _model_of(decl, program, unit, models: dict):
    """The model a block's declaration makes (resolved only for the few numbers judged)."""
    if decl is None:
        return None
    if id(decl) not in models:
        models[id(decl)] = program.resolve_type_expr(decl.type, unit).model
    return models[id(decl)]


def _walk(statements: list):
    """(node, the declaration of the block its statement is in) for every statement and
    expression node below `statements`, without recursion."""
    stack: list = [(s, None) for s in statements]
    while stack:
        node, block = stack.pop()
        yield node, block
        if isinstance(node, ast.Stmt):
            inner = block
            if isinstance(node, ast.Declaration) and node.body and node.type is not None:
                inner = node
            stack.extend((s, inner) for s in ast.body_of(node) or ())
            v = getattr(node, "value", None)
            if v is not None:
                stack.append((v, block))
            continue
        stack.extend((child, block) for child in _children(node))


def _children(node) -> tuple:
    if isinstance(node, ast.Call):
        return (node.func, *node.args)
    if isinstance(node, ast.Member):
        return (node.obj,)
    if isinstance(node, (ast.Brace, ast.Array)):
        return tuple(node.items)
    if isinstance(node, ast.Binary):
        return (node.left, node.right)
    if isinstance(node, ast.Unary):
        return (node.operand,)
    if isinstance(node, ast.Paren):
        return (node.inner,)
    if isinstance(node, ast.Index):
        return (node.obj, node.index)
    return ()
