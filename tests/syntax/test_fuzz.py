"""Property tests (bounded, fast): the lexer and parser never raise on any text, and every position
they report is inside the text and agrees with the one line index (\\r\\n, \\r and \\n all break)."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from plxtools.syntax import ast, parse_bytes, parse_text
from plxtools.syntax.lexer import lex
from tests.conftest import bundle_files, campaign_size

SETTINGS = settings(max_examples=campaign_size(150), deadline=None, suppress_health_check=[HealthCheck.too_slow])

PIECES = [
    "Scene", "is", "becomes", "Physics3D.System", "x", "chassis", "this", "axis", "fn", "const", "trait",
    "with", "import", "reference", "optional", ":", ".", ",", "(", ")", "[", "]", "{", "}", "+", "-",
    "*", "/", "->", "1", "2.5", "1e3", "9" * 4301, '"s"', '"""t\n"""', '"""', '"', "`a.b`", "``", "#c",
    "# plx: ignore[N003]", "# plx: fmt: off", " ", "    ", "\t", "\n", "\r", "\r\n", "\f", "\u2028",
    "\x00", "é", "=",
]
texts = st.lists(st.sampled_from(PIECES), max_size=60).map("".join)
BUNDLES = [p.read_bytes() for p in bundle_files()[:40]]


def _check_positions(tree: ast.File) -> None:
    text, index = tree.text, tree.index
    for d in tree.diagnostics:
        for p in (d.span.start, d.span.end):
            assert 0 <= p.offset <= len(text), d
            assert (p.line, p.column) == tuple(index.pos(p.offset))[1:], d
        assert d.span.start.offset <= d.span.end.offset, d
    for s in ast.walk_statements(tree.statements):
        assert 0 <= s.span.start.offset <= s.span.end.offset <= len(text)
        assert (s.header.start.line, s.header.start.column) == tuple(index.pos(s.header.start.offset))[1:]
    for line in lex(text).lines:
        for t in line.tokens:
            assert (t.line, t.column) == tuple(index.pos(t.start_pos))[1:], t


@SETTINGS
@given(texts)
def test_any_text_parses_without_raising_and_positions_are_valid(text):
    _check_positions(parse_text(text))


@SETTINGS
@given(st.binary(max_size=200))
def test_any_bytes_parse_without_raising(data):
    tree = parse_bytes(data)
    assert tree.text is not None


@SETTINGS
@given(st.sampled_from(BUNDLES), st.integers(0, 10_000), st.sampled_from(PIECES), st.integers(0, 3))
def test_mutated_bundle_files_parse_and_stay_located(data, at, piece, cut):
    text = data.decode("utf-8")
    at %= len(text) + 1
    mutated = text[:at] + piece + text[at + cut:]
    _check_positions(parse_text(mutated))
