"""A model contains itself, directly (`Wheel` with `spare is Wheel`) or through others (`A` holds a
`B` that holds an `A`): `plx lint` reports it at the attribute that closes the ring, and `plx check`
then builds the model without the ring (no follow-on findings). `plx check` also stops distinct
models nested more than 500 levels deep (its nesting limit, not a ring) and says so.

## Why it matters

Instantiating such a model never ends: each `Wheel` makes a `spare`, which is a `Wheel`, which
makes a `spare`... The runtime stops at a depth limit or runs out of memory, and `plx check`
reports the truncated objects. The fix is at one line: the attribute that makes the ring.

## Example

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    spare is Wheel
```

## Use instead

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    inertia.mass: 10

Truck is Physics3D.System:
    wheel is Wheel
    spare is Wheel
```
"""

from __future__ import annotations

from plxtools.model.symbols import MemberSym, ModelSym
from plxtools.syntax import ast


# A ring runs through other statements' models, and judged one statement at a time a moved
# statement lost its ring (the long re-use campaign, 3 case files): judged on the whole file.
WHOLE_FILE = True


def check(facts, report) -> None:
    program, unit = facts.program, facts.unit
    if unit.official:
        return
    for stmt in facts.judged:
        if not isinstance(stmt, ast.Declaration) or not stmt.body:
            continue
        model = _top_model(program, unit, stmt)
        if model is None:
            continue
        ring = _ring_from(program, model)
        if ring is None or _found_earlier(program, unit, stmt, ring):
            continue
        _report(report, program, unit, model, ring)


def _found_earlier(program, unit, stmt, ring) -> bool:
    """Whether a model of the ring defined by an earlier top-level statement finds the same ring
    (it reports it: one finding per ring). Asked of the models themselves, not of what an earlier
    statement reported, so each statement can be judged alone (the language server does)."""
    key = frozenset(id(m) for m, _mem in ring)
    for m, _mem in ring:
        if m.unit is not unit or m.anonymous or m.stmt is None or m.stmt.span.start.offset >= stmt.span.start.offset \
                or not isinstance(m.stmt, ast.Declaration) or not m.stmt.body or _top_model(program, unit, m.stmt) is not m:
            continue
        other = _ring_from(program, m)
        if other is not None and frozenset(id(x) for x, _mem in other) == key:
            return True
    return False


def _top_model(program, unit, stmt) -> ModelSym | None:
    found = program.lookup([p.name for p in stmt.path.parts], unit)
    return found if isinstance(found, ModelSym) and not found.is_trait and found.stmt is stmt else None


def _owned(program, model: ModelSym):
    """(member, its named model) for each object `model` owns (not references, not optional)."""
    for mem in program.all_members(model).values():
        if mem.reference or mem.optional or mem.value is not None:
            continue
        ty = program.member_type(mem)
        if ty.model is None or ty.array or ty.alts or ty.model.is_trait:
            continue
        target = program.concrete(ty.model)
        if target.unit is None or target.unit.official or target.const:
            continue
        yield mem, target


def _ring_from(program, start: ModelSym) -> list[tuple[ModelSym, MemberSym]] | None:
    """The ring of (model, member) from `start` back to `start`, if its owned objects lead back."""
    stack = [(start, [])]
    seen = {id(start)}
    while stack:
        model, trail = stack.pop()
        for mem, target in _owned(program, model):
            step = trail + [(model, mem)]
            if target is start:
                return step
            if id(target) not in seen:
                seen.add(id(target))
                stack.append((target, step))
    return None


def _report(report, program, unit, model: ModelSym, ring) -> None:
    first_model, mem = ring[0]
    names = " -> ".join([m.name for m, _x in ring] + [model.name])
    at = mem.stmt.header if mem.owner.unit is unit else unit.tree.statements[0].header
    for m, x in ring:  # blame the attribute written in this file, the first one of the ring
        if x.owner.unit is unit:
            at, mem = x.stmt.header, x
            break
    ty = program.concrete(program.member_type(mem).model)
    report(f"{model.name} contains itself ({names}): '{mem.name}' is a {ty.name}, which holds another "
           f"{'one' if len(ring) == 1 else model.name}, without end", at,
           help=f"a model cannot own an instance of itself: give '{mem.name}' another model, or declare it in "
                f"the system that holds {model.name}")
