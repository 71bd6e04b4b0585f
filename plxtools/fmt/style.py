"""The canonical style's constants and its one spacing table (see docs/formatter.md).

Kept apart from the printer so that every layout decision that is a *rule* (rather than
bookkeeping) can be read in one place.
"""

from __future__ import annotations

INDENT = 4  # spaces per block level
COMMENT_GAP = 2  # spaces between code and a trailing comment (the least; aligned runs may use more)
MAX_BLANK_TOP = 2  # blank lines kept between top-level items
MAX_BLANK_NESTED = 1  # blank lines kept between items inside a block

# Tokens after which a `-` is binary and a `(` or `[` is a call, index or array suffix.
OPERAND_END = frozenset({"NAME", "TICKNAME", "NUMBER", "STRING", "THIS", "TRUE", "FALSE", "RPAR", "RSQB", "RBRACE"})
OPENERS = frozenset({"LPAR", "LSQB", "LBRACE"})
CLOSERS = frozenset({"RPAR", "RSQB", "RBRACE"})

# Kinds the printer gives some tokens on top of their lexer type.
NEG = "NEG"  # unary minus
OPSYM = "OPSYM"  # the symbol of an `operator +(...)` declaration

_NO_SPACE_BEFORE = frozenset({"COMMA", "COLON", "DOT", "RPAR", "RSQB", "RBRACE"})
_NO_SPACE_AFTER = frozenset({"LPAR", "LSQB", "LBRACE", "DOT", NEG, OPSYM})


def token_kinds(types: list[str]) -> list[str]:
    """The spacing kind of each token of one logical line: its type, or NEG / OPSYM."""
    kinds = list(types)
    for i, t in enumerate(types):
        if t == "MINUS" and (i == 0 or types[i - 1] not in OPERAND_END):
            kinds[i] = NEG
    if len(types) > 1 and types[0] == "OPERATOR":
        kinds[1] = OPSYM
    return kinds


def gap(prev: str, cur: str) -> str:
    """The space between two tokens on one line, given their kinds ("" or " ")."""
    if cur in _NO_SPACE_BEFORE or prev in _NO_SPACE_AFTER:
        return ""
    if cur in ("LPAR", "LSQB") and prev in OPERAND_END:
        return ""  # f(x), a[0], Real[]
    return " "


def blank_cap(depth: int) -> int:
    return MAX_BLANK_TOP if depth == 0 else MAX_BLANK_NESTED
