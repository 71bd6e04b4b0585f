"""One model body gives an attribute a value twice (`inertia.mass: 10`, later `inertia.mass: 15`, or
the same path in an assignment block); reported at the second, which silently replaces the first.

## Why it matters

OpenPLX keeps the last value and drops the first without a word, so the model means something
other than what one of the two lines says. A second assignment is never needed: delete the one
that is wrong. Nested forms count as the same path (`inertia.mass: 10` and an `inertia:` block with
`mass: 15`), and so does a declaration's own value (`speed is Real: 1` then `speed: 2`).

## Example

```openplx
Chassis is Physics3D.Bodies.RigidBody:
    inertia.mass: 1000
    inertia.mass: 1500
```

## Use instead

```openplx
Chassis is Physics3D.Bodies.RigidBody:
    inertia.mass: 1500
```
"""

from __future__ import annotations

from plxtools.syntax import ast


def check(facts, report) -> None:
    tree, path = facts.tree, facts.path
    # a line with an error of its own (an unknown attribute, a syntax error) is that error's: not
    # also said to be a second value
    broken = {d.span.start.line for d in list(tree.diagnostics) + list(facts.analysis.diagnostics)
              if d.severity.value == "error"}
    stack = [s.body for s in facts.judged if ast.body_of(s)]
    while stack:
        body = stack.pop()
        seen: dict[tuple[str, ...], ast.Stmt] = {}
        for key, stmt, value in _values(body, ()):
            if stmt.header.start.line in broken:
                continue
            first = seen.get(key)
            if first is None:
                seen[key] = stmt
                continue
            _report(report, tree, path, ".".join(key), first, stmt, value)
        # every block below a declaration is its own model body
        stack.extend(s.body for s in _declarations(body) if s.body)


def _declarations(body):
    """The declarations of a body and of its assignment blocks (`size:` then `x: 1`)."""
    todo = list(body)
    while todo:
        s = todo.pop()
        if isinstance(s, ast.Declaration):
            yield s
        elif isinstance(s, ast.Assignment) and s.body:
            todo.extend(s.body)


def _values(body, prefix: tuple[str, ...]):
    """(full path, statement, value) for each value the body gives, assignment blocks flattened."""
    for s in body:
        if isinstance(s, ast.Assignment):
            key = prefix + tuple(p.name for p in s.path.parts)
            if s.value is not None:
                yield key, s, s.value
            if s.body:
                yield from _values(s.body, key)
        elif isinstance(s, ast.Declaration) and s.value is not None and s.keyword is not None:
            yield prefix + tuple(p.name for p in s.path.parts), s, s.value


def _text(tree: ast.File, node) -> str:
    text = tree.text[node.span.start.offset:node.span.end.offset]
    return text if len(text) <= 40 else text[:37] + "..."


def _report(report, tree, path, name, first, second, value) -> None:
    line = first.header.start.line + 1
    old = _text(tree, first.value) if getattr(first, "value", None) is not None else "?"
    report(f"'{name}' is given a value twice in this block: {_text(tree, value)} here silently replaces {old} "
           f"from line {line}", second.header, help=f"keep one of the two: delete this line or line {line}",
           related=[(path, first.header, f"'{name}' first given here")])
