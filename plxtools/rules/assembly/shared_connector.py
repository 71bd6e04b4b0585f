"""Two mates in one model name the same connector: the second can only close by moving the body
the first one places. Reported by `plx lint` at the mate that is most likely wrong: when another
body of the same type has that connector unused and the mate's name is closer to that body, that
mate, with the connector it probably meant; otherwise the later mate. And a mate whose two
connectors belong to the same body (A015): `plx lint` reports it at the second connector when the
file says so (`[chassis.a, chassis.b]`), with the unused connector of a sibling it most likely
meant, and does not count it as holding either connector; `plx check` reports the cases only the
assembled scene shows (both on the world or on one system).

## Why it matters

A connector is one frame on one body, and a mate ties two frames together. Copying a hinge line
and changing only one side leaves a wheel held by two hinges (at two places) and another wheel
held by none: `plx check` then reports the consequences elsewhere (A016 on the other hinge, A037
for the loose wheel) and the simulation drags the body away. Motors, springs and ranges use a
mate's connectors on purpose; they are not mates and are not counted.

## Example

```openplx
front_left_hinge is Physics3D.Interactions.Hinge:
    connectors: [chassis.front_left_connector, front_right_wheel.connector]
front_right_hinge is Physics3D.Interactions.Hinge:
    connectors: [chassis.front_right_connector, front_right_wheel.connector]
```

## Use instead

```openplx
front_left_hinge is Physics3D.Interactions.Hinge:
    connectors: [chassis.front_left_connector, front_left_wheel.connector]
front_right_hinge is Physics3D.Interactions.Hinge:
    connectors: [chassis.front_right_connector, front_right_wheel.connector]
```
"""

# How the blame is decided (issue 32.3). A mate connector is one frame on one body; a mate ties
# two of them together. When a second mate names a connector another mate already uses, the body
# behind it is placed by the first mate. Which of the two mates is the mistake is decided by names,
# as a reader would: when another body of the same type has the same connector unused, and one
# mate's name is closer to that body's name than to the one it uses, that mate is blamed, with the
# connector it most likely meant. Otherwise the later mate is. The mates are the declarations whose
# type is a Physics3D.Interactions.Mate with a `connectors: [a, b]` list in their block, compared
# within one model's block. Whole file on every analysis: cheap, so the server never re-uses it.

from __future__ import annotations

import difflib

from plxtools.diagnostics import Edit, Fix
from plxtools.model.symbols import ModelSym
from plxtools.rules.blocks import declaration_blocks, likeliest_meant
from plxtools.syntax import ast

MATE = ("Physics3D", "Interactions", "Mate")
SHARED, SAME_BODY = "connector-used-by-two-mates", "mate-same-body"


def check(facts, report) -> None:
    program, unit = facts.program, facts.unit
    mate = program.lookup_outside_visibility(list(MATE))
    if not isinstance(mate, ModelSym):
        return
    for _owner, body in declaration_blocks(facts.judged):
        _one_block(program, unit, mate, body, report)


def _text(unit, node) -> str:
    return "".join(unit.tree.text[node.span.start.offset:node.span.end.offset].split())


def _connectors(stmt: ast.Declaration) -> list[ast.Expr] | None:
    for s in stmt.body or []:
        if (isinstance(s, ast.Assignment) and [p.name for p in s.path.parts] == ["connectors"]
                and isinstance(s.value, ast.Array)):
            return s.value.items
    return None


def _mates_of_block(program, unit, mate: ModelSym, body: list):
    """The block's mates with their connector lists, and each attribute's type as written (to find
    same-typed siblings)."""
    mates: list[tuple[ast.Declaration, list[ast.Expr]]] = []
    types: dict[str, str] = {}
    for s in body:
        if not isinstance(s, ast.Declaration) or s.keyword != "is" or len(s.path.parts) != 1:
            continue
        if s.type is not None:
            types[s.path.parts[0].name] = "".join(unit.tree.text[s.type.span.start.offset:s.type.span.end.offset].split())
        items = _connectors(s)
        if not items:
            continue
        ty = program.resolve_type_expr(s.type, unit)
        if ty.model is None or not program.is_subtype(ty.model, mate):
            continue
        mates.append((s, items))
    return mates, types


def _one_block(program, unit, mate: ModelSym, body: list, report) -> None:
    mates, types = _mates_of_block(program, unit, mate, body)
    mates = [m for m in mates if not _same_body(unit, m, types, mates, report)]
    used: dict[str, list[tuple[ast.Declaration, ast.Expr]]] = {}
    for s, items in mates:
        for e in items:
            used.setdefault(_text(unit, e), []).append((s, e))
    for conn, uses in used.items():
        if len({id(s) for s, _e in uses}) < 2 or "." not in conn:
            continue
        holder, member = conn.rsplit(".", 1)
        spare = [n for n, t in types.items() if n != holder and t == types.get(holder)
                 and f"{n}.{member}" not in used]
        blamed, meant = _blame(uses, holder, spare)
        for s, e in blamed:
            other = next(o for o, _x in uses if o is not s)
            line = other.header.start.line + 1
            help_ = (f"did you mean '{meant}.{member}'? ('{meant}' is a {types[holder]} that no mate holds)"
                     if meant else "each connector joins one mate: give this mate the connector of the body it "
                                   "should hold")
            fix = (Fix(f"use '{meant}.{member}'", (Edit(e.span.start.offset, e.span.end.offset,
                                                          f"{meant}.{member}"),), safe=False) if meant else None)
            report(f"'{conn}' is already used by mate '{other.path.text}' (line {line}): this mate "
                   f"can only close by moving '{holder}', which that mate places", e.span, help=help_, fix=fix,
                   rule=SHARED,
                   related=[(unit.path, other.header, f"'{conn}' is also used by '{other.path.text}'")])


def _same_body(unit, mate, types: dict[str, str], mates, report) -> bool:
    """A015 for a mate whose two connectors are on one body (`[chassis.a, chassis.b]`), with the
    connector it most likely meant: the same connector of a sibling that no mate holds yet."""
    s, items = mate
    texts = [_text(unit, e) for e in items]
    if len(texts) != 2 or not all("." in t for t in texts) or texts[0] == texts[1]:
        return False  # (one connector twice: A014's, plx check)
    holders = {t.rsplit(".", 1)[0] for t in texts}
    if len(holders) != 1:
        return False
    holder = holders.pop()
    used = {_text(unit, e) for _m, its in mates for e in its}
    # the connector other mates join to bodies of one type, on a sibling of that type no mate holds
    spare = []
    for _m, its in mates:
        for e in its:
            t = _text(unit, e)
            if "." in t and t.rsplit(".", 1)[0] != holder:
                h, member = t.rsplit(".", 1)
                spare += [f"{n}.{member}" for n, ty in types.items() if ty == types.get(h) and n != holder
                          and f"{n}.{member}" not in used]
    name = s.path.parts[0].name
    meant = max(spare, key=lambda c: difflib.SequenceMatcher(None, name, c.split(".")[0]).ratio()) if spare else None
    e = items[1]
    help_ = (f"did you mean '{meant}' for the second connector? (one connector on each body the mate joins)"
             if meant else "one connector must belong to each of the two bodies the mate joins")
    fix = (Fix(f"use '{meant}'", (Edit(e.span.start.offset, e.span.end.offset, meant),), safe=False) if meant else None)
    report(f"mate '{s.path.text}': both connectors belong to '{holder}', so it joins nothing", e.span, help=help_,
           fix=fix, rule=SAME_BODY)
    return True


def _blame(uses, holder: str, spare: list[str]):
    """The mates to report and the body they most likely meant (None: the later uses, no guess)."""
    found = likeliest_meant(uses, holder, spare)
    if found is not None:
        return [found[0]], found[1]
    return [(s, e) for s, e in uses if s is not uses[0][0]], None
