"""What the LALR fallback hands lark: imported on the first line the fast path leaves to the
grammar (importing lark costs about 35 ms, and most runs never need it). The classes live at
module level so that lark's grammar cache can pickle a reference to them."""

from __future__ import annotations

from lark import Transformer
from lark.lexer import Lexer as LarkLexer

from plxtools.syntax.parser import _Build


class PassThrough(LarkLexer):
    """The logical line is already tokenised; hand its tokens to the LALR parser as they are."""

    def __init__(self, lexer_conf):  # noqa: D401 - lark's lexer protocol
        pass

    def lex(self, data, parser_state=None):
        return iter(data)


class LarkBuild(_Build, Transformer):
    """parser._Build as the lark Transformer whose methods build each rule's node."""
