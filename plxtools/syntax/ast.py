"""The OpenPLX syntax tree. Every node carries its exact span; nothing here knows about types.

Statements are one logical line each (a header), optionally owning an indented block (`body`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields, is_dataclass
from itertools import zip_longest
from typing import Iterator, Union

from plxtools.diagnostics import Diagnostic, Span
from plxtools.pickling import fast_pickling
from plxtools.syntax.source import LineIndex


@dataclass(slots=True, eq=False)
class Node:
    span: Span


# ---------------------------------------------------------------- names and types


@dataclass(slots=True, eq=False)
class Ident(Node):
    name: str
    backtick: bool = False


@dataclass(slots=True, eq=False)
class QName(Node):
    parts: list[Ident]

    @property
    def text(self) -> str:
        return ".".join(p.name for p in self.parts)


@dataclass(slots=True, eq=False)
class TypeRef(Node):
    name: QName
    array: bool = False


@dataclass(slots=True, eq=False)
class TypeExpr(Node):
    alternatives: list[TypeRef]
    traits: list[QName] = field(default_factory=list)


# ---------------------------------------------------------------- expressions


@dataclass(slots=True, eq=False)
class Number(Node):
    text: str
    value: int | float
    is_int: bool


@dataclass(slots=True, eq=False)
class String(Node):
    kind: str  # "plain" | "triple" | "path" | "interp"
    value: str
    raw: str


@dataclass(slots=True, eq=False)
class Bool(Node):
    value: bool


@dataclass(slots=True, eq=False)
class This(Node):
    pass


@dataclass(slots=True, eq=False)
class Name(Node):
    ident: Ident


@dataclass(slots=True, eq=False)
class Member(Node):
    obj: "Expr"
    name: Ident


@dataclass(slots=True, eq=False)
class Call(Node):
    func: "Expr"
    args: list["Expr"]


@dataclass(slots=True, eq=False)
class Index(Node):
    obj: "Expr"
    index: "Expr"


@dataclass(slots=True, eq=False)
class Unary(Node):
    op: str
    operand: "Expr"


@dataclass(slots=True, eq=False)
class Binary(Node):
    op: str
    left: "Expr"
    right: "Expr"


@dataclass(slots=True, eq=False)
class Paren(Node):
    inner: "Expr"


@dataclass(slots=True, eq=False)
class Brace(Node):
    items: list["Expr"]


@dataclass(slots=True, eq=False)
class Array(Node):
    items: list["Expr"]


Expr = Union[Number, String, Bool, This, Name, Member, Call, Index, Unary, Binary, Paren, Brace, Array]


# ---------------------------------------------------------------- statements


@dataclass(slots=True, eq=False)
class Stmt(Node):
    """`span` covers the header line and its block; `header` only the logical line."""

    header: Span


@dataclass(slots=True, eq=False)
class Declaration(Stmt):
    """`path is T`, `path becomes T`, or at top level a bare `Name` / `Name:` model."""

    path: QName
    keyword: str | None  # "is" | "becomes" | None (top-level model without base)
    type: TypeExpr | None
    const: bool = False
    optional: bool = False
    reference: bool = False
    value: Expr | None = None
    body: list["Stmt"] | None = None
    colon: bool = False


@dataclass(slots=True, eq=False)
class Assignment(Stmt):
    path: QName
    value: Expr | None = None
    body: list["Stmt"] | None = None


@dataclass(slots=True, eq=False)
class WithStmt(Stmt):
    traits: list[QName]


@dataclass(slots=True, eq=False)
class Annotation(Stmt):
    name: Ident
    value: Expr


@dataclass(slots=True, eq=False)
class Param(Node):
    name: Ident
    type: TypeRef


@dataclass(slots=True, eq=False)
class Method(Stmt):
    name: Ident
    params: list[Param]
    returns: TypeRef | None
    static: bool = False


@dataclass(slots=True, eq=False)
class OperatorDecl(Stmt):
    op: str
    params: list[Param]
    returns: TypeRef | None


@dataclass(slots=True, eq=False)
class TraitDef(Stmt):
    name: Ident
    base: QName | None
    body: list["Stmt"] | None = None
    colon: bool = False


@dataclass(slots=True, eq=False)
class Import(Stmt):
    source: String
    alias: QName | None


@dataclass(slots=True, eq=False)
class ErrorStmt(Stmt):
    """A line that did not parse; kept so its block and its leading name still serve the editor."""

    text: str
    body: list["Stmt"] | None = None


@dataclass(slots=True, eq=False)
class Comment(Node):
    text: str
    own_line: bool


@dataclass(slots=True, eq=False)
class File:
    path: str
    text: str
    statements: list[Stmt]
    comments: list[Comment]
    diagnostics: list[Diagnostic]
    index: LineIndex
    had_bom: bool = False
    newline: str = "\n"

    @property
    def has_errors(self) -> bool:
        return any(d.severity.value == "error" for d in self.diagnostics)

    def has_errors_of_syntax(self) -> bool:
        """Syntax errors (which block fixes and formatting); warnings such as tabs do not."""
        return self.has_errors


BLOCK_OWNERS = (Declaration, Assignment, TraitDef, ErrorStmt)


def body_of(stmt: Stmt) -> list[Stmt] | None:
    return getattr(stmt, "body", None)


def walk_statements(stmts: list[Stmt]) -> Iterator[Stmt]:
    """Every statement, depth first, without recursion (files may nest hundreds of levels)."""
    stack = [iter(stmts)]
    while stack:
        for stmt in stack[-1]:
            yield stmt
            body = body_of(stmt)
            if body:
                stack.append(iter(body))
            break
        else:
            stack.pop()


def structure(node: object) -> tuple:
    """A layout-free rendering of a tree: equal for two texts that mean the same.

    Flat (pre-order, with open and close markers) and built without recursion, so two renderings
    of a file nested hundreds of levels deep compare at Python's default recursion limit.
    """
    return tuple(iter_structure(node))


def same_structure(a: object, b: object) -> bool:
    """`structure(a) == structure(b)`, compared as both are walked: neither rendering is ever held
    whole (on a big file each would take several times the memory of its tree)."""
    end = object()
    return all(x == y for x, y in zip_longest(iter_structure(a), iter_structure(b), fillvalue=end))


def iter_structure(node: object) -> Iterator[object]:
    """The items of `structure(node)`, one by one."""
    stack: list[object] = [node]
    while stack:
        n = stack.pop()
        if n is _CLOSE:
            yield ")"
        elif isinstance(n, list):
            yield "["
            stack.append(_CLOSE)
            stack.extend(reversed(n))
        elif is_dataclass(n) and isinstance(n, Node):
            yield type(n).__name__
            stack.append(_CLOSE)
            stack.extend(reversed([getattr(n, f.name) for f in fields(n) if f.name not in ("span", "header")]))
        else:
            yield repr(n)


_CLOSE = object()


def _all_subclasses(cls):
    for sub in cls.__subclasses__():
        yield sub
        yield from _all_subclasses(sub)


fast_pickling(Node, *_all_subclasses(Node))
