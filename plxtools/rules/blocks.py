"""The declaration blocks of a file, for the rule modules that judge one block at a time (a model's
body, a body's geometry, a system's mates): one walk, so every such rule sees the same blocks."""

from __future__ import annotations

import difflib
from collections.abc import Iterator

from plxtools.syntax import ast


def declaration_blocks(statements: list) -> Iterator[tuple[ast.Declaration, list]]:
    """Each declaration with a body among `statements` (a file's, or the ones a rule judges),
    nested ones included, with that body (depth first)."""
    stack = [s for s in statements if isinstance(s, ast.Declaration) and s.body]
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


def likeliest_meant(uses, taken: str, spare: list[str]):
    """Of `uses` (statement, value) pairs that name `taken`, the one whose own name is most
    clearly closer to one of the `spare` names than to `taken`, with that name: (use, name), or
    None when no use leans towards a spare name. (A copied line with one name left unchanged is
    usually the one that meant the spare.)"""
    def close(a: str, b: str) -> float:
        return difflib.SequenceMatcher(None, a, b).ratio()

    best = None
    for use in uses:
        name = use[0].path.parts[0].name
        for n in spare:
            gain = close(name, n) - close(name, taken)
            if gain > 0 and (best is None or gain > best[0]):
                best = (gain, use, n)
    return None if best is None else (best[1], best[2])
