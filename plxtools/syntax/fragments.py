"""Tokens of a fragment of source (a half-typed line, a header, a postfix chain) for editor features.

The editor asks questions about text that need not parse ("what does `a.b(c).` name?"). It uses
the real lexer for them rather than its own regular expressions, so strings, comments, backticked
names and brackets mean the same thing everywhere.
"""

from __future__ import annotations

from plxtools.syntax.lexer import Lexer, Token


def fragment_tokens(text: str) -> list[Token]:
    """The tokens of `text`, all logical lines joined; comments and layout are dropped.

    The lexer reports what it cannot read as diagnostics, so any fragment yields the tokens it has.
    """
    result = Lexer(text).run()
    return [tok for line in result.lines for tok in line.tokens]


def dotted_name(tokens: list[Token], i: int) -> tuple[list[str], int]:
    """The dotted name starting at tokens[i] (`A.B.C`, backticked parts unquoted) and the index after it."""
    parts: list[str] = []
    while i < len(tokens) and tokens[i].type in ("NAME", "TICKNAME"):
        parts.append(str(tokens[i]))
        i += 1
        if i + 1 < len(tokens) and tokens[i].type == "DOT" and tokens[i + 1].type in ("NAME", "TICKNAME"):
            i += 1
            continue
        break
    return parts, i


def matching_close(tokens: list[Token], i: int) -> int:
    """The index of the bracket closing tokens[i] (an opener), or -1 when it is never closed."""
    pairs = {"LPAR": "RPAR", "LSQB": "RSQB", "LBRACE": "RBRACE"}
    stack = [pairs[tokens[i].type]]
    for j in range(i + 1, len(tokens)):
        t = tokens[j].type
        if t in pairs:
            stack.append(pairs[t])
        elif t == stack[-1]:
            stack.pop()
            if not stack:
                return j
    return -1


def ends_in_comment_or_string(text: str) -> bool:
    """Does the end of `text` (a line up to the cursor) sit in a comment or in a string not yet closed?"""
    result = Lexer(text).run()
    if result.comments:
        return True  # a comment runs to the end of its line
    tokens = [tok for line in result.lines for tok in line.tokens]
    if not tokens or tokens[-1].type != "STRING" or tokens[-1].end_pos != len(text):
        return False
    body = str(tokens[-1]).lstrip("@$")
    quote = '"""' if body.startswith('"""') else '"'
    return len(body) < 2 * len(quote) or not body.endswith(quote)
