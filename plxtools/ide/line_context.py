"""Where the cursor is in a half-typed line, read from the real lexer's tokens (never from regular
expressions over the text): after `is`, `becomes`, `with`, `or`, a parameter's `:` or `->` a type
starts; after an attribute's `:` a value; at the start of a line a statement; after a lone `.` an
annotation.  Completion asks this, so strings, comments and backticked names mean what they mean
everywhere else."""

from __future__ import annotations

from dataclasses import dataclass

from plxtools.syntax.fragments import fragment_tokens

TYPE_KINDS = ("trait_base", "with", "becomes", "is", "or", "param", "operator_param", "returns")
_NAME = ("NAME", "TICKNAME")
_MODIFIERS = ("CONST", "OPTIONAL", "REFERENCE", "STATIC")
# a space typed after one of these asks for completion (a type or a value starts there)
SPACE_TRIGGER_TOKENS = frozenset({"IS", "BECOMES", "WITH", "OR", "REFERENCE", "COLON", "COMMA", "LPAR", "LSQB",
                                  "LBRACE", "ARROW"})


@dataclass(slots=True)
class LineContext:
    kind: str  # one of TYPE_KINDS, or "annotation", "value", "statement"
    indent: str = ""  # the line's leading whitespace
    qual: str = ""  # "A.B." typed before the word being completed
    target: str = ""  # becomes / value: the attribute path on the left ("a.b")
    decl: str = ""  # value: " is T[]" between the target and the ':'
    value: str = ""  # value: the text after the ':'


def _path_end(toks, i: int) -> int:
    """Index after a dotted path starting at toks[i] (i itself when there is none)."""
    if i >= len(toks) or toks[i].type not in _NAME:
        return i
    i += 1
    while i + 1 < len(toks) and toks[i].type == "DOT" and toks[i + 1].type in _NAME:
        i += 2
    return i


def _skip_modifiers(toks, i: int = 0) -> int:
    while i < len(toks) and toks[i].type in _MODIFIERS:
        i += 1
    return i


def _type_list_before(toks, end: int, sep: str) -> int:
    """Start of `T (sep T)*` ending just before ``end`` (types may carry `[]`), or -1."""
    i = end
    while True:
        if i >= 2 and toks[i - 1].type == "RSQB" and toks[i - 2].type == "LSQB":
            i -= 2
        j = i
        while j >= 1 and toks[j - 1].type in _NAME:
            j -= 1
            if j >= 2 and toks[j - 1].type == "DOT" and toks[j - 2].type in _NAME:
                j -= 1
            else:
                break
        if j == i:
            return -1
        if j >= 1 and toks[j - 1].type == sep:
            i = j - 1
            continue
        return j


@dataclass(slots=True)
class _Head:
    """A half-typed line cut into the tokens before the qualifier (`rest`) and the qualifier itself."""

    head: str
    toks: list
    indent: str
    qual: str
    rest: list

    @property
    def n(self) -> int:
        return len(self.rest)

    @property
    def last(self) -> str | None:
        return self.rest[-1].type if self.rest else None

    def context(self, kind: str, **fields) -> LineContext:
        return LineContext(kind, self.indent, self.qual, **fields)


_UNDECIDED = object()  # a handler below that did not recognise the line: the later checks decide


def _cut(head: str) -> _Head | None:
    toks = fragment_tokens(head)
    indent = head[: len(head) - len(head.lstrip())]
    # the qualifier being typed: `A.B.` right before the cursor
    j = len(toks)
    while j >= 2 and toks[j - 1].type == "DOT" and toks[j - 2].type in _NAME and toks[j - 1].end_pos == (
            toks[j].start_pos if j < len(toks) else len(head)):
        j -= 2
    qual = head[toks[j].start_pos:].strip() if j < len(toks) else ""
    if qual and not qual.endswith("."):
        qual = ""
    if qual and head.rstrip() != head:  # `A. ` is not a qualifier any more
        return None
    return _Head(head, toks, indent, qual, toks[:j] if qual else toks)


def _after_is(h: _Head):
    rest, n = h.rest, h.n
    if n == 3 and rest[0].type == "TRAIT" and rest[1].type in _NAME:
        return h.context("trait_base")
    k = _skip_modifiers(rest)
    if _path_end(rest, k) == n - 1 and n - 1 > k:
        return h.context("is")
    return None


def _after_with(h: _Head):
    """`with T`, `with T1, T2, `: another trait starts."""
    rest = h.rest
    if not any(t.type == "WITH" for t in rest):
        return _UNDECIDED
    w = max(i for i, t in enumerate(rest) if t.type == "WITH")
    if h.last == "WITH" or _type_list_before(rest, h.n - 1, "COMMA") == w + 1:
        return h.context("with")
    return _UNDECIDED


def _after_becomes(h: _Head):
    rest, n = h.rest, h.n
    k = _skip_modifiers(rest)
    if _path_end(rest, k) == n - 1 and n - 1 > k:
        return h.context("becomes", target=h.head[rest[k].start_pos:rest[n - 2].end_pos])
    return None


def _after_or(h: _Head):
    start = _type_list_before(h.rest, h.n - 1, "OR")
    if start >= 1 and h.rest[start - 1].type == "IS":
        return h.context("or")
    return None


def _after_arrow(h: _Head):
    return h.context("returns") if h.n >= 2 and h.rest[-2].type == "RPAR" else _UNDECIDED


def _open_paren(rest: list) -> int | None:
    """Index of the `(` that is still open at the end of `rest`, if any."""
    depth = 0
    for i in range(len(rest) - 1, -1, -1):
        t = rest[i].type
        if t == "RPAR":
            depth += 1
        elif t == "LPAR":
            if depth == 0:
                return i
            depth -= 1
    return None


def _after_colon(h: _Head):
    """`fn f(name: ` or `operator +(name: `: a parameter's type starts (a value is decided later)."""
    rest, n = h.rest, h.n
    if n < 3 or rest[-2].type not in _NAME or _open_paren(rest) is None:
        return _UNDECIDED
    k = _skip_modifiers(rest)
    if k < n and rest[k].type == "FN":
        return h.context("param")
    if rest[0].type == "OPERATOR":
        return h.context("operator_param")
    return _UNDECIDED


_BY_LAST = {"IS": _after_is, "WITH": _after_with, "COMMA": _after_with, "BECOMES": _after_becomes,
            "OR": _after_or, "ARROW": _after_arrow, "COLON": _after_colon}


def _value(h: _Head) -> LineContext | None:
    """A value: [modifiers] path [is|becomes T ...] ':' value."""
    toks, head = h.toks, h.head
    k = _skip_modifiers(toks)
    p = _path_end(toks, k)
    if p <= k:
        return None
    c = p
    if c < len(toks) and toks[c].type in ("IS", "BECOMES"):
        c += 1
        while c < len(toks) and toks[c].type != "COLON" and toks[c].type not in ("STRING",):
            c += 1
    if c < len(toks) and toks[c].type == "COLON":
        return h.context("value", target=head[toks[k].start_pos:toks[p - 1].end_pos],
                         decl=head[toks[p - 1].end_pos:toks[c].start_pos], value=head[toks[c].end_pos:])
    return None


def classify(head: str) -> LineContext | None:
    """The context of the end of ``head`` (the line up to the word being typed), or None: first by
    the last token before the qualifier (`_BY_LAST`), then a new statement, an annotation, a value."""
    h = _cut(head)
    if h is None:
        return None
    after = _BY_LAST.get(h.last)
    if after is not None:
        found = after(h)
        if found is not _UNDECIDED:
            return found
    if not h.rest:
        return h.context("statement")
    if h.n == 1 and h.last == "DOT" and not h.qual and head.endswith("."):
        return LineContext("annotation", h.indent)
    return _value(h)


def word_before(text: str) -> str:
    """The identifier being typed at the end of ``text``."""
    i = len(text)
    while i > 0 and (text[i - 1].isalnum() or text[i - 1] == "_"):
        i -= 1
    w = text[i:]
    return w if w and (w[0].isalpha() or w[0] == "_") else ""


def space_triggers(before: str) -> bool:
    """A space typed at the end of ``before`` asks for completion when a type or value starts there."""
    if not before.endswith((" ", "\t")):
        return False
    toks = fragment_tokens(before)
    return bool(toks) and toks[-1].type in SPACE_TRIGGER_TOKENS
