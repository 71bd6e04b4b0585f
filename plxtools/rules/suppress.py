"""Inline suppression comments: `# plx: ignore[CODE, ...]` and `# plx: ignore-file[CODE, ...]`.

A trailing comment applies to its own line; a comment alone on a line applies to the next line
that holds code. Without a code list every code is suppressed. Suppressions that suppress nothing
are reported (C002) so they do not outlive the problem they hid.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from plxtools.diagnostics import Diagnostic, Edit, Fix, Severity
from plxtools.syntax import ast
from plxtools.rules import registry

# the code of an unused suppression, raised here; analysis.py, ide/ and lsp/ recognise it by this name

_RE = re.compile(r"#\s*plx:\s*(ignore-file|ignore)\b(?:\[([^\]]*)\])?")


@dataclass(frozen=True, slots=True)
class Comment:
    """What a suppression comment says, with offsets into the comment's text, so that hover,
    code actions and the formatter read it exactly as lint does."""

    file_wide: bool  # `ignore-file`
    codes: tuple[tuple[str, int, int], ...] | None  # (code as written, start, end); None: every code
    list_end: int | None  # offset of the closing `]`, None without a list


def parse(comment_text: str) -> Comment | None:
    m = _RE.search(comment_text)
    if not m:
        return None
    if m.group(2) is None:
        return Comment(m.group(1) == "ignore-file", None, None)
    codes, at = [], m.start(2)
    for piece in m.group(2).split(","):
        word = piece.strip()
        if word:
            start = at + piece.index(word)
            codes.append((word, start, start + len(word)))
        at += len(piece) + 1
    codes = tuple(codes)
    return Comment(m.group(1) == "ignore-file", codes, m.end(2))


@dataclass(slots=True)
class Suppression:
    comment: ast.Comment
    line: int | None  # None for the whole file
    codes: list[str] | None  # None: all codes
    used: set[str] = field(default_factory=set)
    used_any: bool = False

    def covers(self, d: Diagnostic) -> bool:
        if self.line is not None and d.span.start.line != self.line:
            return False
        return self.codes is None or any(d.code.startswith(c) for c in self.codes)


def collect(tree: ast.File) -> list[Suppression]:
    out: list[Suppression] = []
    code_lines: list[int] | None = None
    for c in tree.comments:
        sc = parse(c.text)
        if sc is None:
            continue
        codes = None if sc.codes is None else [code.upper() for code, _, _ in sc.codes]
        if sc.file_wide:
            out.append(Suppression(c, None, codes))
            continue
        line = c.span.start.line
        if c.own_line:
            if code_lines is None:
                code_lines = sorted({s.header.start.line for s in ast.walk_statements(tree.statements)})
            line = next((ln for ln in code_lines if ln > line), -1)
        out.append(Suppression(c, line, codes))
    return out


def apply(tree: ast.File, diags: list[Diagnostic], report_unused: bool = True) -> list[Diagnostic]:
    sups = collect(tree)
    if not sups:
        return diags
    kept = []
    for d in diags:
        hit = False
        if not d.code.startswith("S"):  # syntax errors are never hidden
            for s in sups:
                if s.covers(d):
                    s.used_any = True
                    s.used.add(d.code)
                    hit = True
        if not hit:
            kept.append(d)
    if report_unused:
        for s in sups:
            unused = []
            if s.codes is None:
                if not s.used_any:
                    unused = ["(all)"]
            else:
                unused = [c for c in s.codes if not any(u.startswith(c) for u in s.used)]
            if unused:
                what = "this suppression" if unused == ["(all)"] else ("suppressed code " if len(unused) == 1 else "suppressed codes ") + ", ".join(unused)
                fix = None
                if s.codes is None or len(unused) == len(s.codes):
                    start, end = s.comment.span.start.offset, s.comment.span.end.offset
                    if not s.comment.own_line:
                        while start > 0 and tree.text[start - 1] in " \t":
                            start -= 1
                    fix = Fix("remove the unused suppression", (Edit(start, end, ""),), safe=True)
                kept.append(Diagnostic(registry.UNUSED_SUPPRESSION, f"unused suppression: {what} matched no diagnostic",
                                       s.comment.span, Severity.WARNING, file=tree.path,
                                       help="remove it, or the code it names", fix=fix))
    return kept
