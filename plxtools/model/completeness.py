"""The values and references that what a file's root model instantiates needs and nothing gives.

Library models may be incomplete; only objects that the root model (the last model in a file
outside any bundle) actually creates must have every non-optional value. The result is facts
(`Unset`), without codes or message text: the rule module `rules/semantic/unset_values.py` turns
them into lint's findings (M007, M008), and check's evaluator, which meets the same faults while it
computes values, leaves them to those findings (the registry's `owns`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from plxtools.diagnostics import Span
from plxtools.model.program import Program
from plxtools.model.symbols import ModelSym, Ty
from plxtools.syntax import ast


@dataclass(frozen=True, slots=True)
class Unset:
    """A non-optional value (or reference) of an instantiated object that nothing gives.

    One per source location: objects of one model that all lack the same value are one fact, whose
    `path` is what they share (`geometry.radius`) and `instances` the objects (`a`, `b`, ...)."""

    reference: bool  # an unbound reference; else a missing Real, Int, Bool or String
    path: str  # dotted, from the root model (from each instance when there are several)
    type: str  # the attribute's type as written for people
    name: str  # the attribute
    owner: str  # the model that declares it
    anchor: Span  # where it is shown: its declaration in this file, else the nearest line above
    instances: tuple[str, ...] = ()

REQUIRED_PRIMITIVES = {"Real", "Int", "Bool", "String"}
MAX_DEPTH = 40
MAX_SHARED_WALKS = 64  # walks kept per bundle model (per set of values given from outside)


_NONE: frozenset = frozenset()


def _anchor(mem, unit):
    """Where a finding about `mem` is shown: its declaration when it is in this file (else None,
    the nearest anchor above)."""
    return mem.stmt.path.span if mem.owner.unit is unit and mem.stmt.path is not None else None


def root_model(program: Program, unit) -> ModelSym | None:
    last = None
    for s in unit.tree.statements:
        if isinstance(s, ast.Declaration) and s.keyword != "becomes" and len(s.path.parts) == 1:
            sym = unit.locals.get(s.path.parts[0].name) if unit.bundle is None else unit.namespace.symbols.get(s.path.parts[0].name)
            if isinstance(sym, ModelSym) and not sym.is_trait and sym.stmt is s:
                last = sym
    return last


def _walk_assigned(body, prefix: tuple[str, ...], out: set[tuple[str, ...]]) -> None:
    for s in body:
        if isinstance(s, ast.Declaration) and s.keyword in ("is", "becomes"):
            if s.value is not None:
                out.add(prefix + tuple(p.name for p in s.path.parts))
        elif isinstance(s, ast.Assignment):
            path = prefix + tuple(p.name for p in s.path.parts)
            if s.value is not None:
                out.add(path)
            if s.body:
                _walk_assigned(s.body, path, out)


def _own_assigned(m: ModelSym) -> frozenset:
    """Paths a model's own body gives a value (kept on the model: its statement never changes)."""
    got = m._assigned
    if got is None:
        out: set[tuple[str, ...]] = set()
        body = getattr(m.stmt, "body", None)
        if body:
            _walk_assigned(body, (), out)
        got = m._assigned = frozenset(out)
    return got


def _assigned(program: Program, model: ModelSym) -> set[tuple[str, ...]]:
    """Paths given a value anywhere in a model's chain of bases, traits and its own body."""
    out: set[tuple[str, ...]] = set()
    for m in program.ancestors(model):
        out |= _own_assigned(m)
    return out


def assigned_paths(program: Program, model: ModelSym, block=None, below: ModelSym | None = None) -> set[tuple[str, ...]]:
    """The attribute paths a model's chain gives a value (`("inertia", "mass")`), with those an
    instance's own `block` gives; `below`: only the models of the chain that derive from it (not
    it nor its bases: their defaults are not a decision of the file's author)."""
    out: set[tuple[str, ...]] = set()
    for m in program.ancestors(model):
        if below is None or (m is not below and not program.is_subtype(below, m)):
            out |= _own_assigned(m)
    if block:
        _walk_assigned(block, (), out)
    return out


def _shared(model: ModelSym, traits: tuple) -> bool:
    """A walk below a bundle model (with bundle traits) is the same for every file that meets it:
    it is kept on the model until the bundles change (Program.invalidate clears it)."""
    unit = model.unit
    if unit is None or unit.bundle is None:
        return False
    for t in traits:
        if t.unit is None or t.unit.bundle is None:
            return False
    return True


class Versions:
    """The walks below this file's own models, carried from one version of the file to the next
    (the language server, rules/analysis.py). A model of this file is known by its statement's
    serial (model/reuse.py: the same serial means the same closure of statements, so the same
    walk) and its place in that statement; models of other files by identity, which stays while
    the program's epoch does. Anchors of kept walks are moved to where their statements now are."""

    def __init__(self, unit, regions: list, serials: list, previous: dict | None, move_span):
        from plxtools.model.reuse import place

        self.unit = unit
        self.starts = [r[0] for r in regions]
        self.serials = serials
        self.previous = previous or {}
        self.move_span = move_span
        self.place = place
        self.walked: dict = {}

    def key(self, model: ModelSym):
        stmt = model.stmt
        if model.unit is not self.unit or stmt is None or not self.serials:
            return id(model)
        got = self.place(self.starts, self.serials, stmt)
        return (got[0], model.qname, got[1]) if got is not None else id(model)

    def kept(self, key):
        """The last version's walk of `key`, moved (None: there is none, or it cannot be moved)."""
        got = self.previous.get(key)
        moved = _moved(got, self.move_span) if got is not None else None
        if moved is not None:
            self.walked[key] = moved
        return moved

    def carry_all(self) -> dict:
        """Every walk of the last version that can be moved (when the rule did not run)."""
        for key in self.previous:
            self.kept(key)
        return self.walked


def _moved(got: tuple, move_span) -> tuple | None:
    finds = []
    for kind, rel, shown, name, owner, a in got[0]:
        if a is not None:
            a = move_span(a)
            if a is None:
                return None
        finds.append((kind, rel, shown, name, owner, a))
    return finds, got[1], got[2]


def unset_values(program: Program, unit, root: ModelSym | None = None, versions: Versions | None = None,
                 explained: Callable[[Span, str], bool] | None = None) -> list[Unset]:
    """What the root model creates and nothing gives a value, one fact per source location and
    attribute.

    `explained(anchor, name)`: whether another finding at that declaration already explains the
    missing `name` (a block that failed to parse, a misspelt attribute): such a value is left out
    (one mistake, one message)."""
    if unit.bundle is not None:
        return []
    root = root or root_model(program, unit)
    if root is None:
        return []
    found: list[tuple[str, str, str, str, str, Span]] = []  # (kind, path, type, name, owner, anchor)
    seen: set[tuple[str, str]] = set()
    memo: dict[int, set[tuple[str, ...]]] = {}

    below_layers: dict[tuple, set[tuple[str, ...]]] = {}  # the union over a run of layers (ids)

    def assigned_in(m: ModelSym) -> set[tuple[str, ...]]:
        got = memo.get(id(m))
        if got is None:
            lin = program.linearize(m)  # ends with m; the models of a file share their bases' layers
            if len(lin) > 2:
                key = tuple(map(id, lin[:-1]))
                below = below_layers.get(key)
                if below is None:
                    below = below_layers[key] = set()
                    for layer in lin[:-1]:
                        below |= _own_assigned(layer)
                got = below | _own_assigned(m)
            else:
                got = _assigned(program, m)
            memo[id(m)] = got
        return got

    walked: dict[tuple, tuple[list, frozenset, int]] = versions.walked if versions is not None else {}
    mkey = versions.key if versions is not None else id
    kept = versions.kept if versions is not None else None
    fast = versions is None  # models are keyed by identity: a kept walk can be looked up inline

    def known(model: ModelSym, me, traits: tuple, outer, depth: int, chain: tuple):
        """(key, shared, hit): the walk's key, whether it is kept on the model (a bundle model), and
        a walk already made that re-using cannot tell from walking again (or None)."""
        key = (me, tuple(map(mkey, traits)) if traits else (), frozenset(outer))
        shared = _shared(model, traits)
        if shared:
            hit = model._walks.get(key) if model._walks is not None else None
        else:
            hit = walked.get(key)
            if hit is None and kept is not None:
                hit = kept(key)
        if hit is not None and (depth + hit[2] > MAX_DEPTH or not hit[1].isdisjoint(chain)):
            hit = None
        return key, shared, hit

    def keep(model: ModelSym, key, shared: bool, got: tuple) -> None:
        if not shared:
            walked[key] = got
            return
        if model._walks is None or len(model._walks) >= MAX_SHARED_WALKS:
            model._walks = {}  # (bounded: a long editing session meets many value sets)
        model._walks[key] = got

    def walk(ty: Ty, outer: set[tuple[str, ...]], depth: int, chain: tuple) -> tuple[list, frozenset, int, bool]:
        """What is missing below `ty`, relative to it: (findings, models met, height, cut short).

        A finding is (kind, path below ty, type shown, member name, declaring model, anchor or None
        for "the nearest anchor above"). The objects a root creates are instances of few models, so
        a subtree is walked once per (model, traits, values given from outside) and re-used; only
        when re-using it cannot differ from walking it again (no cycle or depth cut inside, none of
        its models on the current chain, still within the depth limit)."""
        model = ty.sym
        if not isinstance(model, ModelSym):
            return [], frozenset(), 0, False
        me = mkey(model)
        if depth > MAX_DEPTH or me in chain:
            return [], frozenset(), 0, True
        traits = ty.traits
        key, shared, hit = known(model, me, traits, outer, depth, chain)
        if hit is not None:
            return hit[0], hit[1], hit[2], False
        assigned = assigned_in(model) | outer
        for t in traits:
            assigned |= assigned_in(t)
        below_of = None  # member name -> the paths below it given a value (built on first need)
        finds: list = []
        models = {me}
        height = 0
        cut = False
        inner = chain + (me,)
        member_type = program.member_type
        for name, mem in program.members_of(ty).items():
            mty = mem.ty if mem.ty is not None else member_type(mem)
            if mem.reference:
                if _required(mem, name, assigned):
                    finds.append(("ref", (name,), mty.display(), name, mem.owner.qname, _anchor(mem, unit)))
                continue
            sym = mty.sym
            if sym is None or mty.alts or mty.array:
                continue
            if isinstance(sym, str):
                if sym in REQUIRED_PRIMITIVES and _required(mem, name, assigned):
                    finds.append(("val", (name,), sym, name, mem.owner.qname, _anchor(mem, unit)))
                continue
            if mem.value is not None or (name,) in assigned:
                continue  # given an existing object or a computed value (checked where it is made)
            if below_of is None:
                below_of = _below(assigned)
            sub = below_of.get(name, _NONE)
            hit = _bundle_walk(mty, sym, sub, depth + 1, inner) if fast else None
            below, met, h, c = (hit[0], hit[1], hit[2], False) if hit is not None else walk(mty, sub, depth + 1, inner)
            if below:
                _prefixed(finds, name, below, _anchor(mem, unit))
            models.update(met)
            if h + 1 > height:
                height = h + 1
            cut = cut or c
        got = (finds, frozenset(models), height)
        if not cut:
            keep(model, key, shared, got)
        return got[0], got[1], got[2], cut

    anchor = root.stmt.path.span if isinstance(root.stmt, ast.Declaration) else root.stmt.header
    try:
        finds = walk(Ty(root), set(), 0, ())[0]
    finally:
        # `walk` calls itself through its closure cell: a reference cycle that would keep the memos
        # alive until a collector pass; emptying the cell frees them now
        walk = None  # noqa: F841
    for kind, rel, shown, name, owner, a in finds:
        local_anchor = a if a is not None else anchor
        full = ".".join(rel)
        if (full, kind) in seen or (explained is not None and explained(local_anchor, name)):
            continue
        seen.add((full, kind))
        found.append((kind, full, shown, name, owner, local_anchor))
    return _one_per_location(found)


def _required(mem, name: str, assigned) -> bool:
    """A member that must be given here: not optional, no default, not assigned on the way."""
    return not mem.optional and mem.value is None and (name,) not in assigned


def _below(assigned) -> dict[str, set[tuple[str, ...]]]:
    """Member name -> the paths below it that are given a value (`a.b.c: 1` -> a: {(b, c)})."""
    below_of: dict[str, set[tuple[str, ...]]] = {}
    for p in assigned:
        if len(p) > 1:
            below_of.setdefault(p[0], set()).add(p[1:])
    return below_of


def _bundle_walk(mty: Ty, sym, sub, depth: int, inner: tuple):
    """A bundle model's kept walk for a member (most members), looked up without walking; None
    when there is none or re-using it could differ (depth limit, a model on the current chain)."""
    if mty.traits or not isinstance(sym, ModelSym) or sym._walks is None or id(sym) in inner:
        return None
    u = sym.unit
    if u is None or u.bundle is None or depth > MAX_DEPTH:
        return None
    hit = sym._walks.get((id(sym), (), frozenset(sub)))
    if hit is not None and (depth + hit[2] > MAX_DEPTH or not hit[1].isdisjoint(inner)):
        return None
    return hit


def _prefixed(finds: list, name: str, below: list, local) -> None:
    """The findings below a member, as paths from its owner (anchored at the member when they have no anchor)."""
    for kind, rel, shown, n, owner, a in below:
        finds.append((kind, (name,) + rel, shown, n, owner, a if a is not None else local))


def _one_per_location(found: list[tuple[str, str, str, str, str, Span]]) -> list[Unset]:
    """A model used by four wheels misses its value once, at one place: one fact naming the
    instances (`a.geometry.radius` ... `d.geometry.radius` -> `geometry.radius` in a, b, c, d)."""
    groups: dict[tuple, list[tuple[str, str, str, str, str, Span]]] = {}
    for item in found:
        kind, _full, _shown, name, owner, a = item
        groups.setdefault((kind, a.start.offset, a.end.offset, name, owner), []).append(item)
    out = []
    for items in groups.values():
        kind, full, shown, name, owner, a = items[0]
        instances: tuple[str, ...] = ()
        if len(items) > 1:
            paths = [it[1].split(".") for it in items]
            n = 0  # length of the common suffix, leaving each instance at least one part
            while all(len(p) > n + 1 for p in paths) and len({tuple(p[len(p) - n - 1:]) for p in paths}) == 1:
                n += 1
            full = ".".join(paths[0][len(paths[0]) - n:])
            instances = tuple(".".join(p[:len(p) - n]) for p in paths)
        out.append(Unset(kind == "ref", full, shown, name, owner, a, instances))
    return out
