"""The incremental parser gives exactly `parse_text`'s tree, spans included, after any edit."""

from __future__ import annotations

import random

import pytest

from plxtools.syntax.incremental import IncrementalParser, same_tree, split_chunks
from plxtools.syntax import parse_text
from tests.conftest import bundle_files, campaign_size
from tests.ide.conftest import EXAMPLE


def example() -> str:
    with open(EXAMPLE, encoding="utf-8") as fh:
        return fh.read()


def test_every_bundle_file_parses_the_same():
    for f in bundle_files():
        text = f.read_text(encoding="utf-8")
        assert same_tree(IncrementalParser().parse(text, str(f)), parse_text(text, str(f))), f


def test_chunks_start_at_top_level_statements():
    text = 'A:\n    x: """\nNot a chunk\n"""\nB is A\n# comment\nC is A:\n    y: [1,\n2]\n'
    starts = [line for line, _off in split_chunks(text)]
    assert starts == [0, 4, 6]


SNIPPETS = ["x", " ", "\n", ":", "(", "]", '"', '"""', "#", "    y: 1\n", "Foo is Bar\n", "\n\n", "é", "\t"]


@pytest.mark.parametrize("seed", range(campaign_size(6)))
def test_random_edits_match_a_full_parse(seed):
    rng = random.Random(seed)
    text = example()
    parser = IncrementalParser()
    parser.parse(text, "f.openplx")
    for _ in range(30):
        a = rng.randrange(len(text) + 1)
        b = min(len(text), a + rng.choice([0, 0, 1, 3, 10]))
        text = text[:a] + rng.choice(SNIPPETS + [""]) + text[b:]
        got = parser.parse(text, "f.openplx")
        assert same_tree(got, parse_text(text, "f.openplx")), (seed, a, b)


def test_moved_chunks_keep_exact_positions():
    text = example()
    parser = IncrementalParser()
    parser.parse(text, "f")
    edited = "# a new first line\n" + text.replace("density: 1000", "density: 1200")
    assert same_tree(parser.parse(edited, "f"), parse_text(edited, "f"))
    back = text
    assert same_tree(parser.parse(back, "f"), parse_text(back, "f"))


def test_a_tree_handed_out_is_never_changed_by_later_versions():
    """A reader may still hold version N (a request being answered) while N+1 is parsed."""
    text = example()
    parser = IncrementalParser()
    first = parser.parse(text, "f.openplx")
    # grow the text at the top: every later chunk moves
    second_text = "# a new first line\n\n" + text
    second = parser.parse(second_text, "f.openplx")
    assert same_tree(second, parse_text(second_text, "f.openplx"))
    assert same_tree(first, parse_text(text, "f.openplx"))  # the old tree still has its own positions
    assert parser.stats["reused"] > 0
    # and back: the copies made for version 2 are not changed either
    third = parser.parse(text, "f.openplx")
    assert same_tree(second, parse_text(second_text, "f.openplx"))
    assert same_tree(third, parse_text(text, "f.openplx"))
