"""Parse OpenPLX text into a syntax tree plus located syntax errors. Never raises on input."""

from __future__ import annotations

import threading
from pathlib import Path

from lark import Lark, Token, Transformer
from lark.exceptions import UnexpectedEOF, UnexpectedInput, UnexpectedToken
from lark.lexer import Lexer as LarkLexer

from plxtools.diagnostics import Diagnostic, Pos, Severity, Span
from plxtools.syntax import ast
from plxtools.syntax.lexer import LogicalLine, lex
from plxtools.syntax.source import LineIndex, decode, decode_text

# ------------------------------------------------------------------ building nodes


def _sp(x) -> Span:
    if isinstance(x, Token):
        return Span(Pos(x.start_pos, x.line, x.column), Pos(x.end_pos, x.end_line, x.end_column))
    return x.span


def _cover(children) -> Span:
    items = [c for c in children if c is not None]
    return Span(_sp(items[0]).start, _sp(items[-1]).end)


class _Seq(list):
    """A list of nodes that remembers the span of the brackets around it."""

    __slots__ = ("span",)


def _is_tok(x, kind: str) -> bool:
    return isinstance(x, Token) and x.type == kind


_STRING_KINDS = {"@": "path", "$": "interp"}


class _Build(Transformer):
    """Turns each grammar rule straight into an AST node (no intermediate lark tree)."""

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
        text = str(t)
        is_int = not any(ch in text for ch in ".eE")
        value = int(text) if is_int else float(text)
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


class _PassThrough(LarkLexer):
    """The logical line is already tokenised; hand its tokens to the LALR parser as they are."""

    def __init__(self, lexer_conf):  # noqa: D401 - lark's lexer protocol
        pass

    def lex(self, data, parser_state=None):
        return iter(data)


def _lark_cache_file() -> str | bool:
    import os

    base = os.environ.get("PLX_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache")
    folder = os.path.join(base, "plxtools")
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError:
        return False
    return os.path.join(folder, "grammar.lark-cache")


_parser_lock = threading.Lock()
_PARSER: Lark | None = None


def _get_parser() -> Lark:
    global _PARSER
    if _PARSER is None:
        with _parser_lock:
            if _PARSER is None:
                grammar = Path(__file__).with_name("openplx.lark").read_text(encoding="utf-8")
                options = dict(parser="lalr", lexer=_PassThrough, transformer=_Build(), maybe_placeholders=True)
                try:  # lark caches its grammar analysis, keyed by the grammar and options
                    _PARSER = Lark(grammar, cache=_lark_cache_file(), **options)
                except Exception:  # an unwritable or stale cache must never stop parsing
                    _PARSER = Lark(grammar, **options)
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


def _syntax_error(exc: UnexpectedInput, line: LogicalLine) -> Diagnostic:
    tok = getattr(exc, "token", None)
    expected = getattr(exc, "expected", None) or set()
    if isinstance(exc, UnexpectedEOF) or tok is None or tok.type == "$END":
        last = line.tokens[-1]
        at = Pos(last.end_pos, last.end_line, last.end_column)
        span = _sp(last)
        found = "end of line"
        msg = f"unexpected end of line after '{last}'"
    else:
        span = _sp(tok)
        found = "a string" if tok.type == "STRING" else f"'{tok}'"
        msg = f"unexpected {found}"
        at = span.start
    expected = set(expected)
    if tok is not None and tok.type != "$END":
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
    exp = _expected_text(expected)
    if exp:
        msg += f"; expected {exp}"
    help_ = None
    first = line.tokens[0]
    if first.type in ("NAME", "TICKNAME") and isinstance(exc, UnexpectedToken) and tok is not None:
        if tok.type == "NAME" and len(line.tokens) > 1 and line.tokens[1] is tok:
            help_ = "declare with 'name is Type', or give a value with 'name: value'"
    del at
    return Diagnostic("S011", msg, span, Severity.ERROR, help=help_)


# ------------------------------------------------------------------ the driver


class _Frame:
    __slots__ = ("header_indent", "child_indent", "body", "owner")

    def __init__(self, header_indent: int, child_indent: int | None, body: list, owner):
        self.header_indent = header_indent
        self.child_indent = child_indent
        self.body = body
        self.owner = owner


def _parse_line(parser: Lark, line: LogicalLine, text: str, diags: list[Diagnostic]) -> ast.Stmt:
    if line.error is not None:
        diags.append(line.error)
        return _error_stmt(line, text)
    try:
        return parser.parse(line.tokens)
    except UnexpectedInput as exc:
        diags.append(_syntax_error(exc, line))
    except RecursionError:
        diags.append(
            Diagnostic("S007", "expression nested too deeply", _line_span(line), Severity.ERROR)
        )
    return _error_stmt(line, text)


def _line_span(line: LogicalLine) -> Span:
    return Span(_sp(line.tokens[0]).start, _sp(line.tokens[-1]).end)


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
        s.span = Span(s.header.start, last.span.end)


def parse_lines(text: str, lines: list[LogicalLine], diags: list[Diagnostic]) -> list[ast.Stmt]:
    parser = _get_parser()
    root = _Frame(-1, None, [], None)
    stack = [root]
    pending: tuple[ast.Stmt, int, LogicalLine] | None = None

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

    for line in lines:
        stmt = _parse_line(parser, line, text, diags)
        i = line.indent
        if pending is not None:
            owner, h, pline = pending
            pending = None
            if i > h:
                owner.body = []  # type: ignore[attr-defined]
                stack.append(_Frame(h, i, owner.body, owner))  # type: ignore[attr-defined]
            else:
                missing_block(owner, pline)
        while len(stack) > 1 and i < stack[-1].child_indent:  # type: ignore[operator]
            stack.pop()
        frame = stack[-1]
        if frame.child_indent is None:
            frame.child_indent = i
        stmt = _check_placement(stmt, frame is root, diags)
        frame.body.append(stmt)
        if _opens_block(stmt, line):
            pending = (stmt, i, line)
    if pending is not None:
        missing_block(pending[0], pending[2])
    _close_spans(root.body)
    return root.body


def parse_text(text: str, path: str = "") -> ast.File:
    """Parse text from an editor buffer or stdin."""
    decoded = decode_text(text)
    return _parse_decoded(decoded.text, path, decoded.diagnostics, decoded.had_bom, decoded.newline)


def parse_bytes(data: bytes, path: str = "") -> ast.File:
    decoded = decode(data)
    return _parse_decoded(decoded.text, path, decoded.diagnostics, decoded.had_bom, decoded.newline)


def parse_file(path: str | Path) -> ast.File:
    p = Path(path)
    return parse_bytes(p.read_bytes(), str(path))


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
    diags = list(diags)
    lexed = lex(text)
    diags.extend(lexed.diagnostics)
    statements = parse_lines(text, lexed.lines, diags)
    comments = [
        ast.Comment(Span(Pos(s, ln, col), Pos(e, ln, col + (e - s))), body, own)
        for (s, ln, col, e, body, own) in lexed.comments
    ]
    for d in diags:
        d.file = path
    diags.sort(key=lambda d: d.span.start.offset)
    return ast.File(path, text, statements, comments, diags, LineIndex(text), had_bom, newline)
