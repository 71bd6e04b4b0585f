"""Case files: valid snippets parse clean; broken ones give exactly the errors in their header."""

import re
from pathlib import Path

import pytest

from plxtools.syntax import ast, parse_file
from tests.conftest import CASES

VALID = sorted((CASES / "syntax" / "valid").glob("*.openplx"))
INVALID = sorted((CASES / "syntax" / "invalid").glob("*.openplx"))
EXPECT = re.compile(r"^# expect: (\d+):(\d+) (\w+)$", re.M)


@pytest.mark.parametrize("path", VALID, ids=lambda p: p.name)
def test_valid_case_parses_clean(path: Path):
    tree = parse_file(path)
    assert [d.message for d in tree.diagnostics] == []
    assert tree.statements, "a valid case must produce statements"


@pytest.mark.parametrize("path", INVALID, ids=lambda p: p.name)
def test_invalid_case_reports_expected_errors(path: Path):
    expected = [(int(a), int(b), c) for a, b, c in EXPECT.findall(path.read_text())]
    assert expected, "an invalid case must declare its expected errors"
    tree = parse_file(path)
    got = [(d.span.start.line + 1, d.span.start.column + 1, d.code) for d in tree.diagnostics]
    assert got == expected


def test_constructs_tree_shape():
    tree = parse_file(CASES / "syntax" / "valid" / "constructs.openplx")
    kinds = [type(s).__name__ for s in tree.statements]
    assert kinds[:6] == ["Import", "Import", "OperatorDecl", "OperatorDecl", "TraitDef", "TraitDef"]
    arm = next(s for s in tree.statements if isinstance(s, ast.Declaration) and s.path.text == "Arm")
    members = {s.path.text: s for s in arm.body if isinstance(s, ast.Declaration)}
    assert members["optional_anchor" if False else "anchor"].optional and members["anchor"].reference
    assert members["links"].type.alternatives[0].array
    assert [a.name.text for a in members["shape"].type.alternatives] == ["Real", "Math.Vec2"]
    assert [t.text for t in members["tool"].type.traits] == ["Colored", "Shiny"]
    assert members["inertia"].keyword == "becomes"
    assert members["dotted.name"].path.parts[0].backtick
    assert members["data_dir"].value.kind == "interp"
    assert members["path_string"].value.kind == "path"
    # precedence: -PI / 4 + 2 * (1 - 0.5) / 3  ==  ((-PI) / 4) + ((2 * (1 - 0.5)) / 3)
    angle = members["angle"].value
    assert isinstance(angle, ast.Binary) and angle.op == "+"
    assert isinstance(angle.left, ast.Binary) and angle.left.op == "/"
    assert isinstance(angle.left.left, ast.Unary)
    assert isinstance(angle.right, ast.Binary) and angle.right.op == "/"
    assert isinstance(members["values"].value, ast.Array) and len(members["values"].value.items) == 3
    link = members["link"]
    assert [type(s).__name__ for s in link.body] == ["Assignment", "Declaration"]
    pair = next(s for s in tree.statements if isinstance(s, ast.Declaration) and s.path.text == "Pair")
    doc = pair.body[0]
    assert isinstance(doc, ast.Annotation) and "# contain hashes" in doc.value.value


def test_spans_are_exact():
    src = "A is B:\n    mass: 10 + 2\n"
    tree = parse_file_text(src)
    stmt = tree.statements[0]
    assert (stmt.span.start.line, stmt.span.end.line, stmt.span.end.column) == (0, 1, 16)
    member = stmt.body[0]
    value = member.value
    assert src[value.span.start.offset:value.span.end.offset] == "10 + 2"
    assert (value.span.start.line, value.span.start.column) == (1, 10)


def parse_file_text(src):
    from plxtools.syntax import parse_text

    return parse_text(src)


def test_misaligned_siblings_stay_in_one_block():
    tree = parse_file(CASES / "syntax" / "valid" / "indentation.openplx")
    mis = next(s for s in tree.statements if s.path.text == "Misaligned")
    assert [type(s).__name__ for s in mis.body] == ["Annotation", "Assignment", "Assignment"]
    nine = next(s for s in tree.statements if s.path.text == "NineSpaces")
    assert len(nine.body) == 1 and len(nine.body[0].body) == 1


def test_comments_are_kept_with_positions():
    tree = parse_file(CASES / "syntax" / "valid" / "indentation.openplx")
    trailing = [c for c in tree.comments if not c.own_line]
    assert [c.text for c in trailing] == ["# trailing comment"]
    assert tree.comments[0].own_line and tree.comments[0].span.start.line == 0
