"""Misspelt keywords: which keyword a name that broke a line was probably meant to be."""

from __future__ import annotations

from plxtools.syntax.lexer import KEYWORDS


def closest_keyword(word: str, expected_types: set[str] | None = None) -> str | None:
    """The keyword `word` is a likely typo of (`becoms` -> `becomes`), among those the parser
    expected at that point when `expected_types` (token type names such as "BECOMES") is given."""
    if not word or word in KEYWORDS:
        return None
    options = [kw for kw, ty in KEYWORDS.items() if expected_types is None or ty in expected_types]
    options = [kw for kw in options if len(kw) > 2]  # 'is', 'or', 'fn', 'as' match too many names
    import difflib  # (only a line that did not parse needs it)

    close = difflib.get_close_matches(word, options, n=1, cutoff=0.75)
    return close[0] if close else None
