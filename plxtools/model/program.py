"""The program: every loaded file's symbols in one namespace tree, and the lookups over it.

Name lookup follows the spec's rule (C.2): inside namespace N1.N2.N3 a dotted name A.B is tried as
N1.N2.N3.A.B, N1.N2.A.B, N1.A.B, then A.B from the root; the first full match wins.
"""

from __future__ import annotations

import re
from typing import Iterable

from plxtools.cache import reads
from plxtools.model import resolve
from plxtools.model.symbols import (
    NUMERIC,
    PRIMITIVES,
    UNKNOWN,
    FileUnit,
    GlobalSym,
    MemberSym,
    MethodSym,
    ModelSym,
    Namespace,
    OperatorSym,
    Ty,
    doc_of,
)
from plxtools.syntax import ast

_DEPRECATED_DOC = re.compile(r"^\s*(\w+)\s*[-:]\s*(.*deprecated.*)$", re.I | re.M)


def compose_type(alts: list[Ty], traits: list[ModelSym]) -> Ty:
    """The type of a type expression from its resolved alternatives and the models named after `with`.

    The one answer for lint's checker and everything else (completion, completeness, check): only a
    trait is applied; a model named after `with` is reported by lint (N005) and adds no members here.
    """
    applied = tuple(t for t in traits if t.is_trait)
    if len(alts) == 1:
        a = alts[0]
        if a.unknown:
            return UNKNOWN
        return a if not applied and not a.traits else Ty(a.sym, a.array, applied)
    if any(a.unknown for a in alts):
        return UNKNOWN
    return Ty(alts=tuple(alts))


class Program:
    def __init__(self) -> None:
        self.root = Namespace("", ())
        self.units: dict[str, FileUnit] = {}
        self.operators: dict[str, list[OperatorSym]] = {}
        self.visibility: dict[str, set[str]] = {}  # bundle -> visible bundle names
        self.official_bundles: set[str] = set()
        self.duplicates: list[tuple[FileUnit, ast.Stmt, object]] = []  # (unit, stmt, first symbol)
        self.cycles: dict[int, tuple] = {}  # id(model) -> (model, inheritance cycle or None): resolve.py
        self._comments: tuple = (None, {})  # (tree, own-line comments by line) of the file being added
        # changes any file may see (bundle files added or removed, member tables reset), and how many
        # of them each file caused: model/reuse.py re-uses a file's check while no other file changed
        self.epoch = 0
        self.caused: dict[str, int] = {}

    # ------------------------------------------------------------------ building

    def namespace(self, qname: tuple[str, ...], bundle: str | None) -> Namespace:
        ns = self.root
        for part in qname:
            ns = ns.child(part, bundle)
        return ns

    def add_unit(self, unit: FileUnit) -> None:
        self.units[unit.path] = unit
        if unit.bundle is not None:
            self._changed(unit.path)
        for stmt in unit.tree.statements:
            self._add_top(unit, stmt)
        self._comments = (None, {})

    def remove_unit(self, path: str) -> None:
        """Forget a file's symbols (the language server replaces a file on every edit).

        Only a bundle file's symbols can be named by other files, so only removing one of those
        resets the cached member tables of every model.
        """
        unit = self.units.pop(path, None)
        if unit is None:
            return
        if unit.bundle is not None:
            self._changed(path)
        targets = [unit.namespace.symbols, unit.locals]
        removed = []
        for table in targets:
            for name in [n for n, s in table.items() if getattr(s, "unit", None) is unit]:
                removed.append(table.pop(name))
        for op, lst in self.operators.items():
            self.operators[op] = [o for o in lst if o.unit is not unit]
        self.duplicates = [d for d in self.duplicates if d[0] is not unit]
        self.cycles.clear()
        if unit.bundle is not None:
            self.invalidate(path)
        else:
            _dismantle(removed)

    def _changed(self, path: str | None) -> None:
        self.epoch += 1
        if path is not None:
            self.caused[path] = self.caused.get(path, 0) + 1

    def epoch_without(self, path: str) -> int:
        """The changes to the program that other files made (a loose file's changes are nobody's)."""
        return self.epoch - self.caused.get(path, 0)


    def invalidate(self, cause: str | None = None) -> None:
        """Drop cached member tables and resolved types (after files changed; `cause`: the file)."""
        self._changed(cause)
        self.cycles.clear()
        for ns in self._all_namespaces():
            for sym in ns.symbols.values():
                self._reset(sym)
        for unit in self.units.values():
            for sym in unit.locals.values():
                self._reset(sym)

    def _reset(self, sym) -> None:
        if isinstance(sym, ModelSym):
            stack = [sym]
            while stack:
                m = stack.pop()
                m._lin = m._inherited = m._all = m._methods = m._open = m._walks = None
                m.base = None
                m.traits = None
                for mem in m.members.values():
                    mem.ty = None
                    if mem.anon is not None:
                        stack.append(mem.anon)
                for extra in m.path_members.values():
                    for mem in extra.values():
                        mem.ty = None
                        if mem.anon is not None:
                            stack.append(mem.anon)
        elif isinstance(sym, GlobalSym):
            sym.ty = None

    def _all_namespaces(self) -> Iterable[Namespace]:
        stack = [self.root]
        while stack:
            ns = stack.pop()
            yield ns
            stack.extend(ns.children.values())

    def all_models(self) -> Iterable[ModelSym]:
        """Every named model and trait of the program (bundles' namespaces, then loose files')."""
        for ns in self._all_namespaces():
            for sym in ns.symbols.values():
                if isinstance(sym, ModelSym):
                    yield sym
        for unit in self.units.values():
            for sym in unit.locals.values():
                if isinstance(sym, ModelSym):
                    yield sym

    def _register(self, unit: FileUnit, name: str, sym, stmt: ast.Stmt) -> None:
        table = unit.locals if unit.bundle is None else unit.namespace.symbols
        if unit.bundle is not None and name in unit.locals:  # a bundle file's own import of that name
            self.duplicates.append((unit, stmt, unit.locals[name]))
            return
        if name in table:
            self.duplicates.append((unit, stmt, table[name]))
            return
        table[name] = sym

    def _add_top(self, unit: FileUnit, stmt: ast.Stmt) -> None:
        ns = unit.namespace
        if isinstance(stmt, ast.Declaration) and stmt.keyword != "becomes" and len(stmt.path.parts) == 1:
            name = stmt.path.parts[0].name
            if unit.path.endswith("config.openplx") and name == "config":
                return
            is_global = stmt.keyword == "is" and stmt.value is not None and stmt.body is None
            qname = f"{ns.dotted}.{name}" if ns.dotted else name
            if is_global:
                self._register(unit, name, GlobalSym(name, qname, stmt, unit, ns), stmt)
                return
            model = ModelSym(name, qname, "model", stmt, unit, ns, const=stmt.const, base_ref=stmt.type)
            self._fill_model(model, stmt.body, unit)
            self._register(unit, name, model, stmt)
        elif isinstance(stmt, ast.TraitDef):
            name = stmt.name.name
            qname = f"{ns.dotted}.{name}" if ns.dotted else name
            trait = ModelSym(name, qname, "trait", stmt, unit, ns)
            if stmt.base is not None:
                trait.base_ref = ast.TypeExpr(stmt.base.span, [ast.TypeRef(stmt.base.span, stmt.base)])
            self._fill_model(trait, stmt.body, unit)
            self._register(unit, name, trait, stmt)
        elif isinstance(stmt, ast.OperatorDecl):
            self.operators.setdefault(stmt.op, []).append(OperatorSym(stmt.op, stmt, unit))
        elif isinstance(stmt, ast.Import):
            self._add_import(unit, stmt)

    def _add_import(self, unit: FileUnit, stmt: ast.Import) -> None:
        """An import binds a name in the file's own scope (`unit.locals`, bundle files included);
        `as ns.name` binds `name` in a namespace `ns` of that file only (model/imports.py)."""
        from plxtools.model.imports import import_symbol

        made = import_symbol(stmt, unit, unit.namespace)
        if made is None:
            return  # a name the checker reports (N007)
        parts, sym = made
        doc = sym.doc
        self._fill_model(sym, sym.stmt.body, unit)
        sym.doc = doc
        table = unit.locals
        for i, part in enumerate(parts[:-1]):
            ns = table.get(part)
            if ns is None:
                ns = Namespace(part, tuple(parts[:i + 1]))
                table[part] = ns
            elif not isinstance(ns, Namespace):
                self.duplicates.append((unit, sym.stmt, ns))
                return
            table = ns.symbols
        if parts[-1] in table:
            self.duplicates.append((unit, sym.stmt, table[parts[-1]]))
            return
        table[parts[-1]] = sym

    def _fill_model(self, model: ModelSym, body: list[ast.Stmt] | None, unit: FileUnit) -> None:
        if not body:
            return
        model.doc = doc_of(body)
        if model.doc:
            for m in _DEPRECATED_DOC.finditer(model.doc):
                model.deprecated[m.group(1)] = m.group(2).strip()
        if self._comments[0] is not unit.tree:  # once per file, not once per model
            self._comments = (unit.tree, _comment_lines(unit.tree))
        comments_above = self._comments[1]
        for s in body:
            if isinstance(s, ast.Declaration) and s.keyword in ("is", "becomes"):
                mem = MemberSym(s.path.parts[-1].name, model, s, s.keyword, s.optional, s.reference, s.value)
                mem.doc = doc_of(s.body)
                note = comments_above.get(s.header.start.line - 1)
                if note and "deprecated" in note.lower() and mem.name in note:
                    model.deprecated.setdefault(mem.name, note.lstrip("# ").strip())
                if s.body is not None and len(s.type.alternatives) == 1 and not s.reference:
                    mem.anon = self._anon(model, s, unit)
                if len(s.path.parts) == 1:
                    if mem.name in model.members:
                        self.duplicates.append((unit, s, model.members[mem.name]))
                    else:
                        model.members[mem.name] = mem
                else:
                    key = tuple(p.name for p in s.path.parts[:-1])
                    model.path_members.setdefault(key, {})[mem.name] = mem
            elif isinstance(s, ast.Assignment):
                model.assignments.append(s)
            elif isinstance(s, ast.WithStmt):
                model.trait_refs.extend(s.traits)
            elif isinstance(s, ast.Method):
                model.methods[s.name.name] = MethodSym(s.name.name, model, s, s.static)
            elif isinstance(s, ast.Annotation):
                model.annotations.append(s)

    def _anon(self, owner: ModelSym, decl: ast.Declaration, unit: FileUnit) -> ModelSym:
        name = decl.path.text
        texpr = decl.type  # its first alternative is the base: the declaration's own node when it has one
        base_ref = texpr if len(texpr.alternatives) == 1 else ast.TypeExpr(texpr.span, texpr.alternatives[:1],
                                                                           texpr.traits)
        anon = ModelSym(name, f"{owner.qname}.{name}", "model", decl, unit, owner.namespace, anonymous=True,
                        base_ref=base_ref)
        self._fill_model(anon, decl.body, unit)
        return anon

    # ------------------------------------------------------------------ lookup

    def visible(self, unit: FileUnit) -> set[str] | None:
        """Bundle names a file may name; None means all of them (loose files see every bundle)."""
        if unit.bundle is None:
            return None
        return self.visibility.get(unit.bundle)

    def lookup(self, parts: list[str], unit: FileUnit, namespace: Namespace | None = None):
        """Resolve a dotted name to a symbol, namespace or primitive name; None if nothing matches."""
        if reads.model_active():
            reads.note_model(("n", parts[0]))  # a definition of this name, added or changed, changes the answer
        if len(parts) == 1 and parts[0] in PRIMITIVES:
            return parts[0]
        if parts[0] in unit.locals:  # a loose file's definitions, any file's imports
            return self._walk(unit.locals[parts[0]], parts[1:])
        ns = namespace or unit.namespace
        chain: list[Namespace] = []
        while ns is not None and ns is not self.root:
            chain.append(ns)
            ns = ns.parent
        for start in chain:
            found = self._walk(start, parts)
            if found is not None:
                return found
        visible = self.visible(unit)
        if visible is not None and parts[0] in self.root.children and parts[0] not in visible:
            return None
        return self._walk(self.root, parts)

    def lookup_outside_visibility(self, parts: list[str]):
        return self._walk(self.root, parts)

    def _walk(self, start, parts: list[str]):
        cur = start
        for i, part in enumerate(parts):
            if isinstance(cur, Namespace):
                last = i == len(parts) - 1
                child = cur.children.get(part)
                sym = cur.symbols.get(part)
                if not last and child is not None:
                    cur = child
                elif sym is not None:
                    cur = sym
                elif child is not None:
                    cur = child
                else:
                    return None
            else:
                return None
        return cur

    # ------------------------------------------------------------------ types

    def archive_name(self, parts: list[str], unit: FileUnit):
        """The opaque model a name stands for when only an import plx cannot read can define it.

        An `.agx` archive (or a URDF) defines names plx cannot see: `import @"pendulum.agx"` binds
        `pendulum`, and the archive's bodies keep their AGX names (`PendulumScene_rod`). A one-part
        name that nothing in scope defines, in a file with such an import, is one of those: unknown,
        not wrong. It is a model of kind "import" without a base (model/imports.py), so it is open
        (no missing-attribute cascades) and `plx check` names it as not analysed.
        """
        from plxtools.model.imports import ImportSym

        if len(parts) != 1 or parts[0] in PRIMITIVES:
            return None
        cache = getattr(unit, "archive", None)  # None: a unit unpickled from before the field existed
        if cache is not None and parts[0] in cache:
            return cache[parts[0]]
        source = next((s for s in unit.locals.values() if isinstance(s, ImportSym) and s.opaque), None)
        if source is None or self.lookup(parts, unit) is not None:
            return None
        stmt = source.import_stmt
        sym = ImportSym(parts[0], parts[0], "import", source.stmt, unit, unit.namespace, import_stmt=stmt,
                        file_kind="opaque", suffix=source.suffix)
        sym.doc = f"a name plx cannot see: it can only come from {source.written}, which plx cannot read"
        if cache is not None:
            cache[parts[0]] = sym
        return sym

    def resolve_type_ref(self, ref: ast.TypeRef, unit: FileUnit) -> Ty:
        found = self.lookup([p.name for p in ref.name.parts], unit)
        if found is None:
            found = self.archive_name([p.name for p in ref.name.parts], unit)
        if isinstance(found, str):
            return Ty(found, ref.array)
        if isinstance(found, ModelSym):
            return Ty(found, ref.array)
        return UNKNOWN

    def resolve_type_expr(self, texpr: ast.TypeExpr | None, unit: FileUnit) -> Ty:
        if texpr is None:
            return UNKNOWN
        alts = [self.resolve_type_ref(r, unit) for r in texpr.alternatives]
        found = (self.lookup([p.name for p in q.parts], unit) for q in texpr.traits)
        return compose_type(alts, [t for t in found if isinstance(t, ModelSym)])

    def base_of(self, model: ModelSym) -> Ty | None:
        if reads.model_active():
            reads.note_model(("m", model))
        if model.base is None:
            if model.base_ref is None or model.unit is None:
                model.base = UNKNOWN
            else:
                model.base = self.resolve_type_expr(model.base_ref, model.unit)
        if model.base.model is not None and reads.model_active():
            reads.note_model(("m", model.base.model))
        return model.base if not model.base.unknown else None

    def traits_of(self, model: ModelSym) -> list[ModelSym]:
        if reads.model_active():
            reads.note_model(("m", model))
        if model.traits is None:
            out = []
            if model.unit is not None:
                for q in model.trait_refs:
                    t = self.lookup([p.name for p in q.parts], model.unit)
                    if isinstance(t, ModelSym) and t.is_trait:
                        out.append(t)
            base = model.base_ref
            if model.unit is not None and base is not None and base.traits:
                for q in base.traits:
                    t = self.lookup([p.name for p in q.parts], model.unit)
                    if isinstance(t, ModelSym) and t.is_trait and t not in out:
                        out.append(t)
            model.traits = out
        if reads.model_active():
            for t in model.traits:
                reads.note_model(("m", t))
        return model.traits

    # the hierarchy questions are answered by model/resolve.py (one ordering, one override rule)

    def linearize(self, model: ModelSym, traits: tuple = ()) -> list[ModelSym]:
        """The layers of a model, lowest priority first (see model/resolve.py)."""
        return resolve.linearize(self, model, traits)

    def ancestors(self, model: ModelSym) -> list[ModelSym]:
        """The model, its bases and all traits applied anywhere in that chain, highest priority first.

        A fresh list the caller may extend.
        """
        return resolve.linearize(self, model)[::-1]

    def is_open(self, model: ModelSym) -> bool:
        return resolve.is_open(self, model)

    def has_cycle(self, model: ModelSym) -> list[ModelSym] | None:
        return resolve.has_cycle(self, model)

    def all_members(self, model: ModelSym) -> dict[str, MemberSym]:
        """Every attribute of a model, by the override rule of model/resolve.py. Shared: do not mutate."""
        return resolve.all_members(self, model)

    def inherited_members(self, model: ModelSym) -> dict[str, MemberSym]:
        return resolve.inherited_members(self, model)

    def all_methods(self, model: ModelSym) -> dict[str, MethodSym]:
        return resolve.all_methods(self, model)

    def member_type(self, mem: MemberSym) -> Ty:
        if reads.model_active():
            reads.note_model(("m", mem.owner))
        if mem.ty is None:
            if mem.anon is not None:
                mem.ty = Ty(mem.anon, False)
            elif mem.owner.unit is None:
                mem.ty = UNKNOWN
            else:
                mem.ty = self.resolve_type_expr(mem.stmt.type, mem.owner.unit)
        if mem.ty.model is not None and reads.model_active():
            reads.note_model(("m", mem.ty.model))
        return mem.ty

    def members_of(self, ty: Ty) -> dict[str, MemberSym]:
        """Attributes of a value of this type (shared table: do not mutate)."""
        if ty.array or ty.alts or ty.model is None:
            return {}
        return resolve.members_with_traits(self, ty.model, ty.traits)

    def methods_of(self, ty: Ty) -> dict[str, MethodSym]:
        if ty.array or ty.alts or ty.model is None:
            return {}
        return resolve.methods_with_traits(self, ty.model, ty.traits)

    def concrete(self, model: ModelSym) -> ModelSym:
        """Anonymous instance subtypes stand for their declared base where a name is needed."""
        seen = 0
        while model.anonymous and seen < 100:
            base = self.base_of(model)
            if base is None or base.model is None:
                break
            model = base.model
            seen += 1
        return model

    def is_subtype(self, sub: ModelSym, sup: ModelSym, extra_traits: tuple = ()) -> bool:
        return resolve.is_subtype(self, sub, sup, extra_traits)

    def assignable(self, actual: Ty, expected: Ty) -> str:
        """'ok', 'warn' (Real into Int) or 'no'. Unknown types are always 'ok' (no cascades)."""
        if actual.unknown or expected.unknown:
            return "ok"
        if expected.alts:
            results = [self.assignable(actual, a) for a in expected.alts]
            return "ok" if "ok" in results else ("warn" if "warn" in results else "no")
        if actual.alts:
            results = [self.assignable(a, expected) for a in actual.alts]
            return "ok" if all(r == "ok" for r in results) else "no"
        if actual.array != expected.array:
            return "no"
        ep, ap = expected.primitive, actual.primitive
        if ep is not None or ap is not None:
            if ep == ap:
                return "ok"
            if ep == "Real" and ap == "Int":
                return "ok"
            if ep == "Int" and ap == "Real":
                return "warn"
            return "no"
        em, am = expected.model, actual.model
        if em is None or am is None:
            return "ok"
        return self._model_assignable(am, self.concrete(em), actual, expected)

    def _model_assignable(self, am: ModelSym, em: ModelSym, actual: Ty, expected: Ty) -> str:
        # (`em`: an instance block's anonymous subtype accepts its declared type, so its concrete one)
        if resolve.opaque_import(self, am) is not None:
            return "ok"  # built on a file plx cannot read: it may well be one (no cascades)
        if not self.is_subtype(am, em, actual.traits):
            # a base that does not resolve (its N001 is the cause): it may well be one
            return "ok" if self.is_open(am) else "no"
        for t in expected.traits:
            if not self.is_subtype(am, t, actual.traits):
                return "no"
        return "ok"

    def positional_fields(self, model: ModelSym) -> list[MemberSym] | None:
        """The attributes a `{...}` literal fills, when all of them are numbers (Vec3, Quat, ...)."""
        mems = list(self.all_members(model).values())
        if not mems:
            return None
        for m in mems:
            t = self.member_type(m)
            if t.primitive not in NUMERIC or t.array:
                return None
        return mems


def _comment_lines(tree: ast.File) -> dict[int, str]:
    return {c.span.start.line: c.text for c in tree.comments if c.own_line}


def _dismantle(symbols: list) -> None:
    """Cut the reference cycles inside a forgotten loose file's symbols (a member points at its
    model, a model's layers include itself, ...), so reference counting frees the old version of a
    file, and its syntax tree, as soon as it is replaced: the language server then needs no
    collector pass over everything to reclaim it. No other file can name a loose file's symbols."""
    stack = [s for s in symbols if isinstance(s, ModelSym)]
    while stack:
        m = stack.pop()
        for mem in m.members.values():
            if mem.anon is not None:
                stack.append(mem.anon)
            mem.ty = None
        for extra in m.path_members.values():
            for mem in extra.values():
                if mem.anon is not None:
                    stack.append(mem.anon)
                mem.ty = None
        m.members = {}
        m.path_members = {}
        m.methods = {}
        m._lin = m._inherited = m._all = m._methods = m._open = m._walks = None
        m.base = None
        m.traits = None
