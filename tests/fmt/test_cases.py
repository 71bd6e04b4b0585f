"""Case files: tests/cases/fmt/<name>.input.openplx must format to <name>.output.openplx.

Every case is also checked to mean the same as its input and to be a fixed point; the same cases
are run again with CRLF line endings and with a BOM, built from the bytes so no editor or git
setting can blur them.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from plxtools.fmt import format_bytes, format_text
from tests.fmt.helpers import assert_fixed_point, assert_same_meaning

CASES = Path(__file__).resolve().parents[1] / "cases" / "fmt"
NAMES = sorted(p.name[: -len(".input.openplx")] for p in CASES.glob("*.input.openplx"))
BOM = b"\xef\xbb\xbf"


def _pair(name: str) -> tuple[bytes, bytes]:
    return (CASES / f"{name}.input.openplx").read_bytes(), (CASES / f"{name}.output.openplx").read_bytes()


def test_every_case_has_an_expected_output():
    assert len(NAMES) >= 15
    for name in NAMES:
        assert (CASES / f"{name}.output.openplx").is_file(), name


@pytest.mark.parametrize("name", NAMES)
def test_case(name):
    source, expected = _pair(name)
    result = format_bytes(source, name)
    assert result.ok, result.internal_error or [d.message for d in result.diagnostics]
    assert result.text == expected.decode("utf-8")
    assert result.changed == (source != expected)
    assert_same_meaning(source.decode("utf-8"), result.text)
    assert_fixed_point(result.text)


@pytest.mark.parametrize("name", NAMES)
def test_case_with_crlf(name):
    source, expected = _pair(name)
    result = format_bytes(source.replace(b"\n", b"\r\n"), name)
    assert result.ok
    assert result.text.encode("utf-8") == expected.replace(b"\n", b"\r\n")


@pytest.mark.parametrize("name", ["comments", "literals_multi_line", "tutorial_boxtruck"])
def test_case_with_bom(name):
    source, expected = _pair(name)
    result = format_bytes(BOM + source, name)
    assert result.had_bom and result.text == expected.decode("utf-8")
    text_result = format_text((BOM + source).decode("utf-8"))
    assert text_result.text == (BOM + expected).decode("utf-8")


def test_mixed_line_endings_follow_the_first_line_but_strings_keep_theirs():
    source = b'A is B:\r\n    x:   1\n    .doc: """one\ntwo\r\nthree"""\r\n'
    result = format_bytes(source)
    assert result.text.encode() == b'A is B:\r\n    x: 1\r\n    .doc: """one\ntwo\r\nthree"""\r\n'


def test_expected_outputs_are_fixed_points():
    for name in NAMES:
        _, expected = _pair(name)
        result = format_bytes(expected, name)
        assert result.ok and not result.changed, name


def test_the_projects_example_models_are_already_formatted():
    examples = sorted((CASES.parents[2] / "examples").rglob("*.openplx"))
    assert examples
    for path in examples:
        result = format_bytes(path.read_bytes(), str(path))
        assert result.ok and not result.changed, path
