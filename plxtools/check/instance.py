"""Instantiate a model: the object tree with dotted paths, before any value is computed.

How an object is put together (spec C.3-C.8):

* Every model body is flattened once into *effects* (:class:`TEff`): declarations (``a is T``,
  ``a becomes T``), values (``a.b: expr``, ``a is T: expr``) and ``with`` lines, each with a path
  relative to the object the body configures.  A block under a declaration or an assignment adds
  its statements with the longer path.
* The effects that apply to an object are, lowest priority first: the bodies of its type's
  linearisation (base-most model first; a model's traits above its base; the model's own body on
  top), then the effects its owners route down to it (an instance block, dotted assignments such as
  ``kinematics.local_transform.position.z: 1.1`` in an enclosing model), in the owners' order.  The
  last effect wins.  This gives "instance block > model body > its traits > base" and lets an
  enclosing model override anything inside.
* Every effect carries its *scope*: the instance of the outermost model whose body (or trait body)
  holds the statement.  Expressions are evaluated there (C.6), so ``radius: radius`` in a nested
  block reads the outer model's ``radius`` and ``source: this`` is the body or hinge itself.
* A model-typed attribute owns a new object unless it is given an existing one: a value effect on a
  non-struct model attribute makes it a :class:`Ref` (``connectors: [...]``, ``group1: own_parts``,
  ``material: TireMaterial``); so does a ``reference`` declaration; ``x is SomeConstModel`` aliases
  the singleton.
* Value types (``Math.Vec3``, ``Quat``, ``AffineTransform``, ``Matrix3x3``...) are *struct objects*:
  they keep all their effects in one ordered list, so a whole-value assignment
  (``position: {1, 2, 3}``) and a field assignment (``position.z: 1.1``) compete by priority.

Nothing here evaluates an expression; :mod:`plxtools.check.evaluate` does that, lazily.
"""

from __future__ import annotations

from dataclasses import dataclass
from collections.abc import Mapping
from typing import Any

from plxtools.model.natives import struct_types
from plxtools.model.program import Program
from plxtools.model.resolve import opaque_import, replaces
from plxtools.model.symbols import FileUnit, ModelSym, Ty
from plxtools.syntax import ast
from plxtools.rules import registry


DECL, VALUE, WITH = 0, 1, 2
MAX_DEPTH = 48  # nesting of owned objects from which a model met again among the owners contains itself
MAX_NESTING = 500  # distinct models nested deeper than this are not instantiated: a limit, not a cycle


@dataclass(slots=True, eq=False)
class TEff:
    """One effect of a model body, before it is bound to an object (a template)."""

    kind: int
    path: tuple[str, ...]
    stmt: ast.Stmt
    unit: FileUnit
    expr: Any = None  # VALUE: the expression
    ty: Ty | None = None  # DECL: the declared type (resolved in ``unit``)
    optional: bool = False
    reference: bool = False
    traits: tuple = ()  # WITH: trait ModelSyms


# A bound effect: (template, scope object, depth).  ``template.path[depth:]`` is the path relative
# to the object holding the effect list.
Eff = tuple


@dataclass(slots=True, eq=False)
class Prim:
    """A primitive, array or union attribute of a non-struct object."""

    name: str
    ty: Ty | None
    decl: Eff
    value: Eff | None
    optional: bool


@dataclass(slots=True, eq=False)
class Ref:
    """An attribute that refers to an object instead of owning one."""

    name: str
    path: str
    owner: "Obj"
    ty: Ty
    decl: Eff
    value: Eff | None  # None: unbound (or a const alias when ``const_model`` is set)
    optional: bool
    reference: bool
    const_model: ModelSym | None = None


class _NoMembers(Mapping):
    """The members of an object that has none: empty, and read-only (it is shared)."""

    __slots__ = ()
    __hash__ = object.__hash__

    def __getitem__(self, key):
        raise KeyError(key)

    def __iter__(self):
        return iter(())

    def __len__(self) -> int:
        return 0


_NO_MEMBERS = _NoMembers()


@dataclass(slots=True, eq=False)
class Obj:
    """One model instance.  ``path`` is dotted from the root (the root itself has path "")."""

    name: str
    path: str
    model: ModelSym
    traits: tuple
    owner: "Obj | None"
    decl: Eff | None  # the winning declaration that created it (None for the root / singletons)
    struct: str | None = None  # the struct_types() name for value types
    # An object has either effects (a struct object) or members (the others): the containers it
    # does not fill stay shared read-only empties, not four new ones per object (a model of many
    # bodies has some 14 objects per body)
    effects: list | tuple = ()  # struct objects only: every effect, in order
    children: dict = _NO_MEMBERS  # name -> Obj | Ref
    prims: dict = _NO_MEMBERS  # name -> Prim
    order: list | tuple = ()  # member names in declaration order
    explicit: bool = False  # an owner routed a value to it (or below it): "declared" by the user
    singleton: bool = False
    cut: bool = False  # a model containing itself starts to repeat here: dropped by its owner (A009)

    @property
    def display(self) -> str:
        return self.path or self.model.name

    def __repr__(self) -> str:
        return f"<Obj {self.display}: {self.model.qname}>"


class Builder:
    """Builds object trees over a :class:`Program`.  Template and linearisation caches are shared."""

    def __init__(self, program: Program, report=None):
        self.p = program
        self.structs = struct_types(program)  # Vec3, Quat, ... as this program's bundles declare them
        self.report = report  # callable(code, message, obj) for instantiation problems
        self._templates: dict[int, list[TEff]] = {}
        self._struct: dict[int, str | None] = {}
        self._plans: dict = {}
        self.singletons: dict[int, Obj] = {}
        self._building_singletons: set[int] = set()
        self.objects = 0
        self.too_deep: list[Obj] = []
        self.opaque: list[tuple[Obj, ModelSym]] = []  # objects built on an import plx cannot read
        self._opaque_of: dict[int, ModelSym | None] = {}

    # ------------------------------------------------------------------ types

    def struct_name(self, model: ModelSym | None) -> str | None:
        """The value-type name when ``model`` is (a subtype of) Math.Vec3, Quat, AffineTransform..."""
        if model is None:
            return None
        key = id(model)
        if key not in self._struct:
            found = None
            for m in self.p.ancestors(model):
                if not m.anonymous and m.qname in self.structs:
                    found = m.qname
                    break
            self._struct[key] = found
        return self._struct[key]

    def layers(self, model: ModelSym, traits: tuple = ()) -> list[ModelSym]:
        """Models whose bodies configure an instance, lowest priority first (model/resolve.py's order)."""
        return self.p.linearize(model, traits)

    def templates(self, model: ModelSym) -> list[TEff]:
        cached = self._templates.get(id(model))
        if cached is not None:
            return cached
        out: list[TEff] = []
        body = getattr(model.stmt, "body", None) if model.stmt is not None else None
        if body and model.unit is not None and not model.anonymous:
            self._flatten(body, (), model.unit, out, top=True)
        self._templates[id(model)] = out
        return out

    def _flatten(self, body: list, prefix: tuple, unit: FileUnit, out: list, top: bool = False) -> None:
        for s in body:
            if isinstance(s, ast.Declaration) and s.keyword in ("is", "becomes"):
                path = prefix + tuple(p.name for p in s.path.parts)
                ty = self.p.resolve_type_expr(s.type, unit)
                out.append(TEff(DECL, path, s, unit, ty=ty, optional=s.optional, reference=s.reference))
                if s.value is not None:
                    out.append(TEff(VALUE, path, s, unit, expr=s.value))
                if s.body:
                    self._flatten(s.body, path, unit, out)
            elif isinstance(s, ast.Assignment):
                path = prefix + tuple(p.name for p in s.path.parts)
                if s.value is not None:
                    out.append(TEff(VALUE, path, s, unit, expr=s.value))
                if s.body:
                    self._flatten(s.body, path, unit, out)
            elif isinstance(s, ast.WithStmt) and not top:
                traits = []
                for q in s.traits:
                    t = self.p.lookup([p.name for p in q.parts], unit)
                    if isinstance(t, ModelSym) and t.is_trait:
                        traits.append(t)
                if traits:
                    out.append(TEff(WITH, prefix, s, unit, traits=tuple(traits)))

    # ------------------------------------------------------------------ objects

    def root(self, model: ModelSym) -> Obj:
        obj = Obj(model.name, "", model, (), None, None)
        self._build(obj, model, (), [], 0)
        return obj

    def singleton(self, model: ModelSym) -> Obj | None:
        """The single instance of a const model (None while it is being built: a cycle)."""
        key = id(model)
        obj = self.singletons.get(key)
        if obj is not None:
            return obj
        if key in self._building_singletons:
            return None
        self._building_singletons.add(key)
        try:
            obj = Obj(model.name, model.qname, model, (), None, None, singleton=True)
            self._build(obj, model, (), [], 0)
            self.singletons[key] = obj
            return obj
        finally:
            self._building_singletons.discard(key)

    def _plan(self, model: ModelSym, traits: tuple) -> tuple:
        """The own-layer effects of a type, routed once: (struct name, templates, routing)."""
        key = id(model) if not traits else (id(model), tuple(id(x) for x in traits))
        plan = self._plans.get(key)
        if plan is not None:
            return plan
        templates = [tm for m in self.layers(model, traits) for tm in self.templates(m)]
        struct = self.struct_name(model)
        if struct is not None:
            plan = (struct, templates, None)
        else:
            decls: dict[str, TEff] = {}
            order: list[str] = []
            flags: dict[str, tuple] = {}
            routed: dict[str, list] = {}
            for tm in templates:
                if not tm.path:
                    continue
                name = tm.path[0]
                if tm.kind == DECL and len(tm.path) == 1:
                    if name not in decls:
                        order.append(name)
                        flags[name] = (tm.optional, tm.reference)
                    else:
                        o, r = flags[name]
                        flags[name] = (o or tm.optional, r or tm.reference)
                        if not replaces(decls[name].stmt.keyword, tm.stmt.keyword):
                            continue
                    decls[name] = tm
                    continue
                routed.setdefault(name, []).append(tm)
            plan = (None, templates, (decls, order, flags, routed))
        self._plans[key] = plan
        return plan

    def opaque_import(self, obj: Obj) -> ModelSym | None:
        """The import plx cannot read (an .agx archive, a URDF) that an object's type builds on."""
        key = id(obj.model)
        if key not in self._opaque_of:
            self._opaque_of[key] = opaque_import(self.p, obj.model)
        return self._opaque_of[key]

    def _build(self, obj: Obj, model: ModelSym, traits: tuple, received: list, depth: int) -> None:
        """Fill ``obj``: its type's own effects (the plan) under the effects its owners route down to
        it (``received``), then one member after another."""
        self.objects += 1
        imported = self.opaque_import(obj)
        if imported is not None:
            # its contents live in a file plx cannot read: nothing in it is instantiated (the
            # pipeline says so once, A042), so nothing about it is reported as missing or wrong
            self.opaque.append((obj, imported))
            return
        struct, templates, info = self._plan(model, traits)
        for e in received:
            if e[0].kind == VALUE:
                obj.explicit = True
                break
        obj.struct = struct
        if struct is not None:
            effs = [(tm, obj, 0) for tm in templates]
            effs.extend(received)
            obj.effects = effs
            return
        if depth > MAX_DEPTH and self._stops_too_deep(obj, depth):
            return
        obj.children, obj.prims, obj.order = {}, {}, []
        decls, flags, routed = _merge_received(obj, info, received)
        own_routed = info[3]
        prefix = obj.path + "." if obj.path else ""
        for name in obj.order:
            own = own_routed.get(name)
            ce = [(tm, obj, 1) for tm in own] if own else []
            more = routed.get(name)
            if more:
                ce.extend(more)
            self._member(obj, name, decls[name], flags[name], ce, prefix + name, depth)

    def _stops_too_deep(self, obj: Obj, depth: int) -> bool:
        """Past MAX_DEPTH: stop (A009) at a model that contains itself, or past MAX_NESTING."""
        loop = _same_model_above(obj) if depth <= MAX_NESTING else None
        if loop is None and depth <= MAX_NESTING:
            return False
        cut = _first_repeat(obj) if loop is not None else None
        if cut is not None:
            # the ring is cut where it starts: the first object that repeats an owner's model is not
            # built at all, so nothing below it (bodies without mass, unplaced) is reported as well
            cut.cut = True
            obj = cut
        self.too_deep.append(obj)
        if self.report is not None:
            self.report(registry.INSTANTIATION_TOO_DEEP, _too_deep_message(obj, depth, loop), obj)
        return True

    def _member(self, obj: Obj, name: str, e: Eff, flags: list, ce: list, path: str, depth: int) -> None:
        """One member of ``obj``, from its winning declaration ``e`` and the effects routed to it
        (``ce``): a primitive, a reference to another object, or an owned object built in turn."""
        ty = e[0].ty
        optional, reference = flags
        whole = None  # the last effect that gives the member a whole value (not one of its fields)
        for x in ce:
            if x[0].kind == VALUE and len(x[0].path) == x[2]:
                whole = x
        if ty is None or ty.unknown or ty.alts or ty.array or ty.primitive is not None or ty.model is None:
            obj.prims[name] = Prim(name, ty, e, whole, optional)  # a primitive, array, union or unknown type
            return
        cmodel = ty.model
        is_struct = self.struct_name(cmodel) is not None
        if not is_struct:
            if whole is not None or reference or cmodel.is_trait:
                obj.children[name] = Ref(name, path, obj, ty, e, whole, optional, reference)
                return
            if cmodel.const:
                obj.children[name] = Ref(name, path, obj, ty, e, None, optional, reference, const_model=cmodel)
                return
        ctraits = tuple(ty.traits)
        sub = []
        for x in ce:
            if x[0].kind == WITH and len(x[0].path) == x[2]:
                ctraits = ctraits + tuple(tr for tr in x[0].traits if tr not in ctraits)
            else:
                sub.append(x)
        child = Obj(name, path, cmodel, ctraits, obj, e)
        obj.children[name] = child
        self._build(child, cmodel, ctraits, sub, depth + 1)
        if child.cut:
            del obj.children[name]


def _merge_received(obj: Obj, info: tuple, received: list) -> tuple[dict, dict, dict]:
    """The members of a non-struct object: its plan's declarations, then those its owners route to
    it (a later one replaces an earlier one as model/resolve.py says), in ``obj.order``; and the
    effects routed further down, per member.  Returns (declarations, [optional, reference] flags,
    routed effects) by member name."""
    own_decls, own_order, own_flags, _own_routed = info
    decls: dict[str, Eff] = {}
    flags: dict[str, list] = {}
    order = obj.order
    for name in own_order:
        order.append(name)
        decls[name] = (own_decls[name], obj, 0)
        flags[name] = list(own_flags[name])
    routed: dict[str, list] = {}
    for e in received:
        t, _scope, d = e
        rest = len(t.path) - d
        if rest <= 0:
            continue  # a whole value on a non-struct object: decided by the owner (a Ref)
        name = t.path[d]
        if t.kind == DECL and rest == 1:
            _declare(name, e, decls, flags, order)
            continue
        lst = routed.get(name)
        if lst is None:
            lst = routed[name] = []
        lst.append((t, e[1], d + 1))
    return decls, flags, routed


def _declare(name: str, e: Eff, decls: dict, flags: dict, order: list) -> None:
    """A declaration an owner routes to a member: a new member, or one more declaration of it."""
    t = e[0]
    if name not in decls:
        order.append(name)
        flags[name] = [t.optional, t.reference]
    else:
        f = flags[name]
        f[0] = f[0] or t.optional
        f[1] = f[1] or t.reference
        # the override rule of model/resolve.py: a later plain `is` does not undo a `becomes`
        if not replaces(decls[name][0].stmt.keyword, t.stmt.keyword):
            return
    decls[name] = e


def _same_model_above(obj: Obj) -> list[Obj] | None:
    """The owners from the nearest one of the same model and traits down to `obj` (a model that
    contains itself), or None when every owner is of another model (deep, but finite)."""
    chain = [obj]
    o = obj.owner
    while o is not None:
        chain.append(o)
        if o.model is obj.model and o.traits == obj.traits:
            return chain[::-1]
        o = o.owner
    return None


def _first_repeat(obj: Obj) -> Obj | None:
    """The highest object above (or at) `obj` whose model and traits an owner of it already has:
    where a model that contains itself starts to repeat."""
    chain = []
    o = obj
    while o is not None:
        chain.append(o)
        o = o.owner
    chain.reverse()  # root first
    for i, o in enumerate(chain):
        if any(a.model is o.model and a.traits == o.traits for a in chain[:i]):
            return o
    return None


def _too_deep_message(obj: Obj, depth: int, loop: list[Obj] | None) -> str:
    parts = obj.display.split(".")
    shown = obj.display if len(parts) <= 6 else ".".join(parts[:3]) + ". ... ." + ".".join(parts[-2:])
    if loop is None:
        return (f"{shown} is nested {depth} objects deep, more than plx check instantiates ({MAX_NESTING}); "
                "no model contains itself, but its members are not instantiated")
    names = [o.model.name for o in loop]
    through = " -> ".join(names if len(names) <= 6 else names[:3] + ["..."] + names[-2:])
    return (f"{shown} is nested {depth} objects deep: {obj.model.name} contains itself ({through}); "
            "its members are not instantiated")


def walk_owned(root: Obj):
    """Every owned object below ``root`` (not references, not singletons), depth first, in
    declaration order; ``root`` itself first."""
    stack = [root]
    while stack:
        obj = stack.pop()
        yield obj
        kids = [c for c in (obj.children.get(n) for n in obj.order) if isinstance(c, Obj)]
        stack.extend(reversed(kids))
