"""The one resolver: class ordering, the override rule, and what a name or member means.

Every part of plxtools that asks "which attribute does `x` name here" or "what is `a.b` in this
expression" asks this module (through `Program`, which delegates its hierarchy questions here).
The checker wraps these answers with diagnostics, the editor features call them directly and
`plx check`'s evaluator turns them into values.

**One class ordering (linearisation).** The layers that make up a model, lowest priority first:
the base's own linearisation, then the traits the base is given inline (`is Base with T`), then the
traits applied by the model's `with` lines (in source order), then the model itself. A layer that
already appears earlier is skipped. This is the order `check/instance.py` used to configure objects
and the one the spec gives for "which assignment wins" (C.8: instance block, model body, the traits
applied by that model, then the base).

**One override rule.** A later layer's declaration replaces an earlier one, except that a plain
`is` never undoes a `becomes`: `becomes` narrows a declaration wherever it comes from (a trait may
`becomes` an attribute its host declares, spec C.3/C.4, the four `*WheelSuspension` traits). Of
the four former copies this is the one `check/instance.py` applied; `Program.all_members` let the
model's own `is` undo a trait's `becomes`, and the checker's inherited table let the base win over
every trait (`setdefault`). Both disagreed with what `plx check` builds, so they were dropped.

Everything is computed iteratively and memoised per model, so a 3,000-model inheritance chain
costs linear work per model (no recursion, no list-membership tests).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from plxtools.cache import reads
from plxtools.model.symbols import (
    UNKNOWN,
    FileUnit,
    GlobalSym,
    MemberSym,
    MethodSym,
    ModelSym,
    Namespace,
    Ty,
)
from plxtools.model.values import MethodRef, NsRef, TypeObj
from plxtools.syntax import ast

if TYPE_CHECKING:
    from plxtools.model.program import Program


# ------------------------------------------------------------------ the override rule


def replaces(old_keyword: str, new_keyword: str) -> bool:
    """Does a later layer's declaration (keyword `new_keyword`) replace an earlier one? (module doc)"""
    return not (old_keyword == "becomes" and new_keyword != "becomes")


def _apply(table: dict[str, MemberSym], members: dict[str, MemberSym]) -> None:
    for name, mem in members.items():
        old = table.get(name)
        if old is None or replaces(old.keyword, mem.keyword):
            table[name] = mem


# ------------------------------------------------------------------ linearisation


def direct_parents(p: "Program", model: ModelSym) -> list[ModelSym]:
    """What a model is built on, in increasing priority: base, base's inline traits, own traits."""
    out: list[ModelSym] = []
    base = p.base_of(model)
    if base is not None and base.model is not None:
        out.append(base.model)
        out.extend(base.traits)
    out.extend(p.traits_of(model))
    return out


def ensure(p: "Program", model: ModelSym) -> None:
    """Compute the linearisation, inherited and full member tables of `model` and what it builds on.

    Iterative post-order over the parents; a parent still in progress is part of an inheritance
    cycle (reported by the checker) and is left out.
    """
    if model._lin is None:
        _ensure(p, model)
    if reads.model_active():  # the tables are memos: whoever reads them read every layer
        for layer in model._lin or ():
            reads.note_model(("m", layer))


def _ensure(p: "Program", model: ModelSym) -> None:
    in_progress: set[int] = set()
    # the models of an inheritance cycle leave out each other, whichever the walk met first: an
    # answer that depended on where it started would differ between a fresh check and the server's
    # re-use of the last version (tests/ide/test_reuse.py)
    cycle_of: dict[int, set[int]] = {}
    stack = [model]
    while stack:
        m = stack[-1]
        if m._lin is not None:
            stack.pop()
            continue
        parents = direct_parents(p, m)
        if id(m) not in in_progress:
            in_progress.add(id(m))
            for x in parents:
                if x._lin is None and id(x) in in_progress:
                    _note_cycle(stack, x, in_progress, cycle_of)
            pending = [x for x in parents if x._lin is None and id(x) not in in_progress]
            if pending:
                stack.extend(reversed(pending))
                continue
        ring = cycle_of.get(id(m), ())
        _compute(m, [x for x in parents if x._lin is not None and id(x) not in ring])
        in_progress.discard(id(m))
        stack.pop()


def _note_cycle(stack: list, start: ModelSym, in_progress: set[int], cycle_of: dict[int, set[int]]) -> None:
    """The models on the walk's path from `start` to its top form a cycle: each notes the others."""
    at = max(i for i, s in enumerate(stack) if s is start)
    ring = {id(s) for s in stack[at:] if id(s) in in_progress}
    for k in list(ring):
        ring |= cycle_of.get(k, set())
    for k in ring:
        cycle_of[k] = ring


def _compute(m: ModelSym, parents: list[ModelSym]) -> None:
    if parents:
        # the first parent's layers are a prefix: copy its tables at C speed. `m` cannot be among
        # them: parents still in progress (a cycle through `m`) were left out by `ensure`.
        first = parents[0]
        lin = list(first._lin)
        # one parent: its tables are shared, not copied (the tables are never changed once
        # computed; a big file's thousands of `b is RigidBody:` blocks would each copy them twice)
        inherited = dict(first._all) if len(parents) > 1 else first._all
        methods = dict(first._methods) if len(parents) > 1 or m.methods else first._methods
    else:
        lin, inherited, methods = [], {}, {}
    if len(parents) > 1:
        seen = set(map(id, lin))
        for par in parents[1:]:
            for layer in par._lin:
                if id(layer) in seen:
                    continue
                seen.add(id(layer))
                lin.append(layer)
                _apply(inherited, layer.members)
                methods.update(layer.methods)
    lin.append(m)
    if m.members:
        full = dict(inherited)
        _apply(full, m.members)
    else:
        full = inherited
    if m.methods:
        methods.update(m.methods)
    m._inherited = inherited
    m._all = full
    m._methods = methods
    m._lin = lin


def linearize(p: "Program", model: ModelSym, traits: tuple = ()) -> list[ModelSym]:
    """The layers of a model (plus inline traits given at a use site), lowest priority first."""
    ensure(p, model)
    if not traits:
        return model._lin
    out = list(model._lin)
    seen = set(map(id, out))
    for t in traits:
        ensure(p, t)
        for layer in t._lin:
            if id(layer) not in seen:
                seen.add(id(layer))
                out.append(layer)
    return out


def inherited_members(p: "Program", model: ModelSym) -> dict[str, MemberSym]:
    """The attributes a model gets from its base and traits (not its own declarations)."""
    ensure(p, model)
    return model._inherited


def all_members(p: "Program", model: ModelSym) -> dict[str, MemberSym]:
    ensure(p, model)
    return model._all


def all_methods(p: "Program", model: ModelSym) -> dict[str, MethodSym]:
    ensure(p, model)
    return model._methods


def members_with_traits(p: "Program", model: ModelSym, traits: tuple) -> dict[str, MemberSym]:
    """Attributes of `model with traits` (an inline-trait type): the traits are later layers."""
    if not traits:
        return all_members(p, model)
    ensure(p, model)
    out = dict(model._all)
    seen = set(map(id, model._lin))
    for t in traits:
        ensure(p, t)
        for layer in t._lin:
            if id(layer) not in seen:
                seen.add(id(layer))
                _apply(out, layer.members)
    return out


def methods_with_traits(p: "Program", model: ModelSym, traits: tuple) -> dict[str, MethodSym]:
    if not traits:
        return all_methods(p, model)
    out = dict(all_methods(p, model))
    for layer in linearize(p, model, traits)[len(model._lin):]:
        out.update(layer.methods)
    return out


def path_members(p: "Program", outer: ModelSym | None, prefix: tuple[str, ...]) -> dict[str, MemberSym]:
    """Dotted declarations (`chassis.connector is ...`) made for `prefix` anywhere in `outer`'s layers."""
    out: dict[str, MemberSym] = {}
    if outer is None:
        return out
    for layer in linearize(p, outer):
        extra = layer.path_members.get(prefix)
        if extra:
            _apply(out, extra)
    return out


def attributes(p: "Program", ty: Ty, outer: ModelSym | None, prefix: tuple[str, ...]) -> dict[str, MemberSym]:
    """Attributes a path step may name on an object of type `ty` reached by `prefix` from `outer`:
    its type's, plus dotted declarations (`chassis.connector is ...`) made for that path."""
    out = p.members_of(ty) if not ty.unknown else {}
    extra = path_members(p, outer, prefix)
    if not extra:
        return out
    merged = dict(out)
    for k, v in extra.items():
        merged.setdefault(k, v)
    return merged


def path_target(p: "Program", ty: Ty, outer: ModelSym | None, prefix: tuple[str, ...],
                parts: list[str]) -> tuple[Ty, MemberSym | None]:
    """The type and attribute a dotted path (`a.b.c: ...`) names, starting on `ty`; UNKNOWN if a step
    does not resolve (the checker walks the same steps with `attributes` to say which one)."""
    cur = ty
    mem = None
    for name in parts:
        if cur.unknown or cur.array or cur.alts or cur.primitive is not None:
            return UNKNOWN, None
        mem = attributes(p, cur, outer, prefix).get(name)
        if mem is None:
            return UNKNOWN, None
        cur = p.member_type(mem)
        prefix = prefix + (name,)
    return cur, mem


def introduced_by(p: "Program", mem: MemberSym) -> MemberSym:
    """The `is` a `becomes` specialises: the strongest `is` of that name below the owner's layer."""
    if mem.keyword != "becomes":
        return mem
    for layer in reversed(linearize(p, mem.owner)[:-1]):
        cand = layer.members.get(mem.name)
        if cand is not None and cand.keyword == "is":
            return cand
    return mem


def has_cycle(p: "Program", model: ModelSym) -> list[ModelSym] | None:
    """The inheritance cycle `model`'s base chain runs into, if any.

    Memoised per model in `p.cycles` (the answer for every model walked), so checking every model of
    a long chain is linear overall; a set, not a list search, finds the repeat.
    """
    cache = p.cycles
    hit = cache.get(id(model))
    if hit is not None and hit[0] is model:
        return hit[1]
    trail: list[ModelSym] = []
    index: dict[int, int] = {}
    result: list[ModelSym] | None = None
    cur: ModelSym | None = model
    while cur is not None:
        hit = cache.get(id(cur))
        if hit is not None and hit[0] is cur:
            result = hit[1]
            break
        at = index.get(id(cur))
        if at is not None:
            ring = trail[at:]
            for k, m in enumerate(ring):
                cache[id(m)] = (m, ring[k:] + ring[:k] + [m])
            result = ring + [cur]
            del trail[at:]
            break
        index[id(cur)] = len(trail)
        trail.append(cur)
        base = p.base_of(cur)
        cur = base.model if base is not None else None
    for m in trail:
        cache[id(m)] = (m, result)
    return cache[id(model)][1]


def is_open(p: "Program", model: ModelSym) -> bool:
    """True when some base in the layers does not resolve: attributes are unknown, not absent."""
    if model._open is not None:  # known (reset with the linearisation when the program changes)
        return model._open
    for layer in linearize(p, model):  # parents come before the layers built on them
        if layer._open is None:
            # an import plx cannot read (an .agx archive, a URDF) has no base: its contents are unknown
            own = (layer.base_ref is not None and p.base_of(layer) is None) or (
                layer.kind == "import" and layer.base_ref is None)
            layer._open = own or any(x._open for x in direct_parents(p, layer) if x._open is not None)
    return bool(model._open)


def opaque_import(p: "Program", model: ModelSym) -> ModelSym | None:
    """The import plx cannot read that `model` builds on (itself, a base or a trait), if any."""
    for layer in linearize(p, model):
        if layer.kind == "import" and layer.base_ref is None:
            return layer
    return None


def is_subtype(p: "Program", sub: ModelSym, sup: ModelSym, extra_traits: tuple = ()) -> bool:
    if sub is sup:
        return True
    return any(m is sup for m in linearize(p, sub, extra_traits))


# ------------------------------------------------------------------ statements to symbols


def symbol_of_top(unit: FileUnit, stmt: ast.Stmt) -> ModelSym | GlobalSym | None:
    """The model, trait or global a top-level statement defines (None if it defines nothing)."""
    if isinstance(stmt, ast.TraitDef):
        name = stmt.name.name
    elif isinstance(stmt, ast.Declaration) and stmt.path.parts:
        name = stmt.path.parts[0].name
    else:
        return None
    table = unit.locals if unit.bundle is None else unit.namespace.symbols
    sym = table.get(name)
    if sym is not None and getattr(sym, "stmt", None) is stmt:
        return sym
    return None


def declared_member(model_def: ModelSym | None, stmt: ast.Declaration) -> MemberSym | None:
    """The attribute a declaration in a model's (or instance block's) body creates."""
    if model_def is None or not stmt.path.parts:
        return None
    name = stmt.path.parts[-1].name
    if len(stmt.path.parts) == 1:
        mem = model_def.members.get(name)
    else:
        mem = model_def.path_members.get(tuple(x.name for x in stmt.path.parts[:-1]), {}).get(name)
    return mem if mem is not None and mem.stmt is stmt else None


# ------------------------------------------------------------------ names and members in expressions


def global_meaning(p: "Program", found):
    """What a symbol found by lookup means in an expression: a Ty (a value of that type), a TypeObj
    (a type used for static calls), an NsRef, or None. A const model is its own single instance."""
    if found is None:
        return None
    if isinstance(found, Namespace):
        return NsRef(found)
    if isinstance(found, GlobalSym):
        if found.ty is None:
            found.ty = p.resolve_type_expr(found.stmt.type, found.unit)
        return found.ty
    if isinstance(found, ModelSym):
        return Ty(found) if found.const else TypeObj(found)
    if isinstance(found, str):
        return TypeObj(found)
    return None


def name_target(p: "Program", unit: FileUnit, outer: ModelSym | None, name: str, lookup=None):
    """The symbol a bare name in an expression refers to: an attribute of the enclosing model,
    else a global name (namespace, global value, model, primitive); None if nothing. `lookup`:
    the caller's `p.lookup(parts, unit)` (the checker remembers its answers per file)."""
    if outer is not None:
        mem = all_members(p, outer).get(name)
        if mem is not None:
            return mem
    return p.lookup([name], unit) if lookup is None else lookup([name])


def member_target(p: "Program", base, name: str):
    """The symbol `.name` refers to on an expression's meaning (`base` as `global_meaning` gives it):
    a namespace entry, a static method (MethodRef on_type), an attribute or a method; None if none."""
    if isinstance(base, NsRef):
        return p._walk(base.ns, [name])
    if isinstance(base, TypeObj):
        if isinstance(base.sym, ModelSym):
            meth = all_methods(p, base.sym).get(name)
            if meth is not None:
                return MethodRef(meth, True)
        return None
    if isinstance(base, Ty) and not base.unknown and base.model is not None and not base.array and not base.alts:
        mem = p.members_of(base).get(name)
        if mem is not None:
            return mem
        meth = p.methods_of(base).get(name)
        if meth is not None:
            # a const model is its own single instance: Math.Functions.sin(x) is the normal call
            return MethodRef(meth, bool(base.model.const and meth.static))
    return None


def meaning(p: "Program", target):
    """The expression meaning of a resolved target (attribute -> its type, method -> MethodRef...)."""
    if isinstance(target, MemberSym):
        return p.member_type(target)
    if isinstance(target, MethodRef):
        return target
    return global_meaning(p, target)


def call_result(p: "Program", f) -> Ty | None:
    """The type a call of a MethodRef returns (None: not callable or returns nothing)."""
    if isinstance(f, MethodRef) and f.method.stmt.returns is not None:
        return p.resolve_type_ref(f.method.stmt.returns, f.method.owner.unit)
    return None
