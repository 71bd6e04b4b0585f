"""The checks that stand between the formatter and the user's file.

Before anything is written, the output is parsed again: it must mean the same as the input (the
same layout-free tree, the same comments in the same order) and formatting it once more must
change nothing. black does the same with `--safe`; here it cannot be turned off.
"""

from __future__ import annotations

from plxtools.syntax import ast


def comment_texts(tree: ast.File) -> list[str]:
    # trailing whitespace is layout: the formatter removes it from comments too
    return [c.text.rstrip() for c in tree.comments]


def same_meaning(before: ast.File, after: ast.File) -> str | None:
    """None when both trees mean the same, else a short reason."""
    if after.has_errors:
        first = next(d for d in after.diagnostics if d.severity.value == "error")
        line = first.span.start.line + 1
        return f"the output does not parse (line {line}: {first.code} {first.message})"
    if ast.structure(before.statements) != ast.structure(after.statements):
        return "the output's syntax tree differs from the input's"
    if comment_texts(before) != comment_texts(after):
        return "the output's comments differ from the input's"
    return None
