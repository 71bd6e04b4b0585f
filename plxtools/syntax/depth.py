"""How deep an expression may be: every later stage (the checker, the evaluator, the formatter,
the caches' pickling) walks expressions recursively, so the parser refuses deeper ones with a
located S007 instead of letting one of them hit Python's recursion limit.

The limit counts every level of the tree: a unary minus, an operand of a binary operator (`1+1+1`
is a left-leaning chain as deep as its terms), a bracket, a member access. A line with fewer
tokens than the limit cannot reach it, so ordinary lines are not measured at all.
"""

from __future__ import annotations

import dataclasses

from plxtools.syntax import ast

MAX_EXPR_DEPTH = 500

_CHILD_FIELDS: dict[type, tuple[str, ...]] = {}


def _fields(cls: type) -> tuple[str, ...]:
    names = _CHILD_FIELDS.get(cls)
    if names is None:
        names = tuple(f.name for f in dataclasses.fields(cls) if f.name not in ("span",))
        _CHILD_FIELDS[cls] = names
    return names


def too_deep(stmt: ast.Node, n_tokens: int, limit: int = MAX_EXPR_DEPTH) -> bool:
    """True when an expression in the statement is more than `limit` levels deep (measured without recursion)."""
    if n_tokens <= limit:
        return False
    stack: list[tuple[object, int]] = [(stmt, 0)]  # the statement itself is not a level
    while stack:
        node, depth = stack.pop()
        if depth > limit:
            return True
        for name in _fields(type(node)):
            value = getattr(node, name, None)
            if isinstance(value, ast.Node):
                stack.append((value, depth + 1))
            elif isinstance(value, list):
                stack.extend((v, depth + 1) for v in value if isinstance(v, ast.Node))
    return False
