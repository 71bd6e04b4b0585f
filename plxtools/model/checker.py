"""Checking one file against the program: names, attributes, types, inheritance, completeness.

The checker also records every name it resolves (`occurrences`), which is what hover,
go-to-definition, references and rename use in the language server.
"""

from __future__ import annotations

from dataclasses import dataclass

from plxtools.cache import reads
from plxtools.diagnostics import Diagnostic, Edit, Fix, Severity, Span
from plxtools.model import resolve
from plxtools.model.program import Program, compose_type
from plxtools.model import suggest
from plxtools.model.symbols import (
    BOOL,
    INT,
    NUMERIC,
    REAL,
    STRING,
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

# raised here (`_deprecated_check`); the language server marks it with LSP's Deprecated tag
DEPRECATED_MEMBER = "C004"

E, W, I = Severity.ERROR, Severity.WARNING, Severity.INFO

# The codes other modules recognise (lint's result cache, the workspace's help, completeness and
# check's de-duplication): this module raises them, the others import these names.
UNRESOLVED_TYPE = "N001"
UNKNOWN_ATTRIBUTE = "N002"
UNRESOLVED_NAME = "N003"
TYPE_MISMATCH = "T001"


@dataclass(slots=True)
class Occurrence:
    span: Span
    target: object  # ModelSym | MemberSym | GlobalSym | MethodSym | Namespace
    kind: str  # "type" | "attribute" | "name" | "definition"


class Checker:
    def __init__(self, program: Program, unit: FileUnit, known_annotations: set[str] | None = None):
        self.p = program
        self.unit = unit
        self.diags: list[Diagnostic] = []
        self.occurrences: list[Occurrence] = []
        self.known_annotations = known_annotations
        self.outer: ModelSym | None = None
        self.in_trait = False
        self._broken_cache: dict[int, dict[str, int]] = {}
        self._positional = False
        self._suggests = False
        # a method's parameter and return types, per method called in this file (a file calls the
        # same few functions many times: Vec3.from_xyz); the program does not change during a check
        self._signatures: dict[int, tuple[MethodSym, list[Ty], Ty | None]] = {}
        self._found: dict[tuple[str, ...], object] = {}  # dotted name -> what it names from this file
        # attribute paths set as if they had `becomes` (N002 with that help): the subtype meant
        self._becomes_blocks: dict[tuple[int, tuple[str, ...]], ModelSym] = {}

    # ------------------------------------------------------------------ reporting

    def report(self, code: str, msg: str, span: Span, sev: Severity = E, help: str | None = None,
               fix: Fix | None = None, suggest: str | None = None) -> None:
        """Record a diagnostic; `suggest` is a replacement for the text at `span` ("did you mean"),
        given as a help line and an (unsafe) fix that makes the edit."""
        if suggest is not None:
            help = f"did you mean '{suggest}'?"
            fix = Fix(f"replace with '{suggest}'", (Edit(span.start.offset, span.end.offset, suggest),), safe=False)
        self.diags.append(Diagnostic(code, msg, span, sev, file=self.unit.path, help=help, fix=fix))

    def occ(self, span: Span, target, kind: str) -> None:
        self.occurrences.append(Occurrence(span, target, kind))

    def _closest(self, name: str, options) -> str | None:
        self._suggests = True  # the answer depends on every name in scope (model/reuse.py)
        return suggest.best(name, options)

    def _suggest(self, name: str, options) -> str | None:
        close = self._closest(name, options)
        return f"did you mean '{close}'?" if close else None

    def _broken(self) -> dict[str, int]:
        """Names that a line which did not parse was declaring (`front_left_wheel Wheel`, missing
        `is`), in the current model's body and at the top of the file: name -> line (0-based).

        An unknown name that is one of these is a cascade of that syntax error: no "did you mean"
        (it would offer a sibling such as `front_right_wheel` and wire the wrong object).
        """
        key = id(self.outer)
        cached = self._broken_cache.get(key)
        if cached is not None:
            return cached
        out: dict[str, int] = {}
        bodies = [self.unit.tree.statements]
        body = getattr(self.outer.stmt, "body", None) if self.outer is not None else None
        if body:
            bodies.append(body)
        for stmts in bodies:
            for st in stmts:
                if isinstance(st, ast.ErrorStmt):
                    name = _declared_name(st.text)
                    if name is not None:
                        out.setdefault(name, st.span.start.line)
        self._broken_cache[key] = out
        return out

    def _unknown(self, code: str, msg: str, span: Span, name: str, options) -> None:
        """An unknown name or attribute, with a suggestion unless it is a broken declaration's name."""
        line = self._broken().get(name)
        if line is not None:
            self._positional = True
            self.report(code, msg, span, help=f"its declaration at line {line + 1} has a syntax error; fix that first")
            return
        self.report(code, msg, span, suggest=self._closest(name, options))

    # ------------------------------------------------------------------ entry

    def run(self, only: set[int] | None = None) -> None:
        """Check the file (`only`: just these top-level statements). What each statement added is
        recorded in `slices` (index -> diagnostics and occurrences ranges, whether a finding names
        a line elsewhere, whether a suggestion was looked for among the names in scope), so model/reuse.py can keep it for the next version of the file."""
        self._duplicates()
        self.slices: dict[int, tuple[int, int, int, int, bool]] = {}
        for i, stmt in enumerate(self.unit.tree.statements):
            if only is not None and i not in only:
                continue
            d0, o0 = len(self.diags), len(self.occurrences)
            self._positional = self._suggests = False
            try:
                self._top(stmt)
            except RecursionError:
                self.report("M005", "this definition nests or refers to itself too deeply to check", stmt.header)
            self.slices[i] = (d0, len(self.diags), o0, len(self.occurrences), self._positional, self._suggests)

    def _duplicates(self) -> None:
        for unit, stmt, first in self.p.duplicates:
            if unit is not self.unit:
                continue
            if isinstance(stmt, ast.Declaration) and len(stmt.path.parts) == 1 and isinstance(first, MemberSym):
                self.report("M004", f"'{first.name}' is declared twice in {first.owner.qname}", stmt.path.span,
                            help=f"the first declaration is at line {first.stmt.header.start.line + 1}")
            else:
                where = getattr(first, "unit", None)
                loc = ""
                if where is not None:
                    line = first.stmt.header.start.line + 1
                    loc = f" (first defined in {where.path}:{line})" if where is not self.unit else f" (first defined at line {line})"
                name = stmt.name.name if isinstance(stmt, ast.TraitDef) else stmt.path.text
                self.report("M004", f"'{name}' is already defined in this namespace{loc}",
                            stmt.name.span if isinstance(stmt, ast.TraitDef) else stmt.path.span)

    def _symbol_for(self, stmt: ast.Stmt) -> ModelSym | GlobalSym | None:
        return resolve.symbol_of_top(self.unit, stmt)

    def _top(self, stmt: ast.Stmt) -> None:
        if isinstance(stmt, ast.Declaration) and stmt.keyword != "becomes" and len(stmt.path.parts) == 1:
            sym = self._symbol_for(stmt)
            if isinstance(sym, GlobalSym):
                self.occ(stmt.path.span, sym, "definition")
                self.outer = None
                ty = self._type_expr(stmt.type)
                self._value(stmt.value, ty)
            elif isinstance(sym, ModelSym):
                self._model(sym)
        elif isinstance(stmt, ast.TraitDef):
            sym = self._symbol_for(stmt)
            if isinstance(sym, ModelSym):
                self._model(sym)
        elif isinstance(stmt, ast.OperatorDecl):
            for prm in stmt.params:
                self._type_ref(prm.type)
            if stmt.returns is not None:
                self._type_ref(stmt.returns)
            n = len(stmt.params)
            if stmt.op == "-" and n not in (1, 2) or stmt.op != "-" and n != 2:
                self.report("T004", f"operator {stmt.op} takes {'1 or 2' if stmt.op == '-' else '2'} parameters, "
                            f"not {n}", stmt.header)
        elif isinstance(stmt, ast.ErrorStmt) and stmt.body:
            self.outer = None
            self._block(stmt.body, UNKNOWN, (), None)
        elif isinstance(stmt, ast.Import):
            self._import(stmt)

    def _import(self, stmt: ast.Import) -> None:
        """The name an import binds (a definition for the editor) and the file behind it (N006, N007)."""
        from plxtools.model import imports

        parts, span = imports.bound_name(stmt)
        if not all(imports.valid_name(p) for p in parts):
            self.report("N007", f"the file name {parts[-1]!r} is not a valid OpenPLX name, so the import binds "
                        f"no name", stmt.source.span, help=f"name it with 'as': import {stmt.source.raw} as "
                        f"{imports.name_hint(parts[-1])}")
        else:
            sym = self.p.lookup(parts, self.unit)
            if isinstance(sym, imports.ImportSym) and sym.import_stmt is stmt:
                self.occ(span, sym, "definition")
        full, unset = imports.resolve_file(stmt, self.unit.path)
        if full is None and not unset:
            self.report("N006", "the import names no file (an empty path)", stmt.source.span,
                        help="write the file's path between the quotes: import @\"mesh.obj\" as Mesh")
        elif full is not None and not unset and (found := reads.kind(full)) != "file":
            # a $"..." path is named as written: its expansion would print environment values (secrets)
            shown = repr(stmt.source.value) if stmt.source.kind != "interp" else stmt.source.raw
            what = "is a folder, not a file" if found == "dir" else "does not exist"
            self.report("N006", f"imported file {shown} {what}", stmt.source.span,
                        help="an @\"...\" path is relative to the folder of the .openplx file that imports it"
                        if stmt.source.kind != "interp" else "a $\"...\" path takes each {VAR} from the environment")

    # ------------------------------------------------------------------ types

    def _lookup(self, parts: list[str]):
        """program.lookup(parts) from this file, once per name and check (the program does not
        change while a file is checked; a file names the same few types and namespaces often)."""
        key = tuple(parts)
        try:
            return self._found[key]
        except KeyError:
            found = self._found[key] = self.p.lookup(parts, self.unit)
            return found

    def _type_ref(self, ref: ast.TypeRef, want: str | None = None) -> Ty:
        parts = [p.name for p in ref.name.parts]
        found = self._lookup(parts)
        if found is None:
            outside = self.p.lookup_outside_visibility(parts) if self.unit.bundle else None
            if isinstance(outside, ModelSym) and outside.namespace is not None:
                self.report("B005", f"'{ref.name.text}' is in bundle '{outside.namespace.qname[0]}', which "
                            f"bundle '{self.unit.bundle}' does not depend on", ref.name.span,
                            help=f"add \"{outside.namespace.qname[0]}\" to the dependencies in config.openplx")
                return UNKNOWN
            archived = self.p.archive_name(parts, self.unit)
            if archived is not None:
                # a near miss of a model in scope is a typo: N001 with the suggestion
                from plxtools.model.imports import ImportSym

                defined = [n for n, sym in self.unit.locals.items() if not isinstance(sym, ImportSym)]
                close = self._closest(parts[0], defined + list(self.unit.namespace.symbols))
                if close:
                    self.report(UNRESOLVED_TYPE, f"unknown type '{ref.name.text}'", ref.name.span, suggest=close)
                    return UNKNOWN
                self.occ(ref.name.span, archived, "type")
                self.report("N008", f"'{ref.name.text}' is defined in no file plx reads; it can only come from "
                            f"{archived.written}, which plx cannot read, so it is taken as an opaque model",
                            ref.name.span, Severity.INFO,
                            help="its attributes are not checked; `plx check` does not analyse what is built on it")
                return Ty(archived, ref.array)
            help_, word = self._type_suggestion(parts)
            self.report(UNRESOLVED_TYPE, f"unknown type '{ref.name.text}'", ref.name.span, help=help_, suggest=word)
            return UNKNOWN
        if isinstance(found, Namespace):
            self.occ(ref.name.span, found, "type")
            self.report(UNRESOLVED_TYPE, f"'{ref.name.text}' is a namespace, not a type", ref.name.span,
                        help=self._type_suggestion(parts + [""])[0])
            return UNKNOWN
        if isinstance(found, GlobalSym):
            self.report(UNRESOLVED_TYPE, f"'{ref.name.text}' is a global value, not a type", ref.name.span)
            return UNKNOWN
        if isinstance(found, ModelSym):
            self.occ(ref.name.span, found, "type")
            if want == "trait" and not found.is_trait:
                self.report("N005", f"'{found.qname}' is a model, not a trait", ref.name.span,
                            help="only traits can be applied with 'with'")
            elif want == "model" and found.is_trait:
                self.report("N005", f"'{found.qname}' is a trait; a model cannot inherit from it with 'is'",
                            ref.name.span, help=f"inherit from a model and apply the trait with 'with {ref.name.text}'")
            return Ty(found, ref.array)
        return Ty(found, ref.array)

    def _type_suggestion(self, parts: list[str]) -> tuple[str | None, str | None]:
        """(help, replacement): the closest name in the namespace the prefix names, else what it has."""
        self._suggests = True
        if len(parts) >= 2:
            ns = self.p.lookup(parts[:-1], self.unit)
            if not isinstance(ns, Namespace):
                fixed = self._corrected_path(parts)
                if fixed is not None:
                    return None, fixed
            if isinstance(ns, Namespace):
                close = self._closest(parts[-1], list(ns.symbols) + list(ns.children)) if parts[-1] else None
                if close:
                    return None, ".".join(parts[:-1]) + "." + close
                names = sorted(ns.symbols)[:8]
                if names:
                    return f"{ns.dotted} has: " + ", ".join(names) + (" ..." if len(ns.symbols) > 8 else ""), None
        return None, None

    def _corrected_path(self, parts: list[str]) -> str | None:
        """`Physics3d.Bodies.RigidBody` -> `Physics3D.Bodies.RigidBody`: each part that does not
        resolve replaced by the best suggestion among what the part before it holds."""
        ns = self.p.root
        out = []
        for i, part in enumerate(parts):
            last = i == len(parts) - 1
            names = list(ns.children) + (list(ns.symbols) if last else [])
            word = part if part in names else self._closest(part, names)
            if word is None:
                return None
            out.append(word)
            if not last:
                ns = ns.children.get(word)
                if ns is None:
                    return None
        fixed = ".".join(out)
        return fixed if fixed != ".".join(parts) and isinstance(self.p.lookup(out, self.unit), ModelSym) else None

    def _type_expr(self, texpr: ast.TypeExpr | None, want: str | None = None) -> Ty:
        if texpr is None:
            return UNKNOWN
        alts = [self._type_ref(r, want) for r in texpr.alternatives]
        traits = [self._type_ref(ast.TypeRef(q.span, q), "trait").model for q in texpr.traits]
        return compose_type(alts, [t for t in traits if t is not None])

    # ------------------------------------------------------------------ models

    def _model(self, m: ModelSym) -> None:
        self.outer = m
        self.in_trait = m.is_trait
        stmt = m.stmt
        name_span = stmt.name.span if isinstance(stmt, ast.TraitDef) else stmt.path.span
        self.occ(name_span, m, "definition")
        if m.base_ref is not None:
            self._type_expr(m.base_ref, "trait" if m.is_trait else "model")
            cycle = self.p.has_cycle(m)
            if cycle:
                names = " -> ".join(c.qname for c in cycle)
                self.report("M005", f"inheritance cycle: {names}", m.base_ref.span)
        body = getattr(stmt, "body", None)
        if body:
            self._block(body, Ty(m), (), m)
        self.in_trait = False

    def _inherited(self, model: ModelSym) -> dict[str, MemberSym]:
        return self.p.inherited_members(model)

    def _member_for(self, model_def: ModelSym | None, stmt: ast.Declaration) -> MemberSym | None:
        return resolve.declared_member(model_def, stmt)

    def _block(self, body: list[ast.Stmt], target: Ty, prefix: tuple[str, ...], model_def: ModelSym | None) -> None:
        for s in body:
            if isinstance(s, ast.Declaration):
                self._declaration(s, target, prefix, model_def)
            elif isinstance(s, ast.Assignment):
                ty, _mem = self._path(s.path.parts, target, prefix, model_def)
                if s.value is not None:
                    self._value(s.value, ty)
                if s.body is not None:
                    self._block(s.body, ty, prefix + tuple(p.name for p in s.path.parts), None)
            elif isinstance(s, ast.WithStmt):
                for q in s.traits:
                    self._type_ref(ast.TypeRef(q.span, q), "trait")
            elif isinstance(s, ast.Annotation):
                self._annotation(s)
            elif isinstance(s, ast.Method):
                for prm in s.params:
                    self._type_ref(prm.type)
                if s.returns is not None:
                    self._type_ref(s.returns)
                if model_def is not None and s.name.name in model_def.methods:
                    self.occ(s.name.span, model_def.methods[s.name.name], "definition")
            elif isinstance(s, ast.ErrorStmt) and s.body:
                self._block(s.body, UNKNOWN, prefix, None)

    def _declaration(self, s: ast.Declaration, target: Ty, prefix: tuple[str, ...], model_def: ModelSym | None) -> None:
        """`path is T` or `path becomes T`, with its value and its block."""
        parts = s.path.parts
        mem = self._member_for(model_def, s)
        owner_ty = target
        if len(parts) > 1:
            owner_ty, _ = self._path(parts[:-1], target, prefix, model_def)
        if mem is not None:
            self.occ(parts[-1].span, mem, "definition")
        ty = self._type_expr(s.type)
        if s.keyword == "is":
            if len(parts) == 1:
                self._not_redeclared(s, target, model_def)
        else:
            self._becomes(s, ty, owner_ty, model_def)
        if s.value is not None:
            self._value(s.value, ty)
        if s.body is not None:
            self._declaration_block(s, ty, mem, prefix)
        if mem is not None:
            self._deprecated_check(mem, parts[-1].span)

    def _not_redeclared(self, s: ast.Declaration, target: Ty, model_def: ModelSym | None) -> None:
        """`name is T` for a name the model (or the object being configured) already has: M001."""
        ident = s.path.parts[-1]
        name = ident.name
        if model_def is not None:
            inherited = self._inherited(model_def)
            old = inherited.get(name)
            # a trait may `becomes` an attribute its host declares (spec C.3/C.4): not a redeclaration
            if old is not None and old.stmt is not s and not (old.keyword == "becomes" and old.owner.is_trait):
                self.report("M001", f"'{name}' is already declared in {old.owner.qname}; use 'becomes' to "
                            f"specialise it or ':' to give it a value", ident.span,
                            help=f"'{name} becomes {s.type.alternatives[0].name.text}'" if s.type else None)
        elif not target.unknown and name in self.p.members_of(target):
            self.report("M001", f"'{name}' already exists in {target.display()}; use ':' to give it "
                        f"a value or 'becomes' to specialise it", ident.span)

    def _becomes(self, s: ast.Declaration, ty: Ty, owner_ty: Ty, model_def: ModelSym | None) -> None:
        """`path becomes T`: the attribute must be inherited (M002) and T fit its declared type (M003)."""
        ident = s.path.parts[-1]
        name = ident.name
        if model_def is not None and len(s.path.parts) == 1:
            candidates = self._inherited(model_def)
        else:
            candidates = self.p.members_of(owner_ty) if not owner_ty.unknown else None
        old = candidates.get(name) if candidates is not None else None
        if old is not None and old.stmt is s:
            old = None
        if old is None:
            if candidates is not None and not self.in_trait and not self._opaque(owner_ty):
                where = model_def.qname if model_def is not None else owner_ty.display()
                self.report("M002", f"'{name}' is not inherited by {where}, so it cannot 'become' "
                            f"another type", ident.span,
                            help=self._suggest(name, candidates) or f"declare it with '{name} is ...'")
            return
        self.occ(ident.span, old, "attribute")
        old_ty = self.p.member_type(old)
        if not ty.unknown and not old_ty.unknown and self.p.assignable(ty, old_ty) != "ok":
            self.report("M003", f"'{name}' cannot become {ty.display()}: it is declared as "
                        f"{old_ty.display()} in {old.owner.qname}", s.type.span,
                        help="the new type must be a subtype of the declared type or one of its alternatives")

    def _declaration_block(self, s: ast.Declaration, ty: Ty, mem: MemberSym | None, prefix: tuple[str, ...]) -> None:
        parts = s.path.parts
        if s.reference:
            self.report("M009", f"'{parts[-1].name}' is a reference; a block would create a new object",
                        s.header, help="give it an existing object with ':' instead")
        block_ty = Ty(mem.anon) if mem is not None and mem.anon is not None else ty
        self._block(s.body, block_ty, prefix + tuple(p.name for p in parts), mem.anon if mem is not None else None)

    def _opaque(self, ty: Ty) -> bool:
        return ty.model is not None and self.p.is_open(ty.model)

    # ------------------------------------------------------------------ paths

    def _path(self, parts: list[ast.Ident], target: Ty, prefix: tuple[str, ...], model_def) -> tuple[Ty, MemberSym | None]:
        cur = target
        mem: MemberSym | None = None
        path = prefix
        for i, part in enumerate(parts):
            if cur.unknown or self._opaque(cur):
                return UNKNOWN, None
            if cur.array or cur.alts or cur.primitive is not None:
                self.report(UNKNOWN_ATTRIBUTE, f"'{part.name}' cannot be set on a value of type {cur.display()}", part.span)
                return UNKNOWN, None
            mems = resolve.attributes(self.p, cur, self.outer, path)
            found = mems.get(part.name)
            if found is None:
                if self.in_trait and i == 0 and not prefix:
                    return UNKNOWN, None  # a host attribute the trait does not declare
                where = self.p.concrete(cur.model).qname if cur.model is not None else cur.display()
                if i == 0 and not prefix:
                    self._unknown(UNKNOWN_ATTRIBUTE, f"'{part.name}' is not an attribute of {where}", part.span, part.name,
                                  list(mems))
                else:
                    meant = self._becomes_blocks.get((id(self.outer), path))
                    if meant is not None and part.name in self.p.all_members(meant):
                        return UNKNOWN, None  # follows from the missing `becomes` reported above
                    kind = self._subtype_with(cur.model, part.name) if cur.model is not None else None
                    if kind is not None:
                        self._becomes_blocks[(id(self.outer), path)] = kind
                        self.report(UNKNOWN_ATTRIBUTE, f"'{part.name}' is not an attribute of {where}, but of "
                                    f"{kind.name}, a kind of it", part.span,
                                    help=f"use becomes to make '{'.'.join(path)}' a {kind.name}: write "
                                         f"'{path[-1] if path else 'it'} becomes {kind.qname}:' above")
                    else:
                        self.report(UNKNOWN_ATTRIBUTE, f"'{part.name}' is not an attribute of {where}", part.span,
                                    suggest=self._closest(part.name, list(mems)))
                return UNKNOWN, None
            mem = found
            self.occ(part.span, mem, "attribute")
            self._deprecated_check(mem, part.span)
            cur = self.p.member_type(mem)
            path = path + (part.name,)
        return cur, mem

    def _subtype_with(self, model: ModelSym, name: str) -> ModelSym | None:
        """The one named model that is a kind of `model` and has an attribute `name` (None: none or
        several), for the help of an attribute set on the declared type instead of `becomes`."""
        self._suggests = True  # the answer depends on every model in the program (model/reuse.py)
        found = [m for m in self.p.all_models() if not m.anonymous and not m.is_trait and m is not model
                 and name in self.p.all_members(m) and self.p.is_subtype(m, model)]
        found = [m for m in found if not any(o is not m and self.p.is_subtype(m, o) for o in found)]
        return found[0] if len(found) == 1 else None

    def _deprecated_check(self, mem: MemberSym, span: Span) -> None:
        for owner in (mem.owner,):
            note = owner.deprecated.get(mem.name)
            if note and owner.unit is not self.unit:
                self.report(DEPRECATED_MEMBER, f"'{mem.name}' is deprecated: {note}", span, W)

    # ------------------------------------------------------------------ annotations

    def _annotation(self, s: ast.Annotation) -> None:
        name = s.name.name
        if self.known_annotations is None or name in self.known_annotations or name.startswith("agx_"):
            return
        self.report("C005", f"unknown annotation '.{name}'", s.name.span, I,
                    help="annotations are free-form metadata; this one is not used by the official bundles")

    # ------------------------------------------------------------------ expressions

    def _value(self, expr: ast.Expr | None, expected: Ty) -> None:
        if expr is None:
            return
        got = self._expr(expr, expected)
        if not isinstance(got, Ty):
            if not self._becomes_meant(got, expected, expr.span):
                self._not_a_value(TYPE_MISMATCH, got, expr.span)
            return
        verdict = self.p.assignable(got, expected)
        if verdict == "no":
            help_, fix = self._literal_help(expr, expected)
            if help_ is None and isinstance(expr, ast.String):
                help_, fix = _unquoted(expr, expected)
            if help_ is None and isinstance(expr, ast.String):
                help_, fix = self._const_named(expr, expected)
            self.report(TYPE_MISMATCH, f"expected {expected.display()}, found {got.display()}", expr.span,
                        help=help_ or self._mismatch_help(got, expected), fix=fix)
        elif verdict == "warn":
            self.report("T002", "a Real is given where an Int is expected", expr.span, W,
                        help="write a whole number, or use Math.Functions.round/floor/ceil")

    def _const_named(self, expr: ast.String, expected: Ty) -> tuple[str | None, Fix | None]:
        """A material's `unique_name` string where the material is expected: the const model whose
        attribute holds that string, by name (`material: "Tutorial_WheelMaterial"` -> WheelMaterial)."""
        want = expected.model if not expected.array and not expected.alts else None
        if want is None:
            return None, None
        self._suggests = True  # the answer depends on every const model in the program (model/reuse.py)
        for m in self.p.all_models():
            if not m.const or m.is_trait or not self.p.is_subtype(m, want):
                continue
            for a in m.assignments:
                if isinstance(a.value, ast.String) and a.value.value == expr.value:
                    name = m.name if m.unit is self.unit else m.qname
                    attr = ".".join(p.name for p in a.path.parts)
                    return (f"did you mean {name}? (\"{expr.value}\" is its {attr}; give the const itself, without "
                            "quotes)", Fix(f"replace with '{name}'", (Edit(expr.span.start.offset, expr.span.end.offset,
                                                                             name),), safe=False))
        return None, None

    def _literal_help(self, expr: ast.Expr, expected: Ty) -> tuple[str | None, Fix | None]:
        """How a value of a positional model (a vector, a quaternion) is written, when an array
        literal stands for it: `[0, -1, 0]` for a Math.Vec3 is the usual slip from other languages.
        The fix swaps the brackets when the array has as many items as the model has fields."""
        model = expected.model if not expected.array and not expected.alts else None
        fields = self.p.positional_fields(model) if model is not None else None
        if not fields or not isinstance(expr, ast.Array):
            return None, None
        kind = next((m.qname for m in self.p.ancestors(model) if not m.anonymous and "." in m.qname
                     and m.qname.rsplit(".", 1)[1][:1].isupper()), model.qname)
        names = ", ".join(f.name for f in fields)
        help_ = (f"a {kind} is written in braces, {{ {names} }}, or as a block with one line per field; "
                 "[ ] makes an array")
        fix = None
        if len(expr.items) == len(fields):
            text = self.unit.tree.text if self.unit.tree is not None else None
            if text is not None:
                inner = text[expr.span.start.offset + 1 : expr.span.end.offset - 1]
                fix = Fix("write it in braces", (Edit(expr.span.start.offset, expr.span.end.offset,
                                                      "{ " + inner.strip() + " }"),), safe=True)
        return help_, fix

    def _mismatch_help(self, got: Ty, expected: Ty) -> str | None:
        if expected.primitive == "Bool" and got.primitive in NUMERIC:
            return "use true or false"
        if expected.primitive in NUMERIC and got.primitive == "String":
            return "remove the quotes"
        return None

    def _describe_nonvalue(self, v) -> str:
        if isinstance(v, TypeObj):
            return f"'{getattr(v.sym, 'qname', v.sym)}' is a type and"
        if isinstance(v, NsRef):
            return f"'{v.ns.dotted}' is a namespace and"
        if isinstance(v, MethodRef):
            return f"method '{v.method.name}' must be called: it"
        return "this"

    def _becomes_meant(self, v, expected: Ty, span: Span) -> bool:
        """`friction: Physics...DryConstantNormalForceFriction`: a model that is a kind of the
        attribute's type, given as its value, where `becomes` was meant (T001 with that fix)."""
        sym = v.sym if isinstance(v, TypeObj) else None
        want = expected.model if not expected.array and not expected.alts else None
        if not isinstance(sym, ModelSym) or sym.is_trait or sym.const or want is None or sym is want \
                or sym.unit is self.unit or not self.p.is_subtype(sym, want):
            return False  # (a model of this file given as a value most often lacks `const`: _not_a_value)
        self.report(TYPE_MISMATCH, f"'{sym.qname}' is a model, not a value; it is a kind of "
                    f"{self.p.concrete(want).qname}, the attribute's type", span,
                    help=f"use becomes to make the attribute a {sym.name}: write '<attribute> becomes {sym.qname}' "
                         "(its settings in an indented block below)")
        return True

    def _not_a_value(self, code: str, v, span: Span) -> None:
        """A type, namespace or method where a value is needed. A model named as a value most often
        lacks `const`: say so, and offer to add it when the model is defined in this file."""
        sym = v.sym if isinstance(v, TypeObj) else None
        if isinstance(sym, ModelSym) and not sym.is_trait and not sym.anonymous:
            fix = None
            stmt = sym.stmt
            if sym.unit is self.unit and isinstance(stmt, ast.Declaration):
                at = stmt.header.start.offset
                fix = Fix(f"declare {sym.name} 'const'", (Edit(at, at, "const "),), safe=False)
            self.report(code, f"'{sym.qname}' is a model, not a value: a model used as a value must be declared "
                        f"'const' (or instantiated)", span, fix=fix,
                        help=f"write 'const {sym.name} ...' where it is defined, or declare an attribute "
                             f"'name is {sym.qname}' to create one")
            return
        self.report(code, f"{self._describe_nonvalue(v)} is not a value", span)

    def _as_ty(self, v, span: Span) -> Ty:
        if isinstance(v, Ty):
            return v
        self._not_a_value(TYPE_MISMATCH, v, span)
        return UNKNOWN

    def _expr(self, e, expected: Ty = UNKNOWN):
        """What expression `e` is (a Ty, or the type, namespace or method it names), checking it on
        the way: one handler per expression kind (`_EXPR_KINDS`, after the class)."""
        handler = _EXPR_KINDS.get(type(e))
        return handler(self, e, expected) if handler is not None else UNKNOWN

    def _number(self, e: ast.Number, expected: Ty) -> Ty:
        return INT if e.is_int else REAL

    def _string(self, e: ast.String, expected: Ty) -> Ty:
        return STRING

    def _bool(self, e: ast.Bool, expected: Ty) -> Ty:
        return BOOL

    def _this(self, e: ast.This, expected: Ty) -> Ty:
        # inside a trait, `this` is whatever host the trait is applied to
        return Ty(self.outer) if self.outer is not None and not self.in_trait else UNKNOWN

    def _paren(self, e: ast.Paren, expected: Ty):
        return self._expr(e.inner, expected)

    def _name_expr(self, e: ast.Name, expected: Ty):
        return self._name(e.ident)

    def _member_expr(self, e: ast.Member, expected: Ty):
        return self._member(e)

    def _call_expr(self, e: ast.Call, expected: Ty):
        return self._call(e)

    def _index(self, e: ast.Index, expected: Ty) -> Ty:
        obj = self._as_ty(self._expr(e.obj), e.obj.span)
        idx = self._as_ty(self._expr(e.index), e.index.span)
        if idx.primitive is not None and idx.primitive != "Int":
            self.report("T009", f"an index must be an Int, not {idx.display()}", e.index.span)
        if obj.unknown:
            return UNKNOWN
        if not obj.array:
            self.report("T009", f"a value of type {obj.display()} cannot be indexed", e.span)
            return UNKNOWN
        return obj.element()

    def _unary(self, e: ast.Unary, expected: Ty) -> Ty:
        operand = self._as_ty(self._expr(e.operand, expected), e.operand.span)
        return self._operator("-", [operand], e)

    def _binary(self, e: ast.Binary, expected: Ty) -> Ty:
        left = self._as_ty(self._expr(e.left), e.left.span)
        right = self._as_ty(self._expr(e.right), e.right.span)
        return self._operator(e.op, [left, right], e)

    def _array(self, e: ast.Array, expected: Ty) -> Ty:
        elem = expected.element() if expected.array else UNKNOWN
        if not expected.unknown and not expected.array and not expected.alts:
            for item in e.items:
                self._expr(item)
            return Ty("Array", True)  # reported by the caller as a mismatch
        got_elem = UNKNOWN
        for item in e.items:
            if elem.unknown:
                t = self._expr(item)
                if isinstance(t, Ty) and got_elem.unknown:
                    got_elem = t
            else:
                self._value(item, elem)
        return expected if expected.array else (Ty(got_elem.sym, True, got_elem.traits) if not got_elem.unknown else UNKNOWN)

    def _brace(self, e: ast.Brace, expected: Ty):
        target = expected
        if target.alts:
            target = next((a for a in target.alts if a.model is not None and
                           self.p.positional_fields(a.model) and len(self.p.positional_fields(a.model)) == len(e.items)),
                          UNKNOWN)
        if target.unknown or target.array:
            for item in e.items:
                self._expr(item)
            return UNKNOWN if target.unknown else Ty("Brace")
        if target.primitive is not None:
            if target.primitive == "Blob":
                return target
            for item in e.items:
                self._expr(item)
            self.report(TYPE_MISMATCH, f"a {{...}} literal cannot be a {target.primitive}", e.span)
            return UNKNOWN
        fields = self.p.positional_fields(target.model)
        if fields is None:
            for item in e.items:
                self._expr(item)
            return target
        if len(e.items) != len(fields):
            names = ", ".join(f.name for f in fields)
            self.report("T003", f"{self.p.concrete(target.model).qname} takes {len(fields)} values ({names}), "
                        f"this literal has {len(e.items)}", e.span)
        for item, f in zip(e.items, fields):
            self._value(item, self.p.member_type(f))
        return target

    def _name(self, ident: ast.Ident):
        name = ident.name
        found = resolve.name_target(self.p, self.unit, self.outer, name, self._lookup)
        if isinstance(found, MemberSym):
            self.occ(ident.span, found, "attribute")
            return self.p.member_type(found)
        v = self._global_value(found, ident)
        if v is not None:
            return v
        if self.in_trait:
            return UNKNOWN
        options = list(self.p.members_of(Ty(self.outer))) if self.outer is not None else []
        options += list(self.unit.locals) + list(self.unit.namespace.symbols)
        if name in ("True", "False", "TRUE", "FALSE"):
            self.report(UNRESOLVED_NAME, f"unknown name '{name}'", ident.span, suggest=name.lower())
            return UNKNOWN
        self._unknown(UNRESOLVED_NAME, f"unknown name '{name}'", ident.span, name, options)
        return UNKNOWN

    def _global_value(self, found, ident: ast.Ident):
        v = resolve.global_meaning(self.p, found)
        if v is not None and not isinstance(found, str):
            self.occ(ident.span, found, "name")
        return v

    def _member(self, e: ast.Member):
        base = self._expr(e.obj)
        name = e.name.name
        if isinstance(base, MethodRef):
            self.report("T008", f"method '{base.method.name}' must be called before '.{name}'", e.span)
            return UNKNOWN
        if isinstance(base, Ty):
            if base.unknown or self._opaque(base):
                return UNKNOWN
            if base.array or base.alts or base.primitive is not None:
                self.report("N004", f"a value of type {base.display()} has no member '{name}'", e.name.span)
                return UNKNOWN
        found = resolve.member_target(self.p, base, name)
        if isinstance(base, NsRef):
            v = self._global_value(found, e.name)
            if v is None:
                self.report(UNRESOLVED_NAME, f"'{name}' is not in namespace {base.ns.dotted}", e.name.span,
                            suggest=self._closest(name, list(base.ns.symbols) + list(base.ns.children)))
                return UNKNOWN
            return v
        if isinstance(found, MethodRef):
            self.occ(e.name.span, found.method, "name")
            return found
        if isinstance(found, MemberSym):
            self.occ(e.name.span, found, "attribute")
            self._deprecated_check(found, e.name.span)
            return self.p.member_type(found)
        if isinstance(base, TypeObj):
            if isinstance(base.sym, ModelSym):
                self.report("N004", f"{base.sym.qname} has no static function '{name}'", e.name.span,
                            suggest=self._closest(name, self.p.all_methods(base.sym)))
            return UNKNOWN
        self.report("N004", f"{self.p.concrete(base.model).qname} has no attribute or method '{name}'", e.name.span,
                    suggest=self._closest(name, list(self.p.members_of(base)) + list(self.p.methods_of(base))))
        return UNKNOWN

    def _method_types(self, meth: MethodSym) -> tuple[list[Ty], Ty | None]:
        got = self._signatures.get(id(meth))
        if got is not None and got[0] is meth:
            return got[1], got[2]
        unit = meth.owner.unit
        params = [self.p.resolve_type_ref(prm.type, unit) for prm in meth.stmt.params]
        ret = self.p.resolve_type_ref(meth.stmt.returns, unit) if meth.stmt.returns is not None else None
        self._signatures[id(meth)] = (meth, params, ret)
        return params, ret

    def _call(self, e: ast.Call):
        f = self._expr(e.func)
        arg_types = [self._expr(a) for a in e.args]
        if isinstance(f, Ty) and f.unknown:
            return UNKNOWN
        if not isinstance(f, MethodRef):
            what = self._describe_nonvalue(f) if not isinstance(f, Ty) else f"a value of type {f.display()}"
            self.report("T008", f"{what} cannot be called", e.func.span)
            return UNKNOWN
        meth = f.method
        if f.on_type and not meth.static:
            self.report("T008", f"'{meth.name}' is an instance method of {meth.owner.qname}; call it on an "
                        f"instance, not on the type", e.func.span)
        elif not f.on_type and meth.static:
            self.report("T008", f"'{meth.name}' is a static function; call it on the type, "
                        f"{meth.owner.qname}.{meth.name}(...)", e.func.span, W)
        params, ret = self._method_types(meth)
        if len(params) != len(e.args):
            self.report("T004", f"{meth.owner.qname}.{meth.name} takes {len(params)} argument"
                        f"{'s' if len(params) != 1 else ''}, {len(e.args)} given", e.span,
                        help="signature: " + _signature(meth))
        else:
            for arg, got, want in zip(e.args, arg_types, params):
                if not isinstance(got, Ty):
                    self._not_a_value("T005", got, arg.span)
                    continue
                if isinstance(arg, ast.Brace):
                    got = self._brace(arg, want)
                if self.p.assignable(got, want) == "no":
                    self.report("T005", f"argument of {meth.name}: expected {want.display()}, found {got.display()}",
                                arg.span, help="signature: " + _signature(meth))
        if ret is None:
            self.report("T007", f"{meth.owner.qname}.{meth.name} returns nothing and cannot be used in an expression",
                        e.span)
            return UNKNOWN
        return ret

    def _operator(self, op: str, operands: list[Ty], e) -> Ty:
        if any(o.unknown for o in operands):
            return UNKNOWN
        prims = [o.primitive for o in operands]
        if all(p in NUMERIC for p in prims) and not any(o.array for o in operands):
            if op == "/" or "Real" in prims:
                return REAL
            return INT
        cands = [o for o in self.p.operators.get(op, []) if len(o.stmt.params) == len(operands)]
        for cand in cands:
            ptys = [self.p.resolve_type_ref(prm.type, cand.unit) for prm in cand.stmt.params]
            if all(self.p.assignable(a, p) == "ok" for a, p in zip(operands, ptys)):
                if cand.stmt.returns is None:
                    return UNKNOWN
                return self.p.resolve_type_ref(cand.stmt.returns, cand.unit)
        shown = f"{op}{operands[0].display()}" if len(operands) == 1 else \
            f"{operands[0].display()} {op} {operands[1].display()}"
        help_ = None
        if op == "*" and len(operands) == 2 and operands[0].model and operands[0].model.name == "Quat":
            help_ = "rotate a vector with q.rotate(v)"
        self.report("T006", f"no operator for {shown}", e.span, help=help_)
        return UNKNOWN

_EXPR_KINDS = {
    ast.Number: Checker._number, ast.String: Checker._string, ast.Bool: Checker._bool, ast.This: Checker._this,
    ast.Paren: Checker._paren, ast.Name: Checker._name_expr, ast.Member: Checker._member_expr,
    ast.Call: Checker._call_expr, ast.Index: Checker._index, ast.Unary: Checker._unary,
    ast.Binary: Checker._binary, ast.Brace: Checker._brace, ast.Array: Checker._array,
}


def _signature(meth: MethodSym) -> str:
    params = ", ".join(f"{p.name.name}: {p.type.name.text}{'[]' if p.type.array else ''}" for p in meth.stmt.params)
    ret = f" -> {meth.stmt.returns.name.text}" if meth.stmt.returns is not None else ""
    return f"{'static ' if meth.static else ''}fn {meth.name}({params}){ret}"


def _declared_name(text: str) -> str | None:
    """The name a line that did not parse starts with (after `const`/`optional`), from the lexer."""
    from plxtools.syntax.lexer import lex

    lines = lex(text.split("\n", 1)[0]).lines
    for tok in lines[0].tokens if lines else ():
        if tok.type in ("CONST", "OPTIONAL"):
            continue
        return str(tok) if tok.type == "NAME" else None
    return None


def _unquoted(expr: ast.String, expected: Ty) -> tuple[str | None, Fix | None]:
    """`is_dynamic: "false"`: a Bool written in quotes (a number in quotes has _mismatch_help's)."""
    text = expr.value.strip()
    if expected.primitive != "Bool" or expected.array or text not in ("true", "false"):
        return None, None
    return (f"write {text} without quotes: a {expected.primitive} is not a string",
            Fix(f"write {text}", (Edit(expr.span.start.offset, expr.span.end.offset, text),), safe=False))
