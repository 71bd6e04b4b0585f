"""The declaration blocks of a file, for the rule modules that judge one block at a time (a model's
body, a body's geometry, a system's mates): one walk, so every such rule sees the same blocks."""

from __future__ import annotations

from collections.abc import Iterator

from plxtools.syntax import ast


def declaration_blocks(tree: ast.File) -> Iterator[tuple[ast.Declaration, list]]:
    """Each declaration with a body, nested ones included, with that body (depth first)."""
    stack = [s for s in tree.statements if isinstance(s, ast.Declaration) and s.body]
    while stack:
        owner = stack.pop()
        body = owner.body or []
        stack.extend(s for s in body if isinstance(s, ast.Declaration) and s.body)
        yield owner, body


def written_static(body) -> bool:
    """Whether the block writes `is_dynamic` as anything but `true` (a wrong value has its own
    error, so it counts as static here)."""
    return any(isinstance(s, ast.Assignment) and [p.name for p in s.path.parts] == ["is_dynamic"]
               and not (isinstance(s.value, ast.Bool) and s.value.value) for s in body)
