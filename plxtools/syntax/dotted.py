"""Dotted names as the lexer sees them (`Physics3D.Bodies.RigidBody`, `hinge.connectors`), in code
only: comments and strings are not names. Migration's rewrites and the inference of the release a
file was written for read the same runs."""

from __future__ import annotations

from collections.abc import Iterator

from plxtools.syntax.lexer import lex


def dotted_runs(text: str) -> Iterator[list]:
    """The NAME tokens of each longest run `a.b.c` in `text` (a run of one name included)."""
    for line in lex(text).lines:
        toks = line.tokens
        i = 0
        while i < len(toks):
            if toks[i].type != "NAME" or (i > 0 and toks[i - 1].type == "DOT"):
                i += 1
                continue
            j = i
            while j + 2 < len(toks) and toks[j + 1].type == "DOT" and toks[j + 2].type == "NAME":
                j += 2
            yield [toks[k] for k in range(i, j + 1, 2)]
            i = j + 1
