"""Symbols and types, built from syntax trees (the bundle sources and the user's files).

Nothing here is hand-listed except the language's primitive type names.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Union

from plxtools.pickling import fast_pickling
from plxtools.syntax import ast

PRIMITIVES = frozenset({"Real", "Int", "Bool", "String", "Blob", "BundleConfig"})
NUMERIC = frozenset({"Real", "Int"})


@dataclass(slots=True, eq=False)
class FileUnit:
    """A parsed file and where it sits: its bundle and namespace."""

    path: str
    tree: ast.File
    namespace: "Namespace"
    bundle: str | None  # None: a loose file outside any bundle
    official: bool = False
    locals: dict[str, "Symbol"] = field(default_factory=dict)  # loose files: their own names
    # names only an import plx cannot read can define (`PendulumScene_rod` after `import @"p.agx"`):
    # made on first use by Program.archive_name, one symbol per name
    archive: dict[str, "Symbol"] = field(default_factory=dict)


@dataclass(slots=True, eq=False)
class Namespace:
    name: str
    qname: tuple[str, ...]
    parent: "Namespace | None" = None
    children: dict[str, "Namespace"] = field(default_factory=dict)
    symbols: dict[str, "Symbol"] = field(default_factory=dict)
    bundle: str | None = None

    @property
    def dotted(self) -> str:
        return ".".join(self.qname)

    def child(self, name: str, bundle: str | None) -> "Namespace":
        ns = self.children.get(name)
        if ns is None:
            ns = Namespace(name, (*self.qname, name), self, bundle=bundle or self.bundle)
            self.children[name] = ns
        return ns


@dataclass(slots=True, eq=False)
class ModelSym:
    name: str
    qname: str
    kind: str  # "model" | "trait"
    stmt: ast.Stmt | None
    unit: FileUnit | None
    namespace: Namespace | None
    const: bool = False
    anonymous: bool = False
    base_ref: ast.TypeExpr | None = None  # `is ...` of the definition (models) or QName (traits)
    base: "Ty | None" = None  # resolved lazily
    trait_refs: list[ast.QName] = field(default_factory=list)  # `with` lines
    traits: "list[ModelSym] | None" = None  # resolved lazily
    members: dict[str, "MemberSym"] = field(default_factory=dict)  # declared here (is/becomes)
    path_members: dict[tuple[str, ...], dict[str, "MemberSym"]] = field(default_factory=dict)
    assignments: list[ast.Assignment] = field(default_factory=list)
    methods: dict[str, "MethodSym"] = field(default_factory=dict)
    annotations: list[ast.Annotation] = field(default_factory=list)
    doc: str | None = None
    deprecated: dict[str, str] = field(default_factory=dict)  # member name -> note from the source
    # filled by model/resolve.py (cleared by Program.invalidate)
    _lin: "list[ModelSym] | None" = None  # layers, lowest priority first
    _inherited: "dict[str, MemberSym] | None" = None
    _all: "dict[str, MemberSym] | None" = None
    _methods: "dict[str, MethodSym] | None" = None
    _open: "bool | None" = None
    # filled by model/completeness.py: paths its own body gives a value (a function of `stmt`, never
    # reset), and the completeness walks below this model (cleared with the member tables)
    _assigned: "frozenset | None" = None
    _walks: "dict | None" = None

    @property
    def is_trait(self) -> bool:
        return self.kind == "trait"

    def __repr__(self) -> str:
        return f"<{self.kind} {self.qname}>"


@dataclass(slots=True, eq=False)
class MemberSym:
    name: str
    owner: ModelSym
    stmt: ast.Declaration
    keyword: str  # "is" | "becomes"
    optional: bool
    reference: bool
    value: ast.Expr | None
    anon: ModelSym | None = None  # the instance block's anonymous subtype
    ty: "Ty | None" = None  # resolved lazily
    doc: str | None = None

    @property
    def qname(self) -> str:
        return f"{self.owner.qname}.{self.name}"


@dataclass(slots=True, eq=False)
class GlobalSym:
    name: str
    qname: str
    stmt: ast.Declaration
    unit: FileUnit
    namespace: Namespace
    ty: "Ty | None" = None


@dataclass(slots=True, eq=False)
class MethodSym:
    name: str
    owner: ModelSym
    stmt: ast.Method
    static: bool

    @property
    def qname(self) -> str:
        return f"{self.owner.qname}.{self.name}"


@dataclass(slots=True, eq=False)
class OperatorSym:
    op: str
    stmt: ast.OperatorDecl
    unit: FileUnit
    params: "list[Ty] | None" = None
    returns: "Ty | None" = None


Symbol = Union[ModelSym, GlobalSym]


@dataclass(frozen=True, slots=True)
class Ty:
    """A type: a model, a primitive name, or unknown (sym None); maybe an array, maybe a union."""

    sym: object = None  # ModelSym | str | None
    array: bool = False
    traits: tuple = ()
    alts: tuple = ()  # a union: tuple of Ty

    @property
    def unknown(self) -> bool:
        return self.sym is None and not self.alts

    @property
    def primitive(self) -> str | None:
        return self.sym if isinstance(self.sym, str) else None

    @property
    def model(self) -> ModelSym | None:
        return self.sym if isinstance(self.sym, ModelSym) else None

    def element(self) -> "Ty":
        return Ty(self.sym, False, self.traits, tuple(a.element() for a in self.alts) if self.alts else ())

    def display(self) -> str:
        if self.alts:
            return " or ".join(a.display() for a in self.alts)
        if self.sym is None:
            return "unknown"
        base = self.sym if isinstance(self.sym, str) else self.sym.qname
        if isinstance(self.sym, ModelSym) and self.sym.anonymous:
            base = self.sym.base.display() if self.sym.base is not None else self.sym.qname
        if self.traits:
            base += " with " + ", ".join(t.qname for t in self.traits)
        return base + ("[]" if self.array else "")


UNKNOWN = Ty()
REAL = Ty("Real")
INT = Ty("Int")
BOOL = Ty("Bool")
STRING = Ty("String")


def doc_of(body: list[ast.Stmt] | None) -> str | None:
    if not body:
        return None
    for s in body:
        if isinstance(s, ast.Annotation) and s.name.name == "doc" and isinstance(s.value, ast.String):
            return s.value.value.strip("\n")
    return None


fast_pickling(FileUnit, Namespace, ModelSym, MemberSym, GlobalSym, MethodSym, OperatorSym, Ty)
