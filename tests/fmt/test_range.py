"""format_range: the language server's range formatting (0-based, inclusive lines)."""

from __future__ import annotations

from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from plxtools.diagnostics import Edit
from plxtools.fmt import format_range
from plxtools.syntax import ast, parse_text
from tests.conftest import campaign_size
from tests.fmt.programs import programs

SOURCE = (
    "A is Base:\n"  # 0
    "    x:   1\n"  # 1
    "    y:    [1,2]\n"  # 2
    "    fields: [\n"  # 3
    "          a,b,\n"  # 4
    "       c]\n"  # 5
    "B is   Base\n"  # 6
)


def apply(text: str, edits: list[Edit]) -> str:
    for e in sorted(edits, key=lambda e: e.start, reverse=True):
        text = text[: e.start] + e.text + text[e.end :]
    return text


def test_only_the_statements_in_the_range_change():
    edits = format_range(SOURCE, 1, 1)
    assert all(isinstance(e, Edit) for e in edits)
    assert apply(SOURCE, edits) == SOURCE.replace("x:   1", "x: 1")


def test_a_range_inside_a_statement_grows_to_the_whole_statement():
    out = apply(SOURCE, format_range(SOURCE, 4, 4))
    assert out == SOURCE.replace(
        "    fields: [\n          a,b,\n       c]\n", "    fields: [\n        a, b,\n        c\n    ]\n"
    )


def test_edits_are_offsets_into_the_original_and_as_small_as_whole_lines_allow():
    edits = format_range(SOURCE, 0, 6)
    assert len(edits) == 1
    e = edits[0]
    assert SOURCE[: e.start].endswith("A is Base:\n")  # the unchanged first line is not part of it
    assert SOURCE[e.end :] == "\n"  # B's line changes too, so the edit reaches it


def test_formatted_ranges_blank_ranges_and_broken_files_give_no_edits():
    assert format_range("A is Base:\n    x: 1\n", 0, 1) == []
    assert format_range("A is Base:\n\n\n    x: 1\n", 1, 2) == []
    assert format_range("A is Base:\n    x: = 1\n    y:   2\n", 2, 2) == []


def test_indentation_follows_the_first_selected_statement():
    text = "A is Base:\n  b is B:\n    c:   [1,2]\n  d:   2\n"
    out = apply(text, format_range(text, 1, 2))
    assert out == "A is Base:\n  b is B:\n      c: [1, 2]\n  d:   2\n"


def test_a_selection_across_levels_grows_to_the_top_level_definition_when_needed():
    text = "A is Base:\n  b is B:\n    c:   1\n  d: 2\nE is F\n"
    out = apply(text, format_range(text, 2, 3))
    assert out == "A is Base:\n    b is B:\n        c: 1\n    d: 2\nE is F\n"
    assert ast.structure(parse_text(out).statements) == ast.structure(parse_text(text).statements)


def test_bom_and_crlf():
    text = "\ufeffA is Base:\r\n    x:   1\r\n    y:  2\r\n"
    out = apply(text, format_range(text, 1, 1))
    assert out == "\ufeffA is Base:\r\n    x: 1\r\n    y:  2\r\n"


def test_comments_in_the_range_are_reindented():
    text = "A is Base:\n    x: 1\n        # note\n    y:   2  #  trailing\n"
    out = apply(text, format_range(text, 2, 3))
    assert out == "A is Base:\n    x: 1\n    # note\n    y: 2  #  trailing\n"


@settings(max_examples=campaign_size(80), deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(programs(), st.integers(0, 60), st.integers(0, 20))
def test_any_range_of_any_program_keeps_the_meaning(source, start, length):
    tree = parse_text(source)
    assume(not tree.has_errors)
    out = apply(source, format_range(source, start, start + length))
    after = parse_text(out)
    assert not after.has_errors
    assert ast.structure(after.statements) == ast.structure(tree.statements)
    assert [c.text.rstrip() for c in after.comments] == [c.text.rstrip() for c in tree.comments]
