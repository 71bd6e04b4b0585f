"""Semantic tokens: names coloured by what they resolve to, plus keywords, literals and comments."""

from __future__ import annotations

from plxtools.ide.context import qname_parts
from plxtools.ide.host import FileState
from plxtools.ide.types import SemanticToken
from plxtools.model.symbols import PRIMITIVES, GlobalSym, MemberSym, MethodSym, ModelSym, Namespace
from plxtools.syntax import ast
from plxtools.syntax.lexer import KEYWORDS, lex

TOKEN_TYPES = ["namespace", "type", "class", "interface", "property", "method", "variable", "parameter",
               "keyword", "number", "string", "comment", "operator", "decorator", "enumMember"]
TOKEN_MODIFIERS = ["declaration", "definition", "readonly", "static", "defaultLibrary", "deprecated"]

_KEYWORD_TYPES = set(KEYWORDS.values()) - {"TRUE", "FALSE", "THIS"}
_LITERAL_KEYWORDS = {"TRUE", "FALSE", "THIS"}


def _official(sym) -> bool:
    unit = getattr(sym, "unit", None)
    if unit is None and isinstance(sym, (MemberSym, MethodSym)):
        unit = sym.owner.unit
    return bool(unit is not None and unit.official)


def _classify(sym) -> tuple[str, tuple[str, ...]] | None:
    mods: list[str] = []
    if _official(sym):
        mods.append("defaultLibrary")
    if isinstance(sym, ModelSym):
        if sym.is_trait:
            return "interface", tuple(mods)
        if sym.const:
            mods.append("readonly")
        return "class", tuple(mods)
    if isinstance(sym, MemberSym):
        if sym.owner.deprecated.get(sym.name):
            mods.append("deprecated")
        return "property", tuple(mods)
    if isinstance(sym, MethodSym):
        if sym.static:
            mods.append("static")
        return "method", tuple(mods)
    if isinstance(sym, GlobalSym):
        mods.append("readonly")
        return "variable", tuple(mods)
    if isinstance(sym, Namespace):
        return "namespace", tuple(mods)
    return None


class _Tokens:
    """Semantic tokens being collected: a span that crosses lines becomes one token per line (for
    clients without multiline tokens)."""

    def __init__(self, idx) -> None:
        self.idx = idx
        self.out: list[SemanticToken] = []

    def add(self, start: int, end: int, typ: str, mods: tuple[str, ...] = ()) -> None:
        if end <= start:
            return
        idx = self.idx
        a = idx.pos(start)
        b = idx.pos(end)
        if a.line == b.line:
            self.out.append(SemanticToken(a.line, a.column, b.column - a.column, typ, mods))
            return
        for line in range(a.line, b.line + 1):
            lt = idx.line_text(line)
            c0 = a.column if line == a.line else 0
            c1 = b.column if line == b.line else len(lt)
            if c1 > c0:
                self.out.append(SemanticToken(line, c0, c1 - c0, typ, mods))


def semantic_tokens(st: FileState) -> list[SemanticToken]:
    """Names as the checker resolved them, then what only the syntax tree knows (primitive types,
    parameters, annotations), then keywords, literals and comments from the lexer; where two
    overlap the longest at a column wins."""
    tokens = _Tokens(st.tree.index)
    _name_tokens(tokens, st)
    _syntax_tokens(tokens, st.tree)
    _lexer_tokens(tokens, st.text)
    return _without_overlaps(tokens.out)


def _name_tokens(tokens: _Tokens, st: FileState) -> None:
    text = st.text
    for o in st.occurrences:
        cls = _classify(o.target)
        if cls is None:
            continue
        typ, mods = cls
        if o.kind == "definition":
            mods = mods + ("declaration", "definition")
        parts = qname_parts(text, o.span) if "." in text[o.span.start.offset:o.span.end.offset] else None
        if parts and len(parts) > 1:
            for _name, a, b in parts[:-1]:
                tokens.add(a, b, "namespace", ())
            _name, a, b = parts[-1]
            tokens.add(a, b, typ, mods)
        else:
            tokens.add(o.span.start.offset, o.span.end.offset, typ, mods)


def _syntax_tokens(tokens: _Tokens, tree: ast.File) -> None:
    for s in ast.walk_statements(tree.statements):
        for ref in _type_refs(s):
            if len(ref.name.parts) == 1 and ref.name.parts[0].name in PRIMITIVES:
                sp = ref.name.span
                tokens.add(sp.start.offset, sp.end.offset, "type", ("defaultLibrary",))
        if isinstance(s, (ast.Method, ast.OperatorDecl)):
            for prm in s.params:
                tokens.add(prm.name.span.start.offset, prm.name.span.end.offset, "parameter", ("declaration",))
        if isinstance(s, ast.Annotation):
            tokens.add(s.name.span.start.offset - 1, s.name.span.end.offset, "decorator", ())


def _lexer_tokens(tokens: _Tokens, text: str) -> None:
    lexed = lex(text)
    for ln in lexed.lines:
        for tok in ln.tokens:
            if tok.type in _KEYWORD_TYPES or tok.type in _LITERAL_KEYWORDS:
                tokens.add(tok.start_pos, tok.end_pos, "keyword", ())
            elif tok.type == "NUMBER":
                tokens.add(tok.start_pos, tok.end_pos, "number", ())
            elif tok.type == "STRING":
                tokens.add(tok.start_pos, tok.end_pos, "string", ())
    for (start, _line, _col, end, _body, _own) in lexed.comments:
        tokens.add(start, end, "comment", ())


def _without_overlaps(out: list[SemanticToken]) -> list[SemanticToken]:
    out.sort(key=lambda t: (t.line, t.column, -t.length))
    clean: list[SemanticToken] = []
    for t in out:
        if clean and clean[-1].line == t.line and t.column < clean[-1].column + clean[-1].length:
            continue  # no overlaps: the first (longest at that column) wins
        clean.append(t)
    return clean


def _type_refs(s: ast.Stmt):
    t = getattr(s, "type", None)
    if isinstance(t, ast.TypeExpr):
        yield from t.alternatives
    if isinstance(s, (ast.Method, ast.OperatorDecl)):
        for prm in s.params:
            yield prm.type
        if s.returns is not None:
            yield s.returns


def encode(tokens: list[SemanticToken], columns) -> list[int]:
    """LSP's relative integer encoding; `columns(line, col, length)` converts to the client's units."""
    data: list[int] = []
    prev_line = 0
    prev_col = 0
    type_index = {t: i for i, t in enumerate(TOKEN_TYPES)}
    mod_bits = {m: 1 << i for i, m in enumerate(TOKEN_MODIFIERS)}
    for t in tokens:
        col, length = columns(t.line, t.column, t.length)
        d_line = t.line - prev_line
        d_col = col - prev_col if d_line == 0 else col
        bits = 0
        for m in t.modifiers:
            bits |= mod_bits.get(m, 0)
        data.extend((d_line, d_col, length, type_index[t.type], bits))
        prev_line = t.line
        prev_col = col
    return data
