"""What the LALR fallback hands lark, and where its parser comes from: imported on the first line
the fast path leaves to the grammar (importing lark costs about 35 ms, and most runs never need it).

Building the LALR tables from openplx.lark takes 0.1-0.3 s, a cold run's largest single cost when
a file needs the fallback. lark's own grammar cache is a pickle file anyone able to write the
cache folder could plant, so plx keeps lark's serialized parser as an entry of its own cache
instead (kind `grammars`): authenticated with the per-user secret like the bundle program and
unpickled only after its tag is checked; keyed by the grammar text, the lark and Python versions
and plxtools' code stamp (which covers this module and the grammar file). A missing, planted or
unreadable entry is a miss: the parser is built and the entry rewritten.

The classes live at module level so that the serialized parser refers to them by name."""

from __future__ import annotations

import pickle
import sys

import lark
from lark import Lark, Transformer
from lark.lexer import Lexer as LarkLexer

from plxtools.syntax.parser import _Build

KIND = "grammars"


class PassThrough(LarkLexer):
    """The logical line is already tokenised; hand its tokens to the LALR parser as they are."""

    def __init__(self, lexer_conf):  # noqa: D401 - lark's lexer protocol
        pass

    def lex(self, data, parser_state=None):
        return iter(data)


class LarkBuild(_Build, Transformer):
    """parser._Build as the lark Transformer whose methods build each rule's node."""


def _options() -> dict:
    return dict(parser="lalr", lexer=PassThrough, transformer=LarkBuild(), maybe_placeholders=True)


def entry_key(grammar: str) -> str | None:
    """The cache key of the parser built from `grammar` by this code, or None (no usable cache)."""
    from plxtools.cache import folder, store
    from plxtools.cache.stamp import code_stamp

    if folder.root() is None or folder.secret() is None:
        return None
    h = store.new_hash()
    for part in (lark.__version__, sys.version, code_stamp(), grammar):
        h.update(part.encode("utf-8", "surrogatepass") + b"\0")
    return h.hexdigest()


def _load(payload: bytes) -> Lark | None:
    try:
        saved = pickle.loads(payload)  # authenticated: store.get checked the tag
        # Lark.load's own path (lark's cache=True does the same), with our transformer object
        return Lark.__new__(Lark)._load(saved, transformer=LarkBuild())
    except Exception:  # an entry from code that no longer matches: build instead
        return None


def _serialize(parser: Lark) -> bytes:
    from lark.grammar import Rule
    from lark.lexer import TerminalDef

    data, memo = parser.memo_serialize([TerminalDef, Rule])
    data["options"] = {k: v for k, v in data["options"].items() if k != "transformer"}
    return pickle.dumps({"data": data, "memo": memo}, protocol=pickle.HIGHEST_PROTOCOL)


def build_parser(grammar: str, use_cache: bool = True) -> Lark:
    """The LALR parser for `grammar`: the cached one when its entry is authentic, else built
    (and stored for the next run)."""
    from plxtools.cache import store

    key = entry_key(grammar) if use_cache else None
    if key is not None:
        payload = store.get(KIND, key)
        if payload is not None:
            loaded = _load(payload)
            if loaded is not None:
                return loaded
    parser = Lark(grammar, **_options())
    if key is not None:
        try:
            payload = _serialize(parser)
        except (pickle.PicklingError, TypeError, AttributeError):
            return parser
        store.put(KIND, key, payload)
    return parser
