"""Checking one file against the program: names, attributes, types, inheritance, completeness.

The checker also records every name it resolves (`occurrences`), which is what hover,
go-to-definition, references and rename use in the language server.
"""

from __future__ import annotations

from dataclasses import dataclass

from plxtools.cache import reads
from plxtools.diagnostics import Diagnostic, Severity, Span
from plxtools.model import facts, resolve
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

E = Severity.ERROR


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

    def found(self, fact: facts.Fact) -> None:
        """Record a fact (plxtools/model/facts.py): the rules layer reports it."""
        self.diags.append(fact)

    def occ(self, span: Span, target, kind: str) -> None:
        self.occurrences.append(Occurrence(span, target, kind))

    def _closest(self, name: str, options) -> str | None:
        self._suggests = True  # the answer depends on every name in scope (model/reuse.py)
        return suggest.best(name, options)

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

    def _near(self, name: str, options) -> tuple[str | None, int | None]:
        """(suggestion, line) for an unknown name or attribute: the closest of `options`, unless it
        is the name a line that did not parse declares (that line, 0-based)."""
        line = self._broken().get(name)
        if line is not None:
            self._positional = True
            return None, line
        return self._closest(name, options), None

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
                self.found(facts.TooDeepToCheck(stmt.header))
            self.slices[i] = (d0, len(self.diags), o0, len(self.occurrences), self._positional, self._suggests)

    def _duplicates(self) -> None:
        for unit, stmt, first in self.p.duplicates:
            if unit is not self.unit:
                continue
            if isinstance(stmt, ast.Declaration) and len(stmt.path.parts) == 1 and isinstance(first, MemberSym):
                self.found(facts.DeclaredTwice(stmt.path.span, first.name, first.owner.qname,
                                               first.stmt.header.start.line))
            else:
                where = getattr(first, "unit", None)
                line = first.stmt.header.start.line if where is not None else None
                other = where.path if where is not None and where is not self.unit else None
                name = stmt.name.name if isinstance(stmt, ast.TraitDef) else stmt.path.text
                self.found(facts.DefinedTwice(stmt.name.span if isinstance(stmt, ast.TraitDef) else stmt.path.span,
                                              name, other, line))

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
                self.found(facts.OperatorArity(stmt.header, stmt.op, n))
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
            self.found(facts.ImportBindsNoName(stmt.source.span, parts[-1], stmt.source.raw,
                                               imports.name_hint(parts[-1])))
        else:
            sym = self.p.lookup(parts, self.unit)
            if isinstance(sym, imports.ImportSym) and sym.import_stmt is stmt:
                self.occ(span, sym, "definition")
        full, unset = imports.resolve_file(stmt, self.unit.path)
        if full is None and not unset:
            self.found(facts.ImportNamesNoFile(stmt.source.span))
        elif full is not None and not unset and (found := reads.kind(full)) != "file":
            # a $"..." path is named as written: its expansion would print environment values (secrets)
            shown = repr(stmt.source.value) if stmt.source.kind != "interp" else stmt.source.raw
            self.found(facts.ImportFileMissing(stmt.source.span, shown, found == "dir", stmt.source.kind == "interp"))

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
                self.found(facts.OutsideDependencies(ref.name.span, ref.name.text, outside.namespace.qname[0],
                                                     self.unit.bundle))
                return UNKNOWN
            archived = self.p.archive_name(parts, self.unit)
            if archived is not None:
                # a near miss of a model in scope is a typo: N001 with the suggestion
                from plxtools.model.imports import ImportSym

                defined = [n for n, sym in self.unit.locals.items() if not isinstance(sym, ImportSym)]
                close = self._closest(parts[0], defined + list(self.unit.namespace.symbols))
                if close:
                    self.found(facts.UnknownType(ref.name.span, ref.name.text, suggestion=close))
                    return UNKNOWN
                self.occ(ref.name.span, archived, "type")
                self.found(facts.OpaqueImportName(ref.name.span, ref.name.text, archived.written))
                return Ty(archived, ref.array)
            listing, word = self._type_suggestion(parts)
            self.found(facts.UnknownType(ref.name.span, ref.name.text, suggestion=word,
                                         listing=listing if word is None else None))
            return UNKNOWN
        if isinstance(found, Namespace):
            self.occ(ref.name.span, found, "type")
            self.found(facts.UnknownType(ref.name.span, ref.name.text, "namespace",
                                         listing=self._type_suggestion(parts + [""])[0]))
            return UNKNOWN
        if isinstance(found, GlobalSym):
            self.found(facts.UnknownType(ref.name.span, ref.name.text, "global"))
            return UNKNOWN
        if isinstance(found, ModelSym):
            self.occ(ref.name.span, found, "type")
            if want == "trait" and not found.is_trait:
                self.found(facts.WrongKindOfType(ref.name.span, found.qname, "trait", ref.name.text))
            elif want == "model" and found.is_trait:
                self.found(facts.WrongKindOfType(ref.name.span, found.qname, "model", ref.name.text))
            return Ty(found, ref.array)
        return Ty(found, ref.array)

    def _type_suggestion(self, parts: list[str]) -> tuple[tuple | None, str | None]:
        """(listing, replacement): the closest name in the namespace the prefix names, else what it
        has (its name, up to 8 of its names, whether there are more)."""
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
                    return (ns.dotted, tuple(names), len(ns.symbols) > 8), None
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
                self.found(facts.InheritanceCycle(m.base_ref.span, tuple(c.qname for c in cycle)))
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
                self.found(facts.Redeclared(ident.span, name, old.owner.qname, True,
                                            s.type.alternatives[0].name.text if s.type else None))
        elif not target.unknown and name in self.p.members_of(target):
            self.found(facts.Redeclared(ident.span, name, target.display(), False))

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
                self.found(facts.BecomesNotInherited(ident.span, name, where, self._closest(name, candidates)))
            return
        self.occ(ident.span, old, "attribute")
        old_ty = self.p.member_type(old)
        if not ty.unknown and not old_ty.unknown and self.p.assignable(ty, old_ty) != "ok":
            self.found(facts.BecomesIncompatible(s.type.span, name, ty.display(), old_ty.display(), old.owner.qname))

    def _declaration_block(self, s: ast.Declaration, ty: Ty, mem: MemberSym | None, prefix: tuple[str, ...]) -> None:
        parts = s.path.parts
        if s.reference:
            self.found(facts.ReferenceWithBlock(s.header, parts[-1].name))
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
                self.found(facts.UnknownAttribute(part.span, part.name, cur.display(), on_value=True))
                return UNKNOWN, None
            mems = resolve.attributes(self.p, cur, self.outer, path)
            found = mems.get(part.name)
            if found is None:
                if self.in_trait and i == 0 and not prefix:
                    return UNKNOWN, None  # a host attribute the trait does not declare
                where = self.p.concrete(cur.model).qname if cur.model is not None else cur.display()
                if i == 0 and not prefix:
                    self.found(facts.UnknownAttribute(part.span, part.name, where, *self._near(part.name, list(mems))))
                else:
                    meant = self._becomes_blocks.get((id(self.outer), path))
                    if meant is not None and part.name in self.p.all_members(meant):
                        return UNKNOWN, None  # follows from the missing `becomes` reported above
                    kind = self._subtype_with(cur.model, part.name) if cur.model is not None else None
                    if kind is not None:
                        self._becomes_blocks[(id(self.outer), path)] = kind
                        self.found(facts.UnknownAttribute(part.span, part.name, where, kind_of=(
                            kind.name, kind.qname, ".".join(path), path[-1] if path else "it")))
                    else:
                        self.found(facts.UnknownAttribute(part.span, part.name, where,
                                                          self._closest(part.name, list(mems))))
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
                self.found(facts.DeprecatedMember(span, mem.name, note))

    # ------------------------------------------------------------------ annotations

    def _annotation(self, s: ast.Annotation) -> None:
        name = s.name.name
        if self.known_annotations is None or name in self.known_annotations or name.startswith("agx_"):
            return
        self.found(facts.UnknownAnnotation(s.name.span, name))

    # ------------------------------------------------------------------ expressions

    def _value(self, expr: ast.Expr | None, expected: Ty) -> None:
        if expr is None:
            return
        got = self._expr(expr, expected)
        if not isinstance(got, Ty):
            if not self._becomes_meant(got, expected, expr.span):
                self._not_a_value(got, expr.span)
            return
        verdict = self.p.assignable(got, expected)
        if verdict == "no":
            braces = self._literal_help(expr, expected)
            unquoted = const = None
            if braces is None and isinstance(expr, ast.String):
                unquoted = _unquoted(expr, expected)
                if unquoted is None:
                    const = self._const_named(expr, expected)
            self.found(facts.TypeMismatch(expr.span, expected.display(), got.display(), expected.primitive,
                                          got.primitive, braces, unquoted, const))
        elif verdict == "warn":
            self.found(facts.RealForInt(expr.span))

    def _const_named(self, expr: ast.String, expected: Ty) -> tuple[str, str, str] | None:
        """A material's `unique_name` string where the material is expected: the const model whose
        attribute holds that string, by name (`material: "Tutorial_WheelMaterial"` -> WheelMaterial):
        (its name, the string, the attribute)."""
        want = expected.model if not expected.array and not expected.alts else None
        if want is None:
            return None
        self._suggests = True  # the answer depends on every const model in the program (model/reuse.py)
        for m in self.p.all_models():
            if not m.const or m.is_trait or not self.p.is_subtype(m, want):
                continue
            for a in m.assignments:
                if isinstance(a.value, ast.String) and a.value.value == expr.value:
                    name = m.name if m.unit is self.unit else m.qname
                    return name, expr.value, ".".join(p.name for p in a.path.parts)
        return None

    def _literal_help(self, expr: ast.Expr, expected: Ty) -> tuple | None:
        """How a value of a positional model (a vector, a quaternion) is written, when an array
        literal stands for it: `[0, -1, 0]` for a Math.Vec3 is the usual slip from other languages.
        (its kind, its field names, the items' text when the array has as many as the model has
        fields: the fix swaps the brackets)."""
        model = expected.model if not expected.array and not expected.alts else None
        fields = self.p.positional_fields(model) if model is not None else None
        if not fields or not isinstance(expr, ast.Array):
            return None
        kind = next((m.qname for m in self.p.ancestors(model) if not m.anonymous and "." in m.qname
                     and m.qname.rsplit(".", 1)[1][:1].isupper()), model.qname)
        inner = None
        if len(expr.items) == len(fields):
            text = self.unit.tree.text if self.unit.tree is not None else None
            if text is not None:
                inner = text[expr.span.start.offset + 1 : expr.span.end.offset - 1].strip()
        return kind, tuple(f.name for f in fields), inner

    def _named(self, v) -> facts.Named:
        """What a type, namespace or method named where a value is needed is (facts.Named)."""
        if isinstance(v, TypeObj):
            sym = v.sym
            if isinstance(sym, ModelSym) and not sym.is_trait and not sym.anonymous:
                return facts.Named("model", sym.qname, sym.name)
            return facts.Named("type", str(getattr(sym, "qname", sym)))
        if isinstance(v, NsRef):
            return facts.Named("namespace", v.ns.dotted)
        if isinstance(v, MethodRef):
            return facts.Named("method", name=v.method.name)
        return facts.Named("other")

    def _becomes_meant(self, v, expected: Ty, span: Span) -> bool:
        """`friction: Physics...DryConstantNormalForceFriction`: a model that is a kind of the
        attribute's type, given as its value, where `becomes` was meant (T001 with that fix)."""
        sym = v.sym if isinstance(v, TypeObj) else None
        want = expected.model if not expected.array and not expected.alts else None
        if not isinstance(sym, ModelSym) or sym.is_trait or sym.const or want is None or sym is want \
                or sym.unit is self.unit or not self.p.is_subtype(sym, want):
            return False  # (a model of this file given as a value most often lacks `const`: _not_a_value)
        self.found(facts.ModelForValue(span, sym.qname, sym.name, self.p.concrete(want).qname))
        return True

    def _not_a_value(self, v, span: Span, argument: bool = False) -> None:
        """A type, namespace or method where a value is needed. A model named as a value most often
        lacks `const`: the fact says where it is declared when that is in this file."""
        what = self._named(v)
        at = None
        if what.kind == "model":
            stmt = v.sym.stmt
            if v.sym.unit is self.unit and isinstance(stmt, ast.Declaration):
                at = stmt.header
        self.found(facts.NotAValue(span, what, argument, at))

    def _as_ty(self, v, span: Span) -> Ty:
        if isinstance(v, Ty):
            return v
        self._not_a_value(v, span)
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
            self.found(facts.IndexNotInt(e.index.span, idx.display()))
        if obj.unknown:
            return UNKNOWN
        if not obj.array:
            self.found(facts.NotIndexable(e.span, obj.display()))
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
            self.found(facts.BraceForPrimitive(e.span, target.primitive))
            return UNKNOWN
        fields = self.p.positional_fields(target.model)
        if fields is None:
            for item in e.items:
                self._expr(item)
            return target
        if len(e.items) != len(fields):
            self.found(facts.BraceLength(e.span, self.p.concrete(target.model).qname, tuple(f.name for f in fields),
                                         len(e.items)))
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
            self.found(facts.UnknownName(ident.span, name, name.lower()))
            return UNKNOWN
        self.found(facts.UnknownName(ident.span, name, *self._near(name, options)))
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
            self.found(facts.MethodNotCalled(e.span, base.method.name, name))
            return UNKNOWN
        if isinstance(base, Ty):
            if base.unknown or self._opaque(base):
                return UNKNOWN
            if base.array or base.alts or base.primitive is not None:
                self.found(facts.NoMemberOnValue(e.name.span, base.display(), name))
                return UNKNOWN
        found = resolve.member_target(self.p, base, name)
        if isinstance(base, NsRef):
            v = self._global_value(found, e.name)
            if v is None:
                self.found(facts.UnknownName(e.name.span, name, self._closest(name, list(base.ns.symbols) +
                                                                              list(base.ns.children)),
                                             namespace=base.ns.dotted))
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
                self.found(facts.NoStaticFunction(e.name.span, base.sym.qname, name,
                                                  self._closest(name, self.p.all_methods(base.sym))))
            return UNKNOWN
        self.found(facts.NoAttributeOrMethod(e.name.span, self.p.concrete(base.model).qname, name,
                                             self._closest(name, list(self.p.members_of(base)) + list(self.p.methods_of(base)))))
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
            self.found(facts.NotCallable(e.func.span, self._named(f) if not isinstance(f, Ty) else None,
                                         f.display() if isinstance(f, Ty) else ""))
            return UNKNOWN
        meth = f.method
        if f.on_type and not meth.static:
            self.found(facts.InstanceMethodOnType(e.func.span, meth.name, meth.owner.qname))
        elif not f.on_type and meth.static:
            self.found(facts.StaticOnInstance(e.func.span, meth.name, meth.owner.qname))
        params, ret = self._method_types(meth)
        if len(params) != len(e.args):
            self.found(facts.CallArity(e.span, meth.owner.qname, meth.name, len(params), len(e.args), _signature(meth)))
        else:
            for arg, got, want in zip(e.args, arg_types, params):
                if not isinstance(got, Ty):
                    self._not_a_value(got, arg.span, argument=True)
                    continue
                if isinstance(arg, ast.Brace):
                    got = self._brace(arg, want)
                if self.p.assignable(got, want) == "no":
                    self.found(facts.ArgumentType(arg.span, meth.name, want.display(), got.display(), _signature(meth)))
        if ret is None:
            self.found(facts.ReturnsNothing(e.span, meth.owner.qname, meth.name))
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
        quat = op == "*" and len(operands) == 2 and bool(operands[0].model) and operands[0].model.name == "Quat"
        self.found(facts.NoOperator(e.span, op, tuple(o.display() for o in operands), quat))
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


def _unquoted(expr: ast.String, expected: Ty) -> str | None:
    """`is_dynamic: "false"`: a Bool written in quotes, the word (a number in quotes has its own help)."""
    text = expr.value.strip()
    if expected.primitive != "Bool" or expected.array or text not in ("true", "false"):
        return None
    return text
