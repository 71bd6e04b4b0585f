"""Style rules over the tree (C001, C006), kept per statement by the language server.

C003 and C007, which judge the whole file, are rule modules (semantic/unused_model.py,
semantic/root_not_system.py)."""

from __future__ import annotations

import re

from plxtools.diagnostics import Diagnostic, Severity
from plxtools.syntax import ast
from plxtools.rules import registry

PASCAL = re.compile(r"^[A-Z][A-Za-z0-9]*$")
SNAKE = re.compile(r"^[a-z_][a-z0-9_]*$")
UPPER = re.compile(r"^[A-Z][A-Z0-9_]*$")


def _block_column(body: list, parent_col: int) -> int:
    """The indentation a block means: the one most of its lines have; on a tie, the one a usual
    step (4 spaces) below its parent, else its first line's.  The odd lines are then the ones
    reported, so a first line 3 spaces short is flagged itself, not the correct line after it."""
    counts: dict[int, int] = {}
    for s in body:
        counts[s.header.start.column] = counts.get(s.header.start.column, 0) + 1
    best = max(counts.values())
    tied = [c for c, n in counts.items() if n == best]
    if len(tied) == 1:
        return tied[0]
    for c in tied:
        if c - parent_col == 4:
            return c
    return body[0].header.start.column


def style_diagnostics(unit) -> list[Diagnostic]:
    """Every style rule on a freshly analysed file (the language server re-runs the two halves
    separately: `style_of_statements` on the statements that changed, `style_of_file` always)."""
    return style_of_statements(unit) + style_of_file(unit)


def used_names(unit, occurrences) -> set[str]:
    """The file's top-level names that something in it names (what C003 needs of the occurrences;
    the server keeps the same set per statement)."""
    used = {id(o.target) for o in occurrences if o.kind != "definition"}
    return {name for name, sym in unit.locals.items() if id(sym) in used}


def _adder(out: list[Diagnostic], unit):
    def add(code, msg, span, sev, help_=None):
        out.append(Diagnostic(code, msg, span, sev, file=unit.path, help=help_))

    return add


def style_of_statements(unit, only: set[int] | None = None) -> list[Diagnostic]:
    """C006 inside each top-level statement and C001 of what it defines (`only`: these statements):
    what one statement's text alone decides, so the language server keeps it per statement."""
    out: list[Diagnostic] = []
    add = _adder(out, unit)
    caused = _caused(unit.tree)
    for i, top in enumerate(unit.tree.statements):
        if only is None or i in only:
            _misaligned_inside(top, caused, add)
            _naming(top, unit, add)
    return out


def _misaligned_inside(top, caused: set[int], add) -> None:
    """C006 in every block of one top-level statement: siblings whose indentation differs
    (official files do it; fmt aligns them)."""
    stack: list[tuple[list, int]] = []
    b = ast.body_of(top)
    if b:
        stack.append((b, top.header.start.column))
    while stack:
        body, parent_col = stack.pop()
        _misaligned(body, parent_col, caused, add)
        for s in body:
            b = ast.body_of(s)
            if b:
                stack.append((b, s.header.start.column))


def _naming(s, unit, add) -> None:
    """C001: naming conventions of the definitions one top-level statement makes."""
    if isinstance(s, ast.TraitDef) and not PASCAL.match(s.name.name):
        add(registry.NAMING_CONVENTION, f"trait name '{s.name.name}' should be PascalCase", s.name.span, Severity.INFO)
    elif isinstance(s, ast.Declaration) and len(s.path.parts) == 1:
        name = s.path.parts[0].name
        if name == "config" and unit.path.endswith("config.openplx"):
            return  # the language fixes this name
        is_global = s.keyword == "is" and s.value is not None and s.body is None
        if is_global:
            if not (SNAKE.match(name) or UPPER.match(name)):
                add(registry.NAMING_CONVENTION, f"global '{name}' should be snake_case or UPPER_CASE", s.path.span, Severity.INFO)
        elif not s.const and not PASCAL.match(name):
            add(registry.NAMING_CONVENTION, f"model name '{name}' should be PascalCase", s.path.span, Severity.INFO)
        for m in s.body or []:
            _attribute_naming(m, add)


def _attribute_naming(m, add) -> None:
    if isinstance(m, ast.Declaration) and m.keyword == "is" and len(m.path.parts) == 1:
        n = m.path.parts[0].name
        if not m.path.parts[0].backtick and not SNAKE.match(n):
            add(registry.NAMING_CONVENTION, f"attribute name '{n}' should be snake_case", m.path.span, Severity.INFO,
                _attribute_name_help(n))


def _attribute_name_help(name: str) -> str:
    """The snake_case spelling, and why keeping the name can be right: an attribute's name is the
    path scripts and scenarios use (`boxTruck.front_left_drive_motor` in the tutorial's step 11)."""
    snake = re.sub(r"(?<=[a-z0-9])([A-Z])", r"_\1", name).lower()
    return (f"'{snake}' follows the convention; scripts reach objects by these names, so to keep "
            "'" + name + f"' add '{registry.NAMING_CONVENTION}' to `ignore` in plx.toml (it is a convention, not an error)")


def _caused(tree) -> set[int]:
    """Lines where the parser already reported the cause of an odd indentation (S015, a tab)."""
    return {d.span.start.line for d in tree.diagnostics
            if d.code in (registry.TAB_INDENTATION, registry.INDENTATION_BETWEEN_LEVELS) and d.severity is Severity.ERROR}


def _misaligned(body: list, parent_col: int, caused: set[int], add) -> None:
    if not body:
        return
    col = _block_column(body, parent_col)
    for s in body:
        if s.header.start.column != col and s.header.start.line not in caused:
            add(registry.MISALIGNED_INDENTATION, f"this line is indented {s.header.start.column} spaces but the other lines "
                f"of its block are indented {col}", s.header, Severity.INFO,
                f"indent it {col} spaces; a missing ':' on the line above would also cause this "
                "(`plx fmt` aligns siblings)")


def style_of_file(unit) -> list[Diagnostic]:
    """C006 among the top-level statements: what depends on the whole file."""
    out: list[Diagnostic] = []
    add = _adder(out, unit)
    tree = unit.tree
    _misaligned(tree.statements, 0, _caused(tree), add)
    out.sort(key=lambda d: d.span.start.offset)
    return out
