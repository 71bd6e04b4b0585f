"""Parse OpenPLX text into a syntax tree plus located syntax errors. Never raises on input."""

from __future__ import annotations

import threading
from pathlib import Path

from typing import TYPE_CHECKING, Iterable

from plxtools.diagnostics import Diagnostic, Edit, Fix, Pos, Severity, Span
from plxtools.syntax import ast
from plxtools.syntax.depth import MAX_EXPR_DEPTH, too_deep
from plxtools.syntax.keywords import closest_keyword
from plxtools.syntax.lexer import TAB_INDENTATION, Lexer, LogicalLine, Token, ambiguous_tab
from plxtools.syntax.lexer import too_deep as nesting_too_deep

if TYPE_CHECKING:  # lark is imported when the LALR fallback is first needed (_get_parser)
    from lark import Lark
    from lark.exceptions import UnexpectedInput
from plxtools.syntax.source import LineIndex, TextSpan, decode, decode_text, line_start

INDENTATION_BETWEEN_LEVELS = "S015"  # raised here; style and the consequence filter recognise it by this name

# ------------------------------------------------------------------ building nodes


_TS = TextSpan
# The line table of the text being parsed: every span built refers to it (lines and columns are
# computed from it when asked). Set for one parse at a time under _parsing (the language server
# parses in two threads).
_L: LineIndex | None = None
_parsing = threading.RLock()


def _sp(x) -> TextSpan:
    if type(x) is Token:
        return _TS(x.start_pos, x.end_pos, _L)
    return x.span


def _cover(children) -> Span:
    """The span from the first child that is there to the last (tokens or nodes)."""
    for first in children:
        if first is not None:
            break
    for last in reversed(children):
        if last is not None:
            break
    if first is last and type(first) is not Token:
        return first.span  # one child: its span, shared (spans are immutable; a big file has millions)
    return _TS(first.start_pos if type(first) is Token else first.span.s,
               last.end_pos if type(last) is Token else last.span.e, _L)


class _Seq(list):
    """A list of nodes that remembers the span of the brackets around it."""

    __slots__ = ("span",)


def _is_tok(x, kind: str) -> bool:
    return isinstance(x, Token) and x.type == kind


_STRING_KINDS = {"@": "path", "$": "interp"}


class _Build:
    """Turns each grammar rule straight into an AST node (no intermediate lark tree). The fast
    path calls some of these itself; the LALR parser gets them as a lark Transformer (_get_parser)."""

    # names and types
    def name(self, c):
        t = c[0]
        return ast.Ident(_sp(t), str(t), t.type == "TICKNAME")

    def qname(self, c):
        parts = [x for x in c if isinstance(x, ast.Ident)]
        return ast.QName(_cover(c), parts)

    def type_ref(self, c):
        return ast.TypeRef(_cover(c), c[0], _is_tok(c[1], "LSQB"))

    def type_expr(self, c):
        alts = [x for x in c if isinstance(x, ast.TypeRef)]
        traits = [x for x in c if isinstance(x, ast.QName)]
        return ast.TypeExpr(_cover(c), alts, traits)

    # expressions
    def number(self, c):
        t = c[0]
        text = t.value
        is_int = "." not in text and "e" not in text and "E" not in text
        try:
            value = int(text) if is_int else float(text)
        except ValueError:  # over Python's int-string limit: the lexer has reported it (S005)
            value = float(text)
        return ast.Number(_sp(t), text, value, is_int)

    def string(self, c):
        t = str(c[0])
        if t.startswith('"""'):
            kind, body = "triple", t[3:-3] if t.endswith('"""') and len(t) >= 6 else t[3:]
        else:
            kind = _STRING_KINDS.get(t[0], "plain")
            inner = t[1:] if kind == "plain" else t[2:]
            body = inner[:-1] if inner.endswith('"') else inner
        return ast.String(_sp(c[0]), kind, body, t)

    def true(self, c):
        return ast.Bool(_sp(c[0]), True)

    def false(self, c):
        return ast.Bool(_sp(c[0]), False)

    def this(self, c):
        return ast.This(_sp(c[0]))

    def ref(self, c):
        return ast.Name(c[0].span, c[0])

    def paren(self, c):
        return ast.Paren(_cover(c), c[1])

    def args(self, c):
        return [x for x in c if not isinstance(x, Token) and x is not None]

    def brace(self, c):
        return ast.Brace(_cover(c), c[1] or [])

    def array(self, c):
        return ast.Array(_cover(c), c[1] or [])

    def binary(self, c):
        return ast.Binary(_cover(c), str(c[1]), c[0], c[2])

    def neg(self, c):
        return ast.Unary(_cover(c), "-", c[1])

    def member(self, c):
        return ast.Member(_cover(c), c[0], c[2])

    def call(self, c):
        return ast.Call(_cover(c), c[0], c[2] or [])

    def index(self, c):
        return ast.Index(_cover(c), c[0], c[2])

    # statements
    def import_stmt(self, c):
        s = self.string([c[1]])
        span = _cover(c)
        return ast.Import(span, span, s, c[3])

    def op(self, c):
        return c[0]

    def param(self, c):
        return ast.Param(_cover(c), c[0], c[2])

    def param_kw(self, c):
        t = c[0]  # a keyword used as a parameter name is an ordinary name there
        return ast.Ident(_sp(t), str(t), False)

    def params(self, c):
        seq = _Seq(x for x in c if isinstance(x, ast.Param))
        seq.span = _cover(c)
        return seq

    def operator_decl(self, c):
        span = _cover(c)
        return ast.OperatorDecl(span, span, str(c[1]), list(c[2]), c[4])

    def method(self, c):
        span = _cover(c)
        return ast.Method(span, span, c[2], list(c[3]), c[5], static=c[0] is not None)

    def trait_def(self, c):
        span = _cover(c)
        return ast.TraitDef(span, span, c[1], c[3], None, colon=c[4] is not None)

    def with_stmt(self, c):
        span = _cover(c)
        return ast.WithStmt(span, span, [x for x in c if isinstance(x, ast.QName)])

    def annotation(self, c):
        span = _cover(c)
        return ast.Annotation(span, span, c[1], c[3])

    def declaration(self, c):
        const, optional, path, _is, texpr, reference, colon, value = c
        span = _cover(c)
        return ast.Declaration(
            span,
            span,
            path,
            "is",
            texpr,
            const=const is not None,
            optional=optional is not None,
            reference=reference is not None,
            value=value,
            colon=colon is not None,
        )

    def becomes_stmt(self, c):
        path, _b, texpr, reference, colon, value = c
        span = _cover(c)
        return ast.Declaration(
            span, span, path, "becomes", texpr, reference=reference is not None, value=value,
            colon=colon is not None,
        )

    def assignment(self, c):
        span = _cover(c)
        return ast.Assignment(span, span, c[0], c[2])

    def bare(self, c):
        span = _cover(c)
        return ast.Declaration(span, span, c[0], None, None)

    def const_bare(self, c):
        span = _cover(c)
        return ast.Declaration(span, span, c[1], None, None, const=True, colon=c[2] is not None)


_parser_lock = threading.Lock()
_PARSER: "Lark | None" = None


def _get_parser() -> Lark:
    global _PARSER
    if _PARSER is None:
        with _parser_lock:
            if _PARSER is None:
                grammar = Path(__file__).with_name("openplx.lark").read_text(encoding="utf-8")
                from plxtools.syntax.lalr import build_parser

                # an authenticated entry of plx's cache (lalr.py), never lark's own pickle file
                _PARSER = build_parser(grammar)
    return _PARSER


# ------------------------------------------------------------------ error messages

_TERMINAL_WORDS = {
    "NAME": "a name",
    "TICKNAME": "a name",
    "NUMBER": "a number",
    "STRING": "a string",
    "COLON": "':'",
    "DOT": "'.'",
    "COMMA": "','",
    "LPAR": "'('",
    "RPAR": "')'",
    "LSQB": "'['",
    "RSQB": "']'",
    "LBRACE": "'{'",
    "RBRACE": "'}'",
    "PLUS": "'+'",
    "MINUS": "'-'",
    "STAR": "'*'",
    "SLASH": "'/'",
    "ARROW": "'->'",
    "$END": "the end of the line",
    "an operator": "an operator",
}


def _word(kind: str) -> str:
    if kind in _TERMINAL_WORDS:
        return _TERMINAL_WORDS[kind]
    return f"'{kind.lower()}'"


def _expected_text(expected: set[str]) -> str:
    exp = set(expected)
    parts: list[str] = []
    if {"NUMBER", "STRING", "LBRACE"} <= exp:
        parts.append("a value")
        exp -= {"NUMBER", "STRING", "LBRACE", "LSQB", "LPAR", "MINUS", "NAME", "TICKNAME", "TRUE",
                "FALSE", "THIS"}
    if "TICKNAME" in exp:
        exp.discard("TICKNAME")
        exp.add("NAME")
    words = sorted({_word(k) for k in exp})
    parts.extend(words)
    if not parts:
        return ""
    if len(parts) > 5:
        parts = parts[:5] + ["..."]
    if len(parts) == 1:
        return parts[0]
    return ", ".join(parts[:-1]) + " or " + parts[-1]


_CLOSER_OF = {"LPAR": "RPAR", "LSQB": "RSQB", "LBRACE": "RBRACE"}


def _syntax_error(exc: "UnexpectedInput", line: LogicalLine) -> Diagnostic:
    """S011 from the grammar's failure: what it met, what could have come, and a keyword fix."""
    from lark.exceptions import UnexpectedEOF, UnexpectedToken

    tok = getattr(exc, "token", None)
    at_end = isinstance(exc, UnexpectedEOF) or tok is None or tok.type == "$END"
    if at_end:
        last = line.tokens[-1]
        span = _sp(last)
        msg = f"unexpected end of line after '{last}'"
    else:
        span = _sp(tok)
        msg = "unexpected " + ("a string" if tok.type == "STRING" else f"'{tok}'")
    expected = set(getattr(exc, "expected", None) or set())
    if tok is not None and tok.type != "$END":
        expected = _expected_here(expected, line, tok)
    exp = _expected_text(expected)
    if exp:
        msg += f"; expected {exp}"
    help_ = None
    first = line.tokens[0]
    if first.type in ("NAME", "TICKNAME") and isinstance(exc, UnexpectedToken) and tok is not None \
            and tok.type == "NAME" and len(line.tokens) > 1 and line.tokens[1] is tok:
        help_ = "declare with 'name is Type', or give a value with 'name: value'"
    fix = None
    value_after_is = _value_after_is(line, tok)
    if value_after_is is not None:
        help_, fix = value_after_is
    braces = _paren_vector(line, tok) if tok is not None and tok.type == "COMMA" else None
    if braces is not None:
        (a, b), text = braces
        help_ = f"a vector is written in braces: {text}"
        fix = Fix(f"write {text}", (Edit(a.start.offset, a.end.offset, "{"), Edit(b.start.offset, b.end.offset, "}")),
                  safe=False)
    if tok is not None and tok.type == "NAME":
        kw = closest_keyword(str(tok), set(getattr(exc, "expected", None) or ()))
        if kw is not None:
            help_ = f"did you mean '{kw}'?"
            fix = Fix(f"replace with '{kw}'", (Edit(span.start.offset, span.end.offset, kw),), safe=False)
    return Diagnostic("S011", msg, span, Severity.ERROR, help=help_, fix=fix)


_VALUE_START = frozenset({"NUMBER", "STRING", "TRUE", "FALSE", "MINUS", "LBRACE", "LSQB"})


def _value_after_is(line: LogicalLine, tok):
    """`inertia.mass is 15`: a value after `is`, where `:` gives one: (help, fix) or None."""
    if tok is None or tok.type not in _VALUE_START:
        return None
    toks = line.tokens
    at = next((i for i, t in enumerate(toks) if t is tok), None)
    if not at or toks[at - 1].type != "IS":
        return None
    is_tok = toks[at - 1]
    a, b = _sp(toks[at - 2]) if at >= 2 else _sp(is_tok), _sp(is_tok)
    return ("'is' declares an attribute and its type; a value is given with ':'",
            Fix("give the value with ':'", (Edit(a.end.offset, b.end.offset, ":"),), safe=False))


def _paren_vector(line: LogicalLine, comma: Token):
    """`(1, 0, 0)` where `{1, 0, 0}` was meant: the spans of the parentheses around `comma` (not a
    call's) and the text in braces, or None."""
    toks = line.tokens
    at = next((i for i, t in enumerate(toks) if t is comma), None)
    if at is None:
        return None
    depth, opener = 0, None
    for i in range(at - 1, -1, -1):
        kind = toks[i].type
        if kind in ("RPAR", "RSQB", "RBRACE"):
            depth += 1
        elif kind in ("LPAR", "LSQB", "LBRACE"):
            if depth == 0:
                opener = i
                break
            depth -= 1
    if opener is None or toks[opener].type != "LPAR" or (opener > 0 and toks[opener - 1].type in ("NAME", "TICKNAME", "RPAR")):
        return None
    depth = 0
    for j in range(opener + 1, len(toks)):
        kind = toks[j].type
        if kind in ("LPAR", "LSQB", "LBRACE"):
            depth += 1
        elif kind in ("RPAR", "RSQB", "RBRACE"):
            if depth == 0:
                if kind != "RPAR":
                    return None
                a, b = _sp(toks[opener]), _sp(toks[j])
                inner = line_text_between(toks, opener, j)
                return (a, b), "{" + inner + "}"
            depth -= 1
    return None


def line_text_between(toks, i: int, j: int) -> str:
    """The tokens strictly between `i` and `j`, with a space after each comma."""
    out = ""
    for t in toks[i + 1:j]:
        out += str(t) + (" " if t.type == "COMMA" else "")
    return out


def _expected_here(expected: set[str], line: LogicalLine, tok: Token) -> set[str]:
    """What the grammar expected at `tok`, narrowed to what fits there: only the closer of the
    innermost open bracket, no comma outside brackets, and "an operator" for the operators."""
    open_: list[str] = []
    for t in line.tokens:
        if t is tok:
            break
        if t.type in _CLOSER_OF:
            open_.append(_CLOSER_OF[t.type])
        elif t.type in ("RPAR", "RSQB", "RBRACE") and open_:
            open_.pop()
    expected -= {"RPAR", "RSQB", "RBRACE"} - set(open_[-1:])
    if not open_:
        expected.discard("COMMA")
    if "$END" in expected and expected & {"PLUS", "STAR"}:
        expected -= {"PLUS", "MINUS", "STAR", "SLASH", "DOT", "LPAR", "LSQB"}
        expected.add("an operator")
    return expected


# ------------------------------------------------------------------ the driver


class _Frame:
    __slots__ = ("header_indent", "child_indent", "body", "owner", "child8")

    def __init__(self, header_indent: int, child_indent: int | None, body: list, owner, child8: int | None = None):
        self.header_indent = header_indent
        self.child_indent = child_indent
        self.body = body
        self.owner = owner
        self.child8 = child8  # the child indentation with 8-wide tabs (files with tabs only)


_B = _Build()
_NAMEISH = ("NAME", "TICKNAME")
FAST_PATH = True  # tests turn it off to compare with the grammar


class _NotFast(Exception):
    """The line is not one the fast path builds: the grammar parses it (and reports its errors)."""


_Ident, _QName, _Name, _Member, _Call, _Binary = ast.Ident, ast.QName, ast.Name, ast.Member, ast.Call, ast.Binary
_MAX_FAST_DEPTH = 40  # deeper brackets or `- - -` chains go to the grammar (no recursion limits here)
_PRIMARY_LITERALS = {"NUMBER": _B.number, "STRING": _B.string, "TRUE": _B.true, "FALSE": _B.false,
                     "THIS": _B.this}
_PREC = {"PLUS": 1, "MINUS": 1, "STAR": 2, "SLASH": 2}


def _ident(t: Token) -> ast.Ident:
    """What the grammar's `name` builds for a NAME or TICKNAME token."""
    return _Ident(_TS(t.start_pos, t.end_pos, _L), t.value, t.type == "TICKNAME")


def _qname(tokens: list[Token], i: int) -> tuple[ast.QName | None, int]:
    """What the grammar's `qname` builds from i (None if no name is there), and the next index."""
    n = len(tokens)
    if i >= n or tokens[i].type not in _NAMEISH:
        return None, i
    parts = [_ident(tokens[i])]
    i += 1
    while i + 1 < n and tokens[i].type == "DOT" and tokens[i + 1].type in _NAMEISH:
        parts.append(_ident(tokens[i + 1]))
        i += 2
    if len(parts) == 1:
        return _QName(parts[0].span, parts), i
    return _QName(_TS(parts[0].span.s, parts[-1].span.e, _L), parts), i


class _ExprParser:
    """The grammar's `expr` over one logical line's tokens (precedence climbing for the binary
    operators, a loop for unary minus and the postfix forms), building the nodes the grammar's
    builders build, with the same spans; raises _NotFast on anything else (the grammar then parses
    the line and words the error)."""

    __slots__ = ("tokens", "n", "depth")

    def __init__(self, tokens: list[Token]):
        self.tokens = tokens
        self.n = len(tokens)
        self.depth = 0

    def expr(self, i: int, min_prec: int = 1):
        """`sum` (min_prec 1) or `product` (2) from i: left-associative, `*` `/` above `+` `-`."""
        tokens, n = self.tokens, self.n
        left, i = self.operand(i)
        while i < n:
            op = tokens[i]
            prec = _PREC.get(op.type)
            if prec is None or prec < min_prec:
                break
            right, i = self.expr(i + 1, prec + 1)
            left = _Binary(_TS(left.span.s, right.span.e, _L), op.value, left, right)
        return left, i

    def operand(self, i: int):  # noqa: C901 - `unary`, `postfix` and `primary` in one loop
        tokens, n = self.tokens, self.n
        j = i
        while j < n and tokens[j].type == "MINUS":
            j += 1
        if j - i > _MAX_FAST_DEPTH:
            raise _NotFast
        if j >= n:
            raise _NotFast
        t = tokens[j]
        kind = t.type
        build = _PRIMARY_LITERALS.get(kind)
        if build is not None:
            node = build([t])
            k = j + 1
        elif kind in _NAMEISH:
            name = _ident(t)
            node = _Name(name.span, name)
            k = j + 1
        elif kind == "LPAR":
            self.enter()
            inner, k = self.expr(j + 1)
            self.depth -= 1
            if k >= n or tokens[k].type != "RPAR":
                raise _NotFast
            node = _B.paren([t, inner, tokens[k]])
            k += 1
        elif kind == "LSQB":
            args, k = self.args(j + 1, "RSQB")
            node = _B.array([t, args, tokens[k]])
            k += 1
        elif kind == "LBRACE":
            args, k = self.args(j + 1, "RBRACE")
            node = _B.brace([t, args, tokens[k]])
            k += 1
        else:
            raise _NotFast
        while k < n:  # postfix: `.name`, `(args)`, `[index]`
            t = tokens[k]
            kind = t.type
            if kind == "DOT":
                if k + 1 < n and tokens[k + 1].type in _NAMEISH:
                    name = _ident(tokens[k + 1])
                    node = _Member(_TS(node.span.s, name.span.e, _L), node, name)
                    k += 2
                    continue
                raise _NotFast
            if kind == "LPAR":
                args, k = self.args(k + 1, "RPAR")
                r = tokens[k]
                node = _Call(_TS(node.span.s, r.end_pos, _L), node, args or [])
                k += 1
                continue
            if kind == "LSQB":
                self.enter()
                index, m = self.expr(k + 1)
                self.depth -= 1
                if m >= n or tokens[m].type != "RSQB":
                    raise _NotFast
                node = _B.index([node, t, index, tokens[m]])
                k = m + 1
                continue
            break
        while j > i:  # unary minus, innermost first
            j -= 1
            node = _B.neg([tokens[j], node])
        return node, k

    def args(self, i: int, closer: str):
        """`[args] closer` from i: (the expressions or None, the index of the closer)."""
        tokens, n = self.tokens, self.n
        if i < n and tokens[i].type == closer:
            return None, i
        self.enter()
        items: list = []  # what the grammar's `args` builds: the expressions
        while True:
            item, i = self.expr(i)
            items.append(item)
            if i >= n:
                raise _NotFast
            kind = tokens[i].type
            if kind == closer:
                break
            if kind != "COMMA":
                raise _NotFast
            i += 1
            if i < n and tokens[i].type == closer:
                break
        self.depth -= 1
        return items, i

    def enter(self) -> None:
        self.depth += 1
        if self.depth > _MAX_FAST_DEPTH:
            raise _NotFast


def _value(tokens: list[Token], i: int):
    """The expression from i to the end of the line; raises _NotFast if it is not one."""
    expr, j = _ExprParser(tokens).expr(i)
    if j != len(tokens):
        raise _NotFast
    return expr


def _type_expr(tokens: list[Token], i: int):
    """`type_ref (OR type_ref)* [WITH qname (COMMA qname)*]` from i: (node, next index)."""
    n = len(tokens)
    items: list = []
    while True:
        name, i = _qname(tokens, i)
        if name is None:
            raise _NotFast
        if i + 1 < n and tokens[i].type == "LSQB" and tokens[i + 1].type == "RSQB":
            items.append(_B.type_ref([name, tokens[i], tokens[i + 1]]))
            i += 2
        else:
            items.append(_B.type_ref([name, None, None]))
        if i < n and tokens[i].type == "OR":
            items.append(tokens[i])
            i += 1
            continue
        break
    if i < n and tokens[i].type == "WITH":
        items.append(tokens[i])
        i += 1
        while True:
            name, i = _qname(tokens, i)
            if name is None:
                raise _NotFast
            items.append(name)
            if i < n and tokens[i].type == "COMMA":
                items.append(tokens[i])
                i += 1
                continue
            break
    return _B.type_expr(items), i


def _fast(tokens: list[Token]) -> ast.Stmt | None:
    """The statement lines that models are made of, built without the LALR parser by the grammar's
    own node builders: `a.b:` and `a.b: expr`, `[const] [optional] a is T [or U] [with X]
    [reference] [: [expr]]`, `a becomes T ...`, `.name: expr`, `with A, B` and a bare `A`. Any
    other line (imports, traits, methods, operators, errors) returns None and goes to the
    grammar; tests check that both build the same tree."""
    try:
        return _fast_stmt(tokens)
    except _NotFast:
        return None


def _fast_stmt(tokens: list[Token]) -> ast.Stmt | None:
    """One line's shapes, by its first token (None or _NotFast: the grammar decides)."""
    first = tokens[0].type
    if first == "DOT":  # `.doc: "..."`
        return _fast_annotation(tokens)
    if first == "WITH":  # `with A.B, C`
        return _fast_with(tokens)
    if first in _HEADER_KEYWORDS:
        return _fast_header(tokens, first)
    return _fast_declaration(tokens, first)


def _fast_annotation(tokens: list[Token]) -> ast.Stmt | None:
    if len(tokens) >= 4 and tokens[1].type in _NAMEISH and tokens[2].type == "COLON":
        return _B.annotation([tokens[0], _ident(tokens[1]), tokens[2], _value(tokens, 3)])
    return None


def _fast_with(tokens: list[Token]) -> ast.Stmt | None:
    n = len(tokens)
    items: list = [tokens[0]]
    i = 1
    while True:
        q, i = _qname(tokens, i)
        if q is None:
            return None
        items.append(q)
        if i == n:
            return _B.with_stmt(items)
        if tokens[i].type != "COMMA":
            return None
        items.append(tokens[i])
        i += 1


def _fast_declaration(tokens: list[Token], first: str) -> ast.Stmt | None:
    """`[const] [optional] a.b ...`: a bare name, an assignment, a declaration or a `becomes`."""
    n = len(tokens)
    const = optional = None
    i = 0
    if first == "CONST":
        const = tokens[0]
        i = 1
    if i < n and tokens[i].type == "OPTIONAL":
        optional = tokens[i]
        i += 1
    path, i = _qname(tokens, i)
    if path is None:
        return None
    if i == n:  # `A` (or `const A`): a bare name
        if optional is not None:
            return None
        return _B.const_bare([const, path, None]) if const is not None else _B.bare([path])
    kw = tokens[i]
    kind = kw.type
    if kind == "COLON":
        if optional is not None:
            return None
        if const is not None:
            return _B.const_bare([const, path, kw]) if i + 1 == n else None
        return _B.assignment([path, kw, None if i + 1 == n else _value(tokens, i + 1)])
    if kind == "BECOMES":
        if const is not None or optional is not None:
            return None
    elif kind != "IS":
        return None
    texpr, j = _type_expr(tokens, i + 1)
    reference, colon, value = _typed_tail(tokens, j)
    if kind == "IS":
        return _B.declaration([const, optional, path, kw, texpr, reference, colon, value])
    return _B.becomes_stmt([path, kw, texpr, reference, colon, value])


def _typed_tail(tokens: list[Token], j: int) -> tuple:
    """`[reference] [: [expr]]` after a type: (REFERENCE, COLON, value), each or None."""
    n = len(tokens)
    reference = colon = value = None
    if j < n and tokens[j].type == "REFERENCE":
        reference = tokens[j]
        j += 1
    if j < n:
        if tokens[j].type != "COLON":
            raise _NotFast
        colon = tokens[j]
        if j + 1 < n:
            value = _value(tokens, j + 1)
    return reference, colon, value


_HEADER_KEYWORDS = frozenset(("TRAIT", "FN", "STATIC", "OPERATOR", "IMPORT"))
_OPS = frozenset(("PLUS", "MINUS", "STAR", "SLASH"))


def _type_ref(tokens: list[Token], i: int):
    name, i = _qname(tokens, i)
    if name is None:
        raise _NotFast
    n = len(tokens)
    if i + 1 < n and tokens[i].type == "LSQB" and tokens[i + 1].type == "RSQB":
        return _B.type_ref([name, tokens[i], tokens[i + 1]]), i + 2
    return _B.type_ref([name, None, None]), i


def _params(tokens: list[Token], i: int):
    """`( [param (, param)* [,]] )` from i: (the params node, the index after ')')."""
    n = len(tokens)
    if i >= n or tokens[i].type != "LPAR":
        raise _NotFast
    items: list = [tokens[i]]
    i += 1
    while i < n and tokens[i].type != "RPAR":
        t = tokens[i]
        if t.type in _NAMEISH:
            name = _ident(t)
        elif t.type == "REFERENCE":
            name = _B.param_kw([t])
        else:
            raise _NotFast
        if i + 1 >= n or tokens[i + 1].type != "COLON":
            raise _NotFast
        colon = tokens[i + 1]
        ref, i = _type_ref(tokens, i + 2)
        items.append(_B.param([name, colon, ref]))
        if i < n and tokens[i].type == "COMMA":
            items.append(tokens[i])
            i += 1
        elif i >= n or tokens[i].type != "RPAR":
            raise _NotFast
    if i >= n:
        raise _NotFast
    items.append(tokens[i])
    return _B.params(items), i + 1


def _returns(tokens: list[Token], i: int):
    """`[-> type_ref]` ending the line: (ARROW or None, type_ref or None)."""
    n = len(tokens)
    if i == n:
        return None, None
    if tokens[i].type != "ARROW":
        raise _NotFast
    ref, j = _type_ref(tokens, i + 1)
    if j != n:
        raise _NotFast
    return tokens[i], ref


def _fast_header(tokens: list[Token], first: str) -> ast.Stmt | None:
    """`trait`, `fn`, `static fn`, `operator` and `import` lines."""
    n = len(tokens)
    if first == "TRAIT":  # trait Name [is Q] [:]
        if n < 2 or tokens[1].type not in _NAMEISH:
            return None
        name = _ident(tokens[1])
        kw = base = colon = None
        i = 2
        if i < n and tokens[i].type == "IS":
            kw = tokens[i]
            base, i = _qname(tokens, i + 1)
            if base is None:
                return None
        if i < n and tokens[i].type == "COLON":
            colon = tokens[i]
            i += 1
        if i != n:
            return None
        return _B.trait_def([tokens[0], name, kw, base, colon])
    if first == "IMPORT":  # import "x" [as Q]
        if n < 2 or tokens[1].type != "STRING":
            return None
        if n == 2:
            return _B.import_stmt([tokens[0], tokens[1], None, None])
        if tokens[2].type != "AS":
            return None
        alias, i = _qname(tokens, 3)
        if alias is None or i != n:
            return None
        return _B.import_stmt([tokens[0], tokens[1], tokens[2], alias])
    if first == "OPERATOR":  # operator + (params) [-> T]
        if n < 2 or tokens[1].type not in _OPS:
            return None
        params, i = _params(tokens, 2)
        arrow, ref = _returns(tokens, i)
        return _B.operator_decl([tokens[0], _B.op([tokens[1]]), params, arrow, ref])
    static = None
    i = 0
    if first == "STATIC":
        static = tokens[0]
        i = 1
    if i >= n or tokens[i].type != "FN":
        return None
    fn = tokens[i]
    if i + 1 >= n or tokens[i + 1].type not in _NAMEISH:
        return None
    name = _ident(tokens[i + 1])
    params, j = _params(tokens, i + 2)
    arrow, ref = _returns(tokens, j)
    return _B.method([static, fn, name, params, arrow, ref])


def _parse_line(parser: Lark | None, line: LogicalLine, text: str, diags: list[Diagnostic]) -> ast.Stmt:
    if line.error is not None:
        diags.append(line.error)
        return _error_stmt(line, text)
    if FAST_PATH:
        stmt = _fast(line.tokens)
        if stmt is not None:
            if not too_deep(stmt, len(line.tokens)):
                return stmt
            diags.append(_too_deep(line))
            return _error_stmt(line, text)
    try:  # the LALR parser is built on the first line the fast path leaves to it (not at all for most files)
        stmt = (parser if parser is not None else _get_parser()).parse(line.tokens)
        if not too_deep(stmt, len(line.tokens)):
            return stmt
        diags.append(_too_deep(line))
    except _unexpected_input() as exc:  # (evaluated only when the parse raised: lark is loaded then)
        diags.append(_syntax_error(exc, line))
    except RecursionError:
        diags.append(_too_deep(line))
    return _error_stmt(line, text)


def _too_deep(line: LogicalLine) -> Diagnostic:
    return nesting_too_deep(f"expression nested more than {MAX_EXPR_DEPTH} levels deep (operators, signs and "
                            "brackets): split it into named parts", _line_span(line))


def _unexpected_input():
    from lark.exceptions import UnexpectedInput

    return UnexpectedInput


def _line_span(line: LogicalLine) -> TextSpan:
    return _TS(line.tokens[0].start_pos, line.tokens[-1].end_pos, _L)


def _error_stmt(line: LogicalLine, text: str) -> ast.ErrorStmt:
    span = _line_span(line)
    return ast.ErrorStmt(span, span, text[line.start : line.end])


def _opens_block(stmt: ast.Stmt, line: LogicalLine) -> bool:
    return line.opens_block and isinstance(stmt, ast.BLOCK_OWNERS)


_TOP_ONLY = (ast.TraitDef, ast.OperatorDecl, ast.Import)


def _check_placement(stmt: ast.Stmt, top: bool, diags: list[Diagnostic]) -> ast.Stmt:
    """Rules about where a statement may stand (spec F.7, F.8); returns the statement to keep."""

    def err(code: str, msg: str, span: Span, help_: str | None = None) -> None:
        diags.append(Diagnostic(code, msg, span, Severity.ERROR, help=help_))

    if top:
        if isinstance(stmt, ast.Assignment):
            if stmt.value is None and len(stmt.path.parts) == 1:
                # `Name:` + block at top level is a model without a base
                return ast.Declaration(stmt.span, stmt.header, stmt.path, None, None, colon=True)
            err("S012", f"assignment '{stmt.path.text}: ...' is not allowed at top level",
                stmt.header, "top level holds models, traits, global attributes, operators and imports")
        elif isinstance(stmt, ast.Declaration):
            if stmt.keyword == "becomes":
                err("S012", "'becomes' is not allowed at top level", stmt.header,
                    "use 'becomes' inside a model to specialise an inherited attribute")
            elif len(stmt.path.parts) > 1:
                err("S012", f"a top-level name cannot be dotted: '{stmt.path.text}'", stmt.path.span)
            elif stmt.optional:
                err("S012", "'optional' is not allowed at top level", stmt.header)
        elif isinstance(stmt, (ast.WithStmt, ast.Method, ast.Annotation)):
            what = {ast.WithStmt: "'with'", ast.Method: "a method", ast.Annotation: "an annotation"}
            err("S012", f"{what[type(stmt)]} must be inside a model or trait", stmt.header)
    else:
        if isinstance(stmt, _TOP_ONLY):
            what = {ast.TraitDef: "a trait", ast.OperatorDecl: "an operator", ast.Import: "an import"}
            err("S012", f"{what[type(stmt)]} can only be declared at top level", stmt.header)
        elif isinstance(stmt, ast.Declaration):
            if stmt.const:
                err("S012", "'const' is only allowed on top-level models", stmt.header)
            if stmt.keyword is None:
                err("S013", f"'{stmt.path.text}' needs 'is', 'becomes' or ':' after it",
                    stmt.header, f"declare it with '{stmt.path.text} is Type' or give a value "
                    f"with '{stmt.path.text}: value'")
    if isinstance(stmt, ast.Annotation) and not _is_literal(stmt.value):
        err("S014", f"the value of annotation '.{stmt.name.name}' must be a literal "
            "(string, number, true or false)", stmt.value.span)
    return stmt


def _is_literal(e) -> bool:
    if isinstance(e, ast.Unary) and e.op == "-":
        return isinstance(e.operand, ast.Number)
    return isinstance(e, (ast.String, ast.Number, ast.Bool))


def _close_spans(stmts: list[ast.Stmt]) -> None:
    """Grow each block owner's span over its body, bottom-up and without recursion."""
    order: list[ast.Stmt] = []
    stack = list(stmts)
    while stack:
        s = stack.pop()
        body = ast.body_of(s)
        if body:
            order.append(s)
            stack.extend(body)
    for s in reversed(order):
        last = s.body[-1]  # type: ignore[attr-defined]
        s.span = _TS(s.header.s, last.span.e, _L)


def parse_lines(text: str, lines: Iterable[LogicalLine], diags: list[Diagnostic]) -> list[ast.Stmt]:
    parser = _PARSER  # None until a line needs it: see _parse_line
    root = _Frame(-1, None, [], None)
    stack = [root]
    pending: tuple[ast.Stmt, int, LogicalLine] | None = None
    # the last statement, when its line did not open a block: a deeper line after it means a ':'
    # is missing there (the cause, reported on that line), not a line indented too far
    prev: tuple[ast.Stmt, int, _Frame, LogicalLine] | None = None

    def missing_block(stmt: ast.Stmt, line: LogicalLine) -> None:
        colon = line.tokens[-1]
        diags.append(
            Diagnostic(
                "S010",
                "expected an indented block after ':'",
                _sp(colon),
                Severity.ERROR,
                help="indent the lines that belong to this block, or give a value after ':'",
            )
        )
        stmt.body = []  # type: ignore[attr-defined]

    def land(col: int, wide: bool) -> int:
        """Index of the frame a line at `col` would join (len(stack): the pending block)."""
        if pending is not None and col > (pending_h8 if wide else pending[1]):
            return len(stack)
        k = len(stack) - 1
        while k > 0 and col < (stack[k].child8 if wide else stack[k].child_indent):  # type: ignore[operator]
            k -= 1
        return k

    # With tabs in the file, the block structure is also followed with 8-wide tabs: a line whose
    # block depends on the width is ambiguous (an error, the cause of what would follow)
    tabs = "\t" in text
    i8 = pending_h8 = 0
    for line in lines:
        stmt = _parse_line(parser, line, text, diags)
        i = line.indent
        if tabs:
            lead = text[line_start(text, line.start) : line.start]
            i8 = _width(lead, 8)
            k4, k8 = land(i, False), land(i8, True)
            if k4 != k8:
                _tab_is_ambiguous(diags, line, i, i8)
                if k8 > k4:  # keep the line in the block that is open, as 8-wide tabs show it
                    i = stack[k8].child_indent if k8 < len(stack) else pending[1] + 4  # type: ignore[index]
        if pending is not None:
            owner, h, pline = pending
            pending = None
            if i > h:
                owner.body = []  # type: ignore[attr-defined]
                stack.append(_Frame(h, i, owner.body, owner, i8))  # type: ignore[attr-defined]
            else:
                missing_block(owner, pline)
        elif prev is not None and i > prev[1] and prev[2] is stack[-1]:
            owner = _missing_colon(prev[0], prev[3], text, prev[2] is root, diags)
            if owner is not None:  # read the indented lines as the block the header meant to open
                prev[2].body[-1] = owner
                owner.body = []  # type: ignore[attr-defined]
                stack.append(_Frame(prev[1], i, owner.body, owner, i8))  # type: ignore[attr-defined]
        prev = None
        popped = None
        while len(stack) > 1 and i < stack[-1].child_indent:  # type: ignore[operator]
            popped = stack.pop()
        frame = stack[-1]
        if (popped is not None and frame.child_indent is not None and i > frame.child_indent
                and i != popped.header_indent):  # (at the column of the block's owner: a sibling)
            # between two levels: the file cannot mean what the layout suggests. Report the
            # cause and keep the line in the block it was closer to closing (so the lines
            # after it that are correctly indented stay there too, and nothing cascades)
            lead = text[line_start(text, line.start) : line.start]
            _between_levels(diags, line, lead, frame.child_indent, popped.child_indent)
            stack.append(popped)
            frame = popped
        if frame.child_indent is None:
            frame.child_indent, frame.child8 = i, i8
        stmt = _check_placement(stmt, frame is root, diags)
        frame.body.append(stmt)
        if _opens_block(stmt, line):
            pending, pending_h8 = (stmt, i, line), i8
        elif not line.opens_block:
            prev = (stmt, i, frame, line)
    if pending is not None:
        missing_block(pending[0], pending[2])
    _close_spans(root.body)
    return root.body


def _missing_colon(stmt: ast.Stmt, line: LogicalLine, text: str, top: bool,
                   diags: list[Diagnostic]) -> ast.Stmt | None:
    """A header without ':' followed by a more-indented block: report the missing ':' on the header
    (with the fix) and return the statement that owns the block, so the lines under it keep their
    meaning and nothing cascades from them (S012 at top level, unknown members, unused models).
    None when the line cannot own a block (it has a value, it is an import...): the layout rules
    report the deeper line then."""
    owner: ast.Stmt
    if isinstance(stmt, ast.Declaration) and stmt.value is None:
        owner = stmt
        if stmt.keyword is None:  # a lone name: `size` + block means `size:` + block
            for k in range(len(diags) - 1, -1, -1):  # its S013 is what this error explains
                if diags[k].code == "S013" and diags[k].span.start.offset == stmt.header.start.offset:
                    del diags[k]
                    break
            if top:
                stmt.colon = True  # `Name:` + block at top level: a model without a base
            else:
                owner = ast.Assignment(stmt.span, stmt.header, stmt.path, None)
    elif isinstance(stmt, ast.TraitDef) or (isinstance(stmt, ast.Assignment) and stmt.value is None):
        owner = stmt
    else:
        return None
    last = line.tokens[-1]
    written = text[line.start : line.end]
    diags.append(Diagnostic(
        "S016",
        "missing ':' at the end of this line: the indented lines below it are its block",
        _sp(last),
        Severity.ERROR,
        help=f"write '{written}:' (a line that opens a block ends with ':')",
        fix=Fix("add ':' at the end of the line", (Edit(last.end_pos, last.end_pos, ":"),)),
    ))
    return owner


def _width(lead: str, tab: int) -> int:
    col = 0
    for ch in lead:
        col = (col // tab + 1) * tab if ch == "\t" else col + 1
    return col


def _between_levels(diags: list[Diagnostic], line: LogicalLine, lead: str, outer: int, inner: int) -> None:
    how = f"{line.indent} columns" if "\t" not in lead else f"{line.indent} columns (a tab counted as 4)"
    diags.append(Diagnostic(
        INDENTATION_BETWEEN_LEVELS,
        f"this line is indented {how}: between the block at column {outer} and the one at column {inner}",
        _sp(line.tokens[0]),
        Severity.ERROR,
        help=f"indent it {inner} spaces to keep it in the block above, or {outer} to end that block "
             "(it is read as part of the block above)",
    ))


def _tab_is_ambiguous(diags: list[Diagnostic], line: LogicalLine, narrow: int, wide: int) -> None:
    diags.append(ambiguous_tab(_sp(line.tokens[0]), narrow, wide))


def parse_text(text: str, path: str = "") -> ast.File:
    """Parse text from an editor buffer or stdin."""
    decoded = decode_text(text)
    return _parse_decoded(decoded.text, path, decoded.diagnostics, decoded.had_bom, decoded.newline)


def parse_bytes(data: bytes, path: str = "") -> ast.File:
    decoded = decode(data)
    return _parse_decoded(decoded.text, path, decoded.diagnostics, decoded.had_bom, decoded.newline)


def parse_file(path: str | Path) -> ast.File:
    from plxtools.cache import reads

    return parse_bytes(reads.read_bytes(path), str(path))


def _parse_decoded(text: str, path: str, diags: list[Diagnostic], had_bom: bool, newline: str) -> ast.File:
    import gc

    # the tree is acyclic: collection passes while it grows only rescan it (superlinear on big files)
    enabled = gc.isenabled()
    gc.disable()
    try:
        return _parse_decoded_inner(text, path, diags, had_bom, newline)
    finally:
        if enabled:
            gc.enable()


def _parse_decoded_inner(text: str, path: str, diags: list[Diagnostic], had_bom: bool, newline: str) -> ast.File:
    global _L
    index = LineIndex(text)
    with _parsing:
        outer, _L = _L, index
        try:
            # the lines are parsed as the lexer finishes them: only one line's tokens live at a time
            lexer = Lexer(text)
            parsed: list[Diagnostic] = []
            statements = parse_lines(text, lexer.iter_lines(), parsed)
        finally:
            _L = outer
    diags = [*diags, *lexer.diagnostics, *parsed]  # (the order the stable sort below keeps for ties)
    comments = [ast.Comment(_TS(s, e, index), body, own) for (s, _ln, _col, e, body, own) in lexer.comments]
    ambiguous_tabs = {d.span.start.line for d in diags if d.code == TAB_INDENTATION and d.severity is Severity.ERROR}
    if ambiguous_tabs:  # the error replaces the lexer's warning on the same line
        diags = [d for d in diags if not (d.code == TAB_INDENTATION and d.severity is Severity.WARNING
                                          and d.span.start.line in ambiguous_tabs)]
    for d in diags:
        d.file = path
    diags.sort(key=lambda d: d.span.start.offset)
    return ast.File(path, text, statements, comments, diags, index, had_bom, newline)
