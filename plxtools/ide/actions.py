"""Code actions: lint fixes as quick fixes, "fix all safe fixes", and "suppress this rule here"."""

from __future__ import annotations

from plxtools.diagnostics import Diagnostic
from plxtools.ide.host import FileState
from plxtools.ide.types import CodeAction, TextEdit
from plxtools.rules import suppress
from plxtools.syntax import ast
from plxtools.rules import registry



def _overlaps(d: Diagnostic, start: int, end: int, st: FileState) -> bool:
    a, b = d.span.start.offset, d.span.end.offset
    if a <= end and start <= b:
        return True
    # a cursor on the same line as a zero-width or far diagnostic still gets its actions
    idx = st.tree.index
    return idx.pos(start).line <= d.span.start.line <= idx.pos(end).line


def fix_edits(d: Diagnostic) -> list[TextEdit]:
    return [TextEdit(e.start, e.end, e.text) for e in d.fix.edits] if d.fix is not None else []


def code_actions(st: FileState, start: int, end: int, only: list[str] | None = None,
                 diagnostics: list[Diagnostic] | None = None) -> list[CodeAction]:
    """Actions for a range. `diagnostics` narrows to those the editor sent (else all in the range)."""
    want_quick = only is None or any(k == "quickfix" or "quickfix".startswith(k) or k.startswith("quickfix")
                                     for k in only)
    want_fix_all = only is None or any(k in ("source", "source.fixAll") or k.startswith("source.fixAll")
                                       for k in only)
    pool = diagnostics if diagnostics is not None else [d for d in st.diagnostics if _overlaps(d, start, end, st)]
    out: list[CodeAction] = []
    if want_quick:
        for d in pool:
            if d.fix is not None:
                title = f"Fix {d.code}: {d.fix.message}" + ("" if d.fix.safe else " (unsafe)")
                out.append(CodeAction(title, "quickfix", {st.path: fix_edits(d)}, [d], preferred=d.fix.safe))
        seen_codes: set[tuple[str, int]] = set()
        for d in pool:
            key = (d.code, d.span.start.line)
            if key in seen_codes:
                continue
            seen_codes.add(key)
            edit = suppress_edit(st, d)
            if edit is not None:
                out.append(CodeAction(f"Suppress {d.code} on this line (# plx: ignore[{d.code}])", "quickfix",
                                      {st.path: [edit]}, [d]))
    if want_fix_all:
        action = fix_all(st)
        if action is not None and (only is not None or any(d.fix is not None and d.fix.safe for d in pool)):
            out.append(action)
    return out


def fix_all(st: FileState) -> CodeAction | None:
    """Every safe fix at once; overlapping fixes are skipped, as `plx lint --fix` does."""
    fixes = [d for d in st.diagnostics if d.fix is not None and d.fix.safe]
    if not fixes:
        return None
    edits: list[TextEdit] = []
    last_start = len(st.text) + 1
    for e in sorted((e for d in fixes for e in d.fix.edits), key=lambda e: (e.start, e.end), reverse=True):
        if e.end > last_start:
            continue
        edits.append(TextEdit(e.start, e.end, e.text))
        last_start = e.start
    edits.reverse()
    return CodeAction(f"Fix all safe fixes ({len(fixes)})", "source.fixAll", {st.path: edits}, fixes)


def suppress_edit(st: FileState, d: Diagnostic) -> TextEdit | None:
    """`# plx: ignore[CODE]` at the end of the diagnostic's line (or the code added to one already there)."""
    if d.code.startswith("S") or d.code == registry.UNUSED_SUPPRESSION:
        return None  # syntax errors cannot be suppressed; an unused suppression is removed, not suppressed
    idx = st.tree.index
    line = d.span.start.line
    line_text = idx.line_text(line)
    line_start = idx.offset(line, 0)
    line_end = line_start + len(line_text)
    if _inside_triple_string(st, line_end):
        return None
    comment = next((c for c in st.tree.comments if c.span.start.line == line), None)
    if comment is not None:
        sc = suppress.parse(comment.text)
        if sc is not None:
            if sc.file_wide or sc.codes is None:
                return None  # a file-wide comment, or one that already suppresses every code
            codes = [c for c, _, _ in sc.codes]
            if d.code in codes:
                return None
            insert_at = comment.span.start.offset + sc.list_end
            return TextEdit(insert_at, insert_at, (", " if codes else "") + d.code)
    stripped_end = line_start + len(line_text.rstrip())
    return TextEdit(stripped_end, line_end, f"  # plx: ignore[{d.code}]")


def _inside_triple_string(st: FileState, offset: int) -> bool:
    for s in ast.walk_statements(st.tree.statements):
        v = getattr(s, "value", None)
        if isinstance(v, ast.String) and v.kind == "triple" and v.span.start.offset < offset < v.span.end.offset:
            return True
    return False
