"""Values of one model that depend on each other in a ring: they can never be evaluated.

A fact (`ValueCycle`), without a code or message text: the rule module
`rules/semantic/default_cycle.py` reports it from lint (M006); check's evaluator meets the same ring
when it computes the values and leaves it to that finding (the registry's `owns`). The answer is a
function of the model's own statement (its default values), so it needs no program.
"""

from __future__ import annotations

from dataclasses import dataclass

from plxtools.diagnostics import Pos, Span
from plxtools.syntax import ast


@dataclass(frozen=True, slots=True)
class ValueCycle:
    """`ring`: the dotted attribute paths in order, the first repeated at the end; `span`: the
    value that closes it (the model's header when that value has no span of its own)."""

    ring: tuple[str, ...]
    span: Span


# path -> {a model statement's text: (its offset, its line, its rings)} of the last version of each
# file analysed. The rings are a function of the statement's text alone, so a statement written the
# same way in the next version has the same rings, moved by as many characters and lines as the
# statement moved (columns stay: a top-level statement moves as whole lines).
_KEPT: dict[str, dict[str, tuple[int, int, tuple[ValueCycle, ...]]]] = {}
MAX_FILES = 64


def cycles_of_models(path: str, text: str, stmts: list) -> list[tuple[ValueCycle, ...]]:
    """`value_cycles` of each model statement of one file (in order; `text` the file's text),
    re-using the answers for the statements the last version of `path` wrote the same way."""
    last = _KEPT.get(path, {})
    now: dict[str, tuple[int, int, tuple[ValueCycle, ...]]] = {}
    out = []
    for stmt in stmts:
        start = stmt.span.start
        written = text[start.offset:stmt.span.end.offset]
        hit = last.get(written)
        if hit is None:
            got = tuple(value_cycles(stmt))
        elif hit[0] == start.offset and hit[1] == start.line:
            got = hit[2]
        else:
            d, dl = start.offset - hit[0], start.line - hit[1]
            got = tuple(ValueCycle(c.ring, _moved(c.span, d, dl)) for c in hit[2])
        now[written] = (start.offset, start.line, got)
        out.append(got)
    if path not in _KEPT and len(_KEPT) >= MAX_FILES:
        _KEPT.clear()  # (bounded: a long session meets many files)
    _KEPT[path] = now
    return out


def _moved(span: Span, d: int, dl: int) -> Span:
    a, b = span.start, span.end
    return Span(Pos(a.offset + d, a.line + dl, a.column), Pos(b.offset + d, b.line + dl, b.column))


def value_cycles(stmt) -> list[ValueCycle]:
    """The rings among the default values written in a model's statement (one per ring)."""
    out: list[ValueCycle] = []
    edges: dict[str, list[tuple[str, Span]]] = {}
    spans: dict[str, Span] = {}

    body = getattr(stmt, "body", None)
    if not body:
        return out
    _default_edges(body, "", edges, spans)
    if not edges or not any(edges.values()):
        return out  # no default reads another value: no ring
    # a value depends on a key that is its reference or a dotted prefix of it, so on nothing when
    # no reference starts with the first name of a key (`size: Math.Vec3.from_xyz(...)`)
    firsts = {k.split(".", 1)[0] for k in edges}
    if not any(r.split(".", 1)[0] in firsts for refs in edges.values() for r, _ in refs):
        return out
    keys = list(edges)
    order = {k: i for i, k in enumerate(keys)}

    def deps(key: str) -> list[str]:
        # every key that is the reference or a dotted prefix of it (a reference to a whole
        # object, 'source: logic', is not a value dependency), in the keys' order: a lookup per
        # prefix, not a scan of all keys per reference
        found_ = []
        for r, _ in edges.get(key, []):
            parts = r.split(".")
            found = [order[p] for p in (".".join(parts[:n]) for n in range(1, len(parts) + 1)) if p in order]
            found_.extend(keys[i] for i in sorted(found))
        return found_

    color: dict[str, int] = {}
    reported: set[str] = set()
    for start in keys:
        if color.get(start):
            continue
        stack = [(start, iter(deps(start)))]
        trail = [start]
        color[start] = 1
        while stack:
            node, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                color[node] = 2
                stack.pop()
                trail.pop()
                continue
            if color.get(nxt) == 1:
                ring = trail[trail.index(nxt):] + [nxt]
                if nxt not in reported:
                    reported.update(ring)
                    out.append(ValueCycle(tuple(ring), spans.get(nxt, stmt.header)))
            elif not color.get(nxt):
                color[nxt] = 1
                trail.append(nxt)
                stack.append((nxt, iter(deps(nxt))))
    return out


_LEAVES = (ast.Number, ast.String, ast.Bool, ast.This)


def _value_refs(expr) -> list[tuple[str, Span]]:
    """The dotted names an expression reads, with their spans."""
    if expr.__class__ in _LEAVES:
        return []
    out = []
    stack = [expr]
    push, extend = stack.append, stack.extend
    while stack:
        x = stack.pop()
        cls = x.__class__  # (the expression classes have no subclasses)
        if cls is _Member or cls is _Name:
            chain = []
            cur = x
            while cur.__class__ is _Member:
                chain.append(cur.name.name)
                cur = cur.obj
            if cur.__class__ is _Name:
                chain.append(cur.ident.name)
                out.append((".".join(reversed(chain)), x.span))
                continue
            push(cur)
        elif cls is _Call:
            push(x.func)
            extend(x.args)
        elif cls is _Binary:
            push(x.left)
            push(x.right)
        elif cls is _Unary:
            push(x.operand)
        elif cls is _Paren:
            push(x.inner)
        elif cls is _Brace or cls is _Array:
            extend(x.items)
        elif cls is _Index:
            push(x.obj)
            push(x.index)
    return out


_Member, _Name, _Call, _Binary, _Unary, _Paren, _Brace, _Array, _Index = (
    ast.Member, ast.Name, ast.Call, ast.Binary, ast.Unary, ast.Paren, ast.Brace, ast.Array, ast.Index)


def _default_edges(body, prefix: str, edges: dict, spans: dict) -> None:
    """What each default value reads, by dotted attribute path. Module-level (not a closure that
    calls itself) so a search leaves no reference cycles behind for the collector."""
    for s in body:
        if isinstance(s, (ast.Declaration, ast.Assignment)):
            key = prefix + s.path.text
            if getattr(s, "value", None) is not None:
                edges.setdefault(key, []).extend(_value_refs(s.value))
                spans.setdefault(key, s.path.span)
            if getattr(s, "body", None):
                _default_edges(s.body, key + ".", edges, spans)
