"""Tokens and logical lines.

OpenPLX statements end at a newline unless a bracket is open, and blocks are given by indentation.
This pass turns the text into logical lines (indentation + tokens) and comments; the grammar then
parses one logical line at a time, so a broken line costs one diagnostic and nothing else.
"""

from __future__ import annotations

import re
from sys import intern
from dataclasses import dataclass, field
from typing import Iterator

from plxtools.diagnostics import Diagnostic, Pos, Severity, Span


class Token(str):
    """A token: its text, kind (`type`) and place. The fields and behaviour of lark's `Token`
    (equality also compares the kind, the same constructor), so the LALR fallback parses these
    tokens as they are; being plxtools' own class, lexing (and a whole run whose lines the fast
    path builds) does not import lark (about 35 ms of every start-up)."""

    __slots__ = ("type", "start_pos", "value", "line", "column", "end_line", "end_column", "end_pos")
    __match_args__ = ("type", "value")

    def __new__(cls, type, value, start_pos=None, line=None, column=None, end_line=None, end_column=None,
                end_pos=None):
        inst = str.__new__(cls, value)
        inst.type = type
        inst.start_pos = start_pos
        inst.value = value
        inst.line = line
        inst.column = column
        inst.end_line = end_line
        inst.end_column = end_column
        inst.end_pos = end_pos
        return inst

    @classmethod
    def new_borrow_pos(cls, type_: str, value, borrow_t: "Token") -> "Token":
        return cls(type_, value, borrow_t.start_pos, borrow_t.line, borrow_t.column, borrow_t.end_line,
                   borrow_t.end_column, borrow_t.end_pos)

    def update(self, type: str | None = None, value=None) -> "Token":
        return Token.new_borrow_pos(type if type is not None else self.type,
                                    value if value is not None else self.value, self)

    def __reduce__(self):
        return (self.__class__, (self.type, self.value, self.start_pos, self.line, self.column))

    def __repr__(self) -> str:
        return "Token(%r, %r)" % (self.type, self.value)

    def __deepcopy__(self, memo):
        return Token(self.type, self.value, self.start_pos, self.line, self.column)

    def __eq__(self, other):
        if isinstance(other, Token) and self.type != other.type:
            return False
        return str.__eq__(self, other)

    __hash__ = str.__hash__

KEYWORDS = {
    "is": "IS",
    "becomes": "BECOMES",
    "with": "WITH",
    "trait": "TRAIT",
    "const": "CONST",
    "fn": "FN",
    "static": "STATIC",
    "operator": "OPERATOR",
    "optional": "OPTIONAL",
    "reference": "REFERENCE",
    "this": "THIS",
    "or": "OR",
    "import": "IMPORT",
    "as": "AS",
    "true": "TRUE",
    "false": "FALSE",
}

PUNCT = {
    ":": "COLON",
    ".": "DOT",
    ",": "COMMA",
    "(": "LPAR",
    ")": "RPAR",
    "[": "LSQB",
    "]": "RSQB",
    "{": "LBRACE",
    "}": "RBRACE",
    "+": "PLUS",
    "-": "MINUS",
    "*": "STAR",
    "/": "SLASH",
}
OPENERS = {"(": ")", "[": "]", "{": "}"}
CLOSERS = {")", "]", "}"}
MAX_BRACKET_DEPTH = 200

# the layout codes this module raises; the parser, incremental parsing, style and fmt recognise them by these names
TAB_INDENTATION = "S003"
UNBALANCED_BRACKET = "S004"
NESTING_TOO_DEEP = "S007"
UNTERMINATED_STRING = "S009"

_TOKEN_RE = re.compile(
    r"""
    (?P<ws>[ \t\f]+)
  | (?P<nl>\r\n?|\n)
  | (?P<comment>\#[^\r\n]*)
  | (?P<number>\d+(?:\.\d+)?(?:[eE][+-]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<str>\"\"\"|[@$]?\")
  | (?P<tick>`[^`\r\n]*`)
  | (?P<arrow>->)
  | (?P<punct>[:.,()\[\]{}+\-*/])
  | (?P<bad>.)
    """,
    re.VERBOSE | re.DOTALL,
)
# the same tokens after the blanks before them (group 1), commonest first; `eof`: blanks end the text
_SCAN_RE = re.compile(
    r"""
    ([ \t\f]*)
    (?:
      (?P<name>[A-Za-z_][A-Za-z0-9_]*)
    | (?P<arrow>->)
    | (?P<punct>[:.,()\[\]{}+\-*/])
    | (?P<number>\d+(?:\.\d+)?(?:[eE][+-]?\d+)?)
    | (?P<nl>\r\n?|\n)
    | (?P<comment>\#[^\r\n]*)
    | (?P<str>\"\"\"|[@$]?\")
    | (?P<tick>`[^`\r\n]*`)
    | (?P<bad>.)
    | (?P<eof>\Z)
    )
    """,
    re.VERBOSE | re.DOTALL,
)
# _SCAN_RE's groups by number (m.lastindex: the one token group that matched; group 1 is the blanks)
_NAME, _ARROW, _PUNCT, _NUMBER, _NL, _COMMENT, _STR, _TICK, _BAD, _EOF = (
    _SCAN_RE.groupindex[g] for g in ("name", "arrow", "punct", "number", "nl", "comment", "str", "tick", "bad", "eof"))
_SPACES_RE = re.compile(r" *")
_IDENT_CHAR = re.compile(r"[A-Za-z0-9_.]")
_BREAK_RE = re.compile(r"\r\n?|\n")  # the line breaks of OpenPLX (and of LSP): \r\n, \r, \n
MAX_INT_DIGITS = 4300  # Python's int-from-string limit (sys.get_int_max_str_digits)


@dataclass(slots=True)
class LogicalLine:
    indent: int
    tokens: list[Token]
    error: Diagnostic | None = None

    @property
    def start(self) -> int:
        return self.tokens[0].start_pos

    @property
    def end(self) -> int:
        return self.tokens[-1].end_pos

    @property
    def opens_block(self) -> bool:
        return self.tokens[-1].type == "COLON"


@dataclass(slots=True)
class LexResult:
    lines: list[LogicalLine]
    comments: list[tuple[int, int, int, int, str, bool]]  # start, line, col, end, text, own_line
    diagnostics: list[Diagnostic] = field(default_factory=list)


def _describe(ch: str) -> str:
    if ch == "\t":
        return "a tab"
    if ch.isprintable():
        return f"'{ch}'"
    return f"character U+{ord(ch):04X}"


class Lexer:
    def __init__(self, text: str):
        self.text = text
        self.pos = 0
        self.line = 0
        self.line_start = 0

    def _p(self, offset: int) -> Pos:
        return Pos(offset, self.line, offset - self.line_start)

    def _newline(self, end: int) -> None:
        self.line += 1
        self.line_start = end

    def run(self) -> LexResult:
        """Every logical line, the comments and the diagnostics of the whole text."""
        lines = list(self.iter_lines())
        return LexResult(lines, self.comments, self.diagnostics)

    def iter_lines(self) -> Iterator[LogicalLine]:
        """One pass over the text, yielding each logical line as soon as it is complete, so a parser
        that consumes them one by one never holds the tokens of the whole file (they take more memory
        than the tree built from them). `self.comments` and `self.diagnostics` are complete once
        the iteration ends. The common tokens (names, punctuation) are built inline, in locals;
        line starts, brackets, line breaks inside brackets and the rarer tokens are handled by the
        helpers below."""
        text = self.text
        n = len(text)
        lines: list[LogicalLine] = []  # finished lines not yet yielded (one at most, between yields)
        comments: list[tuple[int, int, int, int, str, bool]] = []
        diagnostics: list[Diagnostic] = []
        self.comments, self.diagnostics = comments, diagnostics

        tokens: list[Token] = []
        line_error: Diagnostic | None = None
        indent = 0
        at_line_start = True
        brackets: list[Token] = []
        scan = _SCAN_RE.match
        spaces = _SPACES_RE.match
        keyword = KEYWORDS.get
        punct_type = PUNCT.__getitem__
        new = str.__new__
        # the position lives in locals here (the helpers below read and update self.*)
        pos = line = line_start = 0

        def finish() -> None:
            nonlocal tokens, line_error, brackets
            if tokens:
                lines.append(LogicalLine(indent, tokens, line_error))
            elif line_error is not None:
                diagnostics.append(line_error)
            tokens = []
            line_error = None
            brackets = []

        def fail(diag: Diagnostic) -> None:
            nonlocal line_error
            if line_error is None:
                line_error = diag

        snapshot = None  # where to resume if an open bracket turns out never to close

        def bracket(tok: Token, ch: str) -> bool:
            """An opening or closing bracket: checked and tracked; whether one is still open."""
            if ch in OPENERS:
                brackets.append(tok)
                if len(brackets) > MAX_BRACKET_DEPTH:
                    fail(too_deep(f"brackets nested more than {MAX_BRACKET_DEPTH} levels deep", _tok_span(tok)))
            elif not brackets:
                fail(Diagnostic(UNBALANCED_BRACKET, f"unmatched '{ch}'", _tok_span(tok), Severity.ERROR))
            elif OPENERS[brackets[-1].value] != ch:
                opener = brackets.pop()
                fail(Diagnostic(UNBALANCED_BRACKET,
                                f"'{ch}' does not match '{opener.value}' opened at line {opener.line + 1}",
                                _tok_span(tok), Severity.ERROR))
            else:
                brackets.pop()
            return bool(brackets)

        def line_break(pos: int, line: int, line_start: int) -> bool:
            """At a line break inside brackets (its end at `pos`): does the statement end here? Only
            when the next line cannot continue it (a never-closed bracket)."""
            nonlocal snapshot
            self.pos, self.line, self.line_start = pos, line, line_start
            kind = self._next_line_kind(indent)
            if kind == _STRONG or (kind == _PARAM_LIKE and not _in_params(tokens, brackets)):
                fail(_never_closed(brackets[-1]))
                finish()
                snapshot = None
                return True
            if kind == _PARAM_LIKE and snapshot is None:
                # `b: Real` continues a parameter list, unless the list is never closed:
                # remember where to resume if the end of the file proves it was not
                snapshot = (pos, line, line_start, len(tokens), len(comments),
                            len(diagnostics), list(brackets), line_error)
            return False

        def rare(kind: int, start: int, end: int, line: int, line_start: int) -> tuple[int, int, int]:
            """The less common tokens (comments, strings, backtick names, arrows, bad characters,
            blanks at the end): the position after them."""
            text = self.text  # (not the enclosing `text`: a closure reading it would slow the loop's reads)
            if kind == _COMMENT:
                own = not (tokens and tokens[-1].end_line == line)
                comments.append((start, line, start - line_start, end, text[start:end], own))
            elif kind == _STR:
                self.pos, self.line, self.line_start = start, line, line_start
                tokens.append(self._string(text[start:end], start, fail, diagnostics))
                return self.pos, self.line, self.line_start
            elif kind == _TICK:
                tokens.append(_tick(text[start:end], start, end, line, line_start, fail))
            elif kind == _ARROW:
                tokens.append(Token("ARROW", "->", start, line, start - line_start, line, end - line_start, end))
            elif kind != _EOF:  # (_EOF: blanks at the end of the text)
                ch = text[start:end]
                fail(Diagnostic("S008", f"unexpected {_describe(ch)}",
                                Span(Pos(start, line, start - line_start), Pos(end, line, end - line_start)),
                                Severity.ERROR, help=_bad_char_help(ch)))
            return end, line, line_start

        while True:
            while pos < n:
                if at_line_start:
                    i = spaces(text, pos).end()
                    if i < n and text[i] not in _NOT_CODE:  # code indented with spaces (most lines)
                        indent = i - pos
                        pos = i
                        at_line_start = False
                        continue
                    pos, line, line_start, col = _line_start(text, pos, line, line_start, comments, diagnostics)
                    if col >= 0:
                        indent = col
                        at_line_start = False
                    continue

                m = scan(text, pos)
                kind = m.lastindex  # the token's group (numbers: _NAME ...)
                start, end = m.span(kind)
                if kind == _NAME:
                    # a Token built without its constructor's argument handling (the hot path)
                    word = intern(text[start:end])  # names repeat: the tree and the symbols share one copy
                    tok = new(Token, word)
                    tok.type = keyword(word, "NAME")
                    tok.value = word
                    tok.start_pos = start
                    tok.end_pos = end
                    tok.line = tok.end_line = line
                    tok.column = start - line_start
                    tok.end_column = end - line_start
                    tokens.append(tok)
                    pos = end
                    continue
                if kind == _PUNCT:
                    ch = text[start]
                    tok = new(Token, ch)
                    tok.type = punct_type(ch)
                    tok.value = ch
                    tok.start_pos = start
                    tok.end_pos = end
                    tok.line = tok.end_line = line
                    tok.column = start - line_start
                    tok.end_column = end - line_start
                    tokens.append(tok)
                    pos = end
                    if ch in _BRACKETS and not bracket(tok, ch):
                        snapshot = None
                    continue
                if kind == _NL:
                    pos = line_start = end
                    line += 1
                    if brackets:
                        at_line_start = line_break(pos, line, line_start)
                    else:
                        finish()
                        at_line_start = True
                    if lines:
                        yield from lines
                        lines.clear()
                    continue
                if kind == _NUMBER:
                    word = text[start:end]
                    tok = new(Token, word)
                    tok.type = "NUMBER"
                    tok.value = word
                    tok.start_pos = start
                    tok.end_pos = end
                    tok.line = tok.end_line = line
                    tok.column = start - line_start
                    tok.end_column = end - line_start
                    if (end < n and _IDENT_CHAR.match(text, end)) or end - start > MAX_INT_DIGITS:
                        bad = _bad_number(text, start, end, line, line_start)
                        if bad is not None:
                            fail(bad)
                    tokens.append(tok)
                    pos = end
                    continue
                pos, line, line_start = rare(kind, start, end, line, line_start)

            if brackets and snapshot is not None:
                # never closed: resume at the first line that could have been a statement
                (pos, line, line_start, ntok, ncom, ndiag, brackets, line_error) = snapshot
                snapshot = None
                del tokens[ntok:], comments[ncom:], diagnostics[ndiag:]
                fail(_never_closed(brackets[-1]))
                finish()
                at_line_start = True
                continue
            break
        if brackets:
            fail(_never_closed(brackets[-1]))
        finish()
        self.pos, self.line, self.line_start = pos, line, line_start
        yield from lines
        lines.clear()

    def _next_line_kind(self, indent: int) -> int:
        """Inside brackets at a line break: can the next code line still continue the statement?

        Only the tokens decide: a line at or left of the statement's indentation that begins the
        way a statement does and no expression can (`x is`, `x becomes`, `.a:`, a keyword such as
        `const` or `fn`) is `_STRONG`; `x:` is `_PARAM_LIKE` (a parameter of a continued `fn`
        list); anything else continues.
        """
        i, col = _next_code_line(self.text, self.pos)
        if i < 0 or col > indent:
            return _CONTINUES
        return _statement_start(self.text, i)

    def _string(self, opener: str, start: int, fail, diagnostics) -> Token:
        text = self.text
        p0 = self._p(start)
        if opener == '"""':
            close = text.find('"""', start + 3)
            if close < 0:
                end = len(text)
                fail(
                    Diagnostic(
                        UNTERMINATED_STRING,
                        'unterminated """ string: it runs to the end of the file',
                        Span(p0, Pos(start + 3, p0.line, p0.column + 3)),
                        Severity.ERROR,
                        help='close the string with """',
                    )
                )
            else:
                end = close + 3
            body = text[start:end]
            if "\r" in body:
                breaks = [m.end() for m in _BREAK_RE.finditer(body)]
                if breaks:
                    self.line += len(breaks)
                    self.line_start = start + breaks[-1]
            else:
                nl = body.count("\n")
                if nl:
                    self.line += nl
                    self.line_start = start + body.rfind("\n") + 1
            self.pos = end
            p1 = self._p(end)
            return Token("STRING", body, start, p0.line, p0.column, p1.line, p1.column, end)
        # one-line string, maybe prefixed with @ or $
        i = start + len(opener)
        n = len(text)
        while i < n and text[i] not in '"\r\n':
            i += 1
        if i < n and text[i] == '"':
            end = i + 1
        else:
            end = i
            fail(
                Diagnostic(
                    UNTERMINATED_STRING,
                    "unterminated string: a \"...\" string must close on the same line",
                    Span(p0, self._p(end)),
                    Severity.ERROR,
                    help='add the closing " (use """...""" for text over several lines)',
                )
            )
        self.pos = end
        p1 = self._p(end)
        return Token("STRING", text[start:end], start, p0.line, p0.column, p1.line, p1.column, end)


_CONTINUES, _PARAM_LIKE, _STRONG = 0, 1, 2
_STATEMENT_KEYWORDS = {"const", "optional", "static", "trait", "fn", "operator", "with", "import", "becomes"}
_BRACKETS = frozenset("()[]{}")
_NOT_CODE = frozenset(" \t\f\r\n#")  # what can follow leading spaces on a line without code or with tabs


def _line_start(text: str, pos: int, line: int, line_start: int, comments: list, diagnostics: list):
    """At the start of a line: (the position after its indentation, line, line start, indentation
    width); for a blank or comment-only line, the position after it and width -1."""
    n = len(text)
    i = _SPACES_RE.match(text, pos).end()  # (spaces only: one regex match)
    col = i - pos
    tab_at = -1
    if i < n and text[i] in "\t\f":
        i, col, tab_at = _tabbed_indentation(text, pos)
    if i >= n or text[i] in "\r\n#":
        pos = i
        if i < n and text[i] == "#":
            m = _TOKEN_RE.match(text, i)
            end = m.end()
            comments.append((i, line, i - line_start, end, m.group(), True))
            pos = end
        if pos < n:
            pos = line_start = _TOKEN_RE.match(text, pos).end()
            line += 1
        return pos, line, line_start, -1
    if tab_at >= 0:
        diagnostics.append(_tab_in_indentation(tab_at, line, tab_at - line_start))
    return i, line, line_start, col


def _tabbed_indentation(text: str, pos: int) -> tuple[int, int, int]:
    """Indentation with tabs (4 columns wide) or form feeds: (its end, its width, the first tab or -1)."""
    n = len(text)
    i = pos
    col = 0
    tab_at = -1
    while i < n and text[i] in " \t\f":
        if text[i] == "\t":
            if tab_at < 0:
                tab_at = i
            col = (col // 4 + 1) * 4
        else:
            col += 1
        i += 1
    return i, col, tab_at


def _bad_number(text: str, start: int, end: int, line: int, line_start: int) -> Diagnostic | None:
    """S005 for a number run into letters (`0.32m`, `1.x`) or too long for Python's int, else None."""
    n = len(text)
    if end < n and _IDENT_CHAR.match(text, end):
        bad_end = end + 1
        while bad_end < n and _IDENT_CHAR.match(text, bad_end):
            bad_end += 1
        word = text[start:bad_end]
        msg = (
            f"invalid number '{word}': a number needs digits after the '.'"
            if text[end] == "."
            else f"invalid number '{word}'"
        )
        span = Span(Pos(start, line, start - line_start), Pos(bad_end, line, bad_end - line_start))
        return Diagnostic("S005", msg, span, Severity.ERROR, help=unit_help(word, text[start:end]))
    if end - start > MAX_INT_DIGITS and text[start:end].isdigit():
        span = Span(Pos(start, line, start - line_start), Pos(end, line, end - line_start))
        return Diagnostic("S005", f"integer literal too long: {end - start} digits "
                          f"(at most {MAX_INT_DIGITS})", span, Severity.ERROR,
                          help="write it with an exponent, e.g. 1e4300")
    return None


def _tick(word: str, start: int, end: int, line: int, line_start: int, fail) -> Token:
    """A `backtick name` token (S006 when it is empty)."""
    tok = Token("TICKNAME", word[1:-1], start, line, start - line_start, line, end - line_start, end)
    if len(word) == 2:
        span = Span(Pos(start, line, start - line_start), Pos(end, line, end - line_start))
        fail(Diagnostic("S006", "empty backtick name", span, Severity.ERROR))
    return tok


def _next_code_line(text: str, i: int) -> tuple[int, int]:
    """From a line start: (where the next line with code starts its tokens, its indentation),
    blank and comment-only lines skipped; (-1, 0) at the end of the text."""
    n = len(text)
    match = _TOKEN_RE.match
    while True:
        col = 0
        while i < n and text[i] in " \t\f":
            col = (col // 4 + 1) * 4 if text[i] == "\t" else col + 1
            i += 1
        if i >= n:
            return -1, 0
        if text[i] == "#":
            i = match(text, i).end()
        if i < n and text[i] in "\r\n":
            i = match(text, i).end()
            continue
        if i >= n:
            return -1, 0
        return i, col


def _token_at(text: str, i: int) -> tuple[str | None, str, int]:
    """The next token from `i`, blanks skipped: (its group name or None, its text, its end)."""
    match = _TOKEN_RE.match
    while True:
        m = match(text, i)
        if m is None:
            return None, "", i
        if m.lastgroup != "ws":
            return m.lastgroup, m.group(), m.end()
        i = m.end()


def _statement_start(text: str, i: int) -> int:
    """How a code line inside brackets begins: `_STRONG` (as only a statement can), `_PARAM_LIKE`
    (`x:`) or `_CONTINUES`."""
    kind, word, i = _token_at(text, i)
    if kind == "name" and word in _STATEMENT_KEYWORDS:
        return _STRONG
    if kind == "punct" and word == ".":
        kind, word, i = _token_at(text, i)
        if kind not in ("name", "tick") or word in KEYWORDS:
            return _CONTINUES
        kind, word, i = _token_at(text, i)
        return _STRONG if word == ":" else _CONTINUES
    if kind not in ("name", "tick") or (kind == "name" and word in KEYWORDS):
        return _CONTINUES
    while True:  # a dotted name
        kind, word, i = _token_at(text, i)
        if word != ".":
            break
        kind, word, i = _token_at(text, i)
        if kind not in ("name", "tick"):
            return _CONTINUES
    if kind == "name" and word in ("is", "becomes"):
        return _STRONG
    if word == ":":
        return _PARAM_LIKE
    return _CONTINUES


def _in_params(tokens: list[Token], brackets: list[Token]) -> bool:
    """Is the only open bracket the parameter list of a `fn` or `operator` header?"""
    if len(brackets) != 1 or brackets[0].type != "LPAR" or not tokens:
        return False
    first = tokens[0].type
    return first in ("FN", "OPERATOR") or (first == "STATIC" and len(tokens) > 1 and tokens[1].type == "FN")


def _bad_char_help(ch: str) -> str | None:
    if ch in "=<>!&|%^":
        return "OpenPLX expressions only use + - * / and unary -; values are given with ':'"
    if ch == "'":
        return 'strings use double quotes: "text"'
    if ch == "\\":
        return "there is no line continuation; open a bracket to continue an expression"
    if ch == "@" or ch == "$":
        return f'{ch} starts a path or interpolated string only right before a quote: {ch}"..."'
    return None


def _never_closed(opener: Token) -> Diagnostic:
    return Diagnostic(UNBALANCED_BRACKET, f"'{opener.value}' was never closed", _tok_span(opener), Severity.ERROR,
                      help=f"add the closing '{OPENERS[opener.value]}'")


def _tab_in_indentation(offset: int, line: int, column: int) -> Diagnostic:
    """S003 as a warning: a tab in the indentation whose block is clear either way."""
    return Diagnostic(TAB_INDENTATION, "tab character in indentation; OpenPLX indents with spaces",
                      Span(Pos(offset, line, column), Pos(offset + 1, line, column + 1)), Severity.WARNING,
                      help="indent with 4 spaces per level (`plx fmt` does this)")


def ambiguous_tab(span: Span, narrow: int, wide: int) -> Diagnostic:
    """S003 as an error (the parser finds it, knowing the blocks): the tab's width decides the block."""
    return Diagnostic(
        TAB_INDENTATION,
        f"a tab in this line's indentation makes its block ambiguous: {narrow} columns with 4-wide tabs, "
        f"{wide} with 8-wide tabs, and the two belong to different blocks",
        span,
        Severity.ERROR,
        help="indent with spaces only (4 per level); it is read as part of the deeper block",
    )


def too_deep(message: str, span: Span) -> Diagnostic:
    """S007: nesting deeper than the later (recursive) stages can walk: brackets on one line (here)
    or an expression's tree (the parser)."""
    return Diagnostic(NESTING_TOO_DEEP, message, span, Severity.ERROR)


def _tok_span(tok: Token) -> Span:
    return Span(
        Pos(tok.start_pos, tok.line, tok.column),
        Pos(tok.end_pos, tok.end_line, tok.end_column),
    )


_last: tuple[str, LexResult] | None = None


def lex(text: str) -> LexResult:
    """Lex a text; the last result is kept, since the formatter lexes the text it just parsed.

    The key is the text object itself (strings are immutable), so a hit is always the same input.
    """
    global _last
    last = _last
    if last is not None and last[0] is text:
        return last[1]
    result = Lexer(text).run()
    _last = (text, result)
    return result


def forget_last() -> None:
    """Drop the kept lex result (its tokens take about as much memory as the tree): callers that
    will not format the text they parsed (lint) call this after parsing."""
    global _last
    _last = None


# a unit written after a number: SI units need only the number; others say what the number is in SI
_SI_UNITS = {"m": "metres", "kg": "kilograms", "s": "seconds", "rad": "radians", "n": "newtons",
             "nm": "newton metres", "w": "watts", "pa": "pascals", "j": "joules", "hz": "hertz"}
_SCALED_UNITS = {"mm": ("metres", 1e-3), "cm": ("metres", 1e-2), "km": ("metres", 1e3), "g": ("kilograms", 1e-3),
                 "t": ("kilograms", 1e3), "ms": ("seconds", 1e-3), "min": ("seconds", 60.0), "h": ("seconds", 3600.0)}


def unit_help(word: str, number: str) -> str | None:
    """The help line of a number with a unit after it (`0.32m`): OpenPLX numbers carry no unit and
    every quantity is in SI units, so the number alone (converted when the unit is not SI) is meant."""
    unit = word[len(number):]
    if not unit or not unit.isalpha() or "." in unit:
        return None
    low = unit.lower()
    if low in _SI_UNITS:
        return f"OpenPLX numbers have no units (SI units are assumed, here {_SI_UNITS[low]}): write {number}"
    if low in ("deg", "degrees"):
        return f"OpenPLX numbers have no units and angles are in radians: write {number} * Math.PI / 180"
    if low in _SCALED_UNITS:
        what, scale = _SCALED_UNITS[low]
        try:
            value = float(number) * scale
        except ValueError:
            return None
        return f"OpenPLX numbers have no units (SI units are assumed, here {what}): write {value:g}"
    return None  # `2x`: a typo rather than a unit
