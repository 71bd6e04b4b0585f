"""Range formatting for the language server: format only the statements a selection touches.

The whole file is laid out once; the statements (and comments) overlapping the selection are
cut out of that layout and put in place of their source lines. Their indentation is based on
where the first of them stands now, so a selection in a 2-space file does not jump to 4 spaces.
If the edited file would not mean the same (a selection across block levels can do that), the
selection grows to whole top-level definitions, which are always safe to replace.
"""

from __future__ import annotations

from plxtools.diagnostics import Edit
from plxtools.fmt.api import BOM, layout_tree, syntax_errors
from plxtools.fmt.brackets import LayoutError
from plxtools.fmt.document import Piece
from plxtools.fmt.safety import same_meaning
from plxtools.fmt.style import INDENT
from plxtools.syntax import ast, parse_text


def format_range(text: str, start_line: int, end_line: int) -> list[Edit]:
    """Edits (offsets into `text`) that format the statements on lines start_line..end_line.

    Lines are 0-based and inclusive. Returns no edits for a file with syntax errors, a range that
    holds only blank lines, or statements that are already formatted.
    """
    shift = 1 if text.startswith(BOM) else 0
    tree = parse_text(text)
    if syntax_errors(tree):
        return []
    try:
        pieces = layout_tree(tree).pieces
    except LayoutError:
        return []
    hit = [i for i, p in enumerate(pieces) if p.first_line <= end_line and p.last_line >= start_line]
    if not hit:
        return []
    first, last = hit[0], hit[-1]
    for lo, hi, rebase in ((first, last, True), *_top_level(pieces, first, last)):
        edit = _edit(tree, pieces, lo, hi, rebase)
        if edit is None:
            return []  # already formatted
        if _keeps_meaning(tree, edit):
            return [Edit(edit.start + shift, edit.end + shift, edit.text)]
    return []


def _top_level(pieces: list[Piece], first: int, last: int) -> list[tuple[int, int, bool]]:
    lo = first
    while lo > 0 and pieces[lo].depth > 0:
        lo -= 1
    hi = last
    while hi + 1 < len(pieces) and pieces[hi + 1].depth > 0:
        hi += 1
    if (lo, hi) == (first, last) and pieces[first].depth == 0:
        return []
    return [(lo, hi, False)]


def _edit(tree: ast.File, pieces: list[Piece], lo: int, hi: int, rebase: bool) -> Edit | None:
    index = tree.index
    start = index.offset(pieces[lo].first_line, 0)
    end = index.line_end(pieces[hi].last_line)
    delta = _rebase_delta(pieces, lo, hi) if rebase else 0
    chunks: list[str] = []
    for k in range(lo, hi + 1):
        p = pieces[k]
        if k > lo:
            chunks.extend([""] * p.blanks)
        for chunk in p.out:
            chunks.append(_shifted(chunk, delta))
    new = tree.newline.join(chunks)
    old = tree.text[start:end]
    if new == old:
        return None
    return _trimmed(start, old, new)


def _rebase_delta(pieces: list[Piece], lo: int, hi: int) -> int:
    """How far the selection's first statement (comments carry no structure) stands from its
    canonical column; the statement after the selection stands in if it holds only comments."""
    order = list(range(lo, hi + 1)) + list(range(hi + 1, len(pieces))) + list(range(lo - 1, -1, -1))
    for k in order:
        p = pieces[k]
        if p.stmt is not None:
            return p.indent - p.depth * INDENT
    return 0


def _shifted(chunk: str, delta: int) -> str:
    """Move a printed line by `delta` columns; only its first physical line (the rest is string)."""
    if delta > 0 and chunk:
        return " " * delta + chunk
    if delta < 0:
        lead = len(chunk) - len(chunk.lstrip(" "))
        return chunk[min(lead, -delta) :]
    return chunk


def _trimmed(start: int, old: str, new: str) -> Edit:
    """The smallest whole-line replacement that turns `old` into `new`."""
    a = old.splitlines(keepends=True)
    b = new.splitlines(keepends=True)
    head = 0
    while head < min(len(a), len(b)) - 1 and a[head] == b[head]:
        head += 1
    tail = 0
    while tail < min(len(a), len(b)) - head - 1 and a[-1 - tail] == b[-1 - tail]:
        tail += 1
    cut_start = start + sum(len(x) for x in a[:head])
    cut_end = start + len(old) - sum(len(x) for x in a[len(a) - tail :])
    text = "".join(b[head : len(b) - tail])
    return Edit(cut_start, cut_end, text)


def _keeps_meaning(tree: ast.File, edit: Edit) -> bool:
    after = parse_text(tree.text[: edit.start] + edit.text + tree.text[edit.end :])
    try:
        return same_meaning(tree, after) is None
    except RecursionError:
        return False
