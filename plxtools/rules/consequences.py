"""What a reader sees first: the cause, not what follows from it (issue 32).

A line indented between two levels (S015) or made ambiguous by a tab (S003) is read into a block
the author may not have meant, so what the model says about the names on that line (an attribute
missing from the block it landed in, a declaration that clashes there) follows from the layout,
not from the names. Those findings are dropped; the layout error on the line says what to fix,
and once it is fixed the line is checked again in the block it really belongs to.

Syntax and layout errors are listed before everything else, like a compiler's parse errors:
nothing below them can be trusted until they are fixed, and the first line printed is the cause.
"""

from __future__ import annotations

import difflib

from plxtools.diagnostics import Diagnostic, Severity, Span
from plxtools.rules import registry
from plxtools.syntax import ast

# layout errors that decide which block a line is read into (tagged so in the registry)
_LAYOUT = registry.tagged("layout")
# the model's findings that depend on the block a name stands in (names and structure)
_BLOCK_DEPENDENT = ("N", "M")


def drop_consequences(diags: list[Diagnostic]) -> list[Diagnostic]:
    """`diags` without the name and structure findings on a line whose block is a layout error."""
    lines = {(d.file, d.span.start.line) for d in diags
             if d.code in _LAYOUT and d.severity is Severity.ERROR}
    if not lines:
        return diags
    return [d for d in diags
            if not (d.code.startswith(_BLOCK_DEPENDENT) and (d.file, d.span.start.line) in lines)]


def drop_owned(diags: list[Diagnostic]) -> list[Diagnostic]:
    """`diags` without a finding whose code another finding on the same line owns (the registry's
    `owns`) and reports at least as gravely: one fault seen by a lint rule and a check rule is
    reported once, by its owner (a tab's warning does not hide a missing value's error)."""
    owners: dict[tuple, int] = {}
    for d in diags:
        for code in registry.owned_by((d.code,)):
            key = (d.file, d.span.start.line, code)
            owners[key] = max(owners.get(key, -1), d.severity.rank)
    if not owners:
        return diags
    return [d for d in diags if owners.get((d.file, d.span.start.line, d.code), -1) < d.severity.rank]


class Explained:
    """`explained(anchor, name)`: whether an error already reported in the declaration at `anchor`
    explains that its value `name` is missing (model/completeness.py asks): the block did not
    parse, or holds a misspelt attribute close to `name` (`raduis:` meant `radius:`)."""

    def __init__(self, tree: ast.File, causes: list[Diagnostic]):
        self.text = tree.text
        self.errors = [d for d in causes if d.severity is Severity.ERROR
                       and (d.code[0] == "S" or d.code == registry.UNKNOWN_ATTRIBUTE)]
        self.extent: dict[int, tuple[int, int]] = {}
        if self.errors:
            for st in ast.walk_statements(tree.statements):
                path = getattr(st, "path", None)
                if path is not None:
                    self.extent[path.span.start.offset] = (st.span.start.offset, st.span.end.offset)

    def __call__(self, anchor: Span, name: str) -> bool:
        if not self.errors:
            return False
        ext = self.extent.get(anchor.start.offset)
        if ext is None:
            return False
        for d in self.errors:
            if not ext[0] <= d.span.start.offset <= ext[1]:
                continue
            if d.code[0] == "S":
                return True  # the block did not parse: what it lacks follows from that
            written = self.text[d.span.start.offset:d.span.end.offset].split(".")[-1]
            if difflib.SequenceMatcher(None, written.lower(), name.lower()).ratio() >= 0.75:
                return True  # `raduis:` was meant to be `radius:`
        return False


def report_order(d: Diagnostic) -> tuple:
    """Sort key: per file, syntax and layout findings first, then the rest, each by position."""
    return (d.file, not d.code.startswith("S"), d.span.start.offset, d.code)
