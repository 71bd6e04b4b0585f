"""Collecting check diagnostics for one file: location rules, severities from the rule catalogue,
and merging of the same finding repeated through a library model used several times."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from plxtools.check.instance import Obj
from plxtools.diagnostics import EMPTY_SPAN, Diagnostic, Severity, Span
from plxtools.syntax import ast
from plxtools.rules.registry import get


def _rule_severity(code: str) -> Severity:
    r = get(code)
    return r.severity if r is not None else Severity.WARNING


def span_of(node: Any) -> Span:
    if isinstance(node, ast.Stmt):
        return node.header
    return node.span


@dataclass(slots=True)
class Entry:
    diag: Diagnostic
    path: str | None


@dataclass
class Reporter:
    """Diagnostics of one checked file.  Every finding is placed on a line of *that* file: the
    statement that causes it when it is written there, otherwise the declaration (in that file)
    of the nearest enclosing object."""

    unit: Any
    file: str
    root_stmt: Any = None
    entries: list[Entry] = field(default_factory=list)
    skip_codes: frozenset[str] = frozenset()  # codes another owner (lint) already reports for this file
    # A023's motor pairs (paths) and its diagnostic: a later A106 on one of them refers to it
    mirrored_motors: list[tuple[str, str, Diagnostic]] = field(default_factory=list)

    def anchor(self, obj: Obj | None) -> Span:
        seen = 0
        while obj is not None and seen < 200:
            seen += 1
            if obj.decl is not None:
                t = obj.decl[0]
                if t.unit is self.unit:
                    return t.stmt.header
            elif obj.singleton and obj.model.unit is self.unit and obj.model.stmt is not None:
                return obj.model.stmt.header
            obj = obj.owner
        if self.root_stmt is not None:
            return self.root_stmt.header
        return EMPTY_SPAN

    def locate(self, node: Any = None, unit: Any = None, obj: Obj | None = None) -> Span:
        if node is not None and unit is self.unit:
            return span_of(node)
        return self.anchor(obj)

    def add(self, code: str, message: str, *, node: Any = None, unit: Any = None, obj: Obj | None = None,
            severity: Severity | str | None = None, help: str | None = None, path: str | None = None,
            span: Span | None = None) -> Diagnostic:
        if span is None:
            span = self.locate(node, unit, obj)
        if code in self.skip_codes:
            return Diagnostic(code, message, span, Severity.INFO, file=self.file, help=help)  # not reported
        if severity is None:
            sev = _rule_severity(code)
        else:
            sev = Severity(severity) if not isinstance(severity, Severity) else severity
        d = Diagnostic(code, message, span, sev, file=self.file, help=help)
        if path is None and obj is not None:
            path = obj.display
        self.entries.append(Entry(d, path))
        return d

    def has(self, code: str, path: str | None = None) -> bool:
        return any(e.diag.code == code and (path is None or e.path == path) for e in self.entries)

    def diagnostics(self) -> list[Diagnostic]:
        """Merged: one diagnostic per (code, place); repeats of the same finding on other objects
        (a library model used several times) are named in the first one's message."""
        groups: dict[tuple, list[Entry]] = {}
        order: list[tuple] = []
        for e in self.entries:
            key = (e.diag.code, e.diag.span.start.offset, e.diag.span.end.offset)
            if key not in groups:
                groups[key] = []
                order.append(key)
            g = groups[key]
            if any(x.diag.message == e.diag.message for x in g):
                continue
            g.append(e)
        out = []
        for key in order:
            g = groups[key]
            first = g[0].diag
            if len(g) > 1:
                others = [x.path or "?" for x in g[1:]]
                shown = ", ".join(others[:3]) + (", ..." if len(others) > 3 else "")
                first = Diagnostic(first.code, f"{first.message} (also {len(others)} more: {shown})", first.span,
                                   max((x.diag.severity for x in g), key=lambda s: s.rank), first.file,
                                   first.help, first.fix, first.related)
            out.append(first)
        return out
