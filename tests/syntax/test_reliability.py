"""Defects a fuzzing campaign found in the lexer and parser (issue 14), each as the user meets it."""

from __future__ import annotations

from pathlib import Path

from plxtools.syntax import parse_text
from plxtools.syntax.lexer import lex
from tests.conftest import run_plx

HEAD = "Scene is Physics3D.System:\n"


def _codes(text: str) -> list[str]:
    return [d.code for d in parse_text(text).diagnostics]


def _write(tmp_path: Path, text: str, name: str = "x.openplx", newline: str | None = None) -> Path:
    p = tmp_path / name
    p.write_bytes(text.encode("utf-8") if newline is None else text.replace("\n", newline).encode("utf-8"))
    return p


# ------------------------------------------------------------ 1. continuation inside brackets


def test_words_ending_in_is_continue_an_open_bracket(tmp_path):
    for word in ("chassis", "this.x", "axis", "basis"):
        text = (HEAD + "    x is Real: 1\n    chassis is Physics3D.Bodies.RigidBody\n"
                "    axis is Real: 1\n    basis is Real: 1\n"
                f"    v is Real[]: [1,\n    {word}]\n")
        assert _codes(text) == [], word
    p = _write(tmp_path, HEAD + "    chassis is Physics3D.Bodies.RigidBody\n"
               "    wheel is Physics3D.Bodies.RigidBody\n    group is Simulation.CollisionGroup:\n"
               "        bodies: [wheel,\n        chassis]\n")
    r = run_plx("lint", str(p))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "S004" not in r.stdout
    r = run_plx("fmt", "--check", str(p))
    assert r.returncode == 1 and "would reformat" in r.stderr, r.stdout + r.stderr
    assert run_plx("fmt", str(p)).returncode == 0
    assert "            wheel,\n            chassis\n        ]\n" in p.read_text()


def test_fn_parameters_continued_at_the_statement_indentation():
    text = "Calc is Physics.System:\n    fn area(w: Real,\n    h: Real) -> Real\n    x is Real: 1\n"
    tree = parse_text(text)
    assert tree.diagnostics == []
    assert [type(s).__name__ for s in tree.statements[0].body] == ["Method", "Declaration"]


def test_a_never_closed_bracket_costs_one_diagnostic():
    text = HEAD + "    v is Real[]: [1, 2,\n    3\n    x is Real: 3\n    y is Real: 4\n"
    tree = parse_text(text)
    assert [(d.code, d.message) for d in tree.diagnostics] == [("S004", "'[' was never closed")]
    names = [s.path.text for s in tree.statements[0].body if hasattr(s, "path")]
    assert names[-2:] == ["x", "y"]


def test_a_never_closed_parameter_list_resumes_where_a_statement_could_start():
    # `b: Real` could continue the list; the end of the file proves it never closes, so the
    # statement is cut before `b` and the lines after it are statements again
    text = "Calc is Physics.System:\n    fn area(a: Real,\n    b: Real\n    c: 2\n"
    tree = parse_text(text)
    assert [d.code for d in tree.diagnostics] == ["S004"]
    assert tree.diagnostics[0].span.start.line == 1
    assert [s.path.text for s in tree.statements[0].body[1:]] == ["b", "c"]
    # and a statement that cannot continue ends it at once
    text = "Calc is Physics.System:\n    fn area(a: Real,\n    x is Real: 1\n"
    tree = parse_text(text)
    assert [d.code for d in tree.diagnostics] == ["S004"]
    assert tree.statements[0].body[-1].path.text == "x"


# ------------------------------------------------------------ 2. lone CR


def test_lone_cr_is_a_line_break_for_cli_positions(tmp_path):
    p = _write(tmp_path, "# header\r\rScene is Physics3D.System:\r\r    x is Real: nope\r\r")
    r = run_plx("lint", str(p))
    assert r.returncode == 1
    assert f"{p}:5:16: error N003" in r.stdout


def test_fmt_check_on_a_valid_lone_cr_file(tmp_path):
    p = _write(tmp_path, HEAD + "    # a comment\n    x is   Real: 1\n", newline="\r")
    r = run_plx("fmt", "--check", str(p))
    assert r.returncode == 1 and "would reformat" in r.stderr, r.stderr
    r = run_plx("fmt", str(p))
    assert r.returncode == 0, r.stderr
    assert p.read_bytes() == (HEAD + "    # a comment\n    x is Real: 1\n").replace("\n", "\r").encode()


def test_lexer_positions_agree_with_the_line_index_on_every_line_break():
    text = 'A is B:\r    x: 1\r\n    y: """a\rb\nc"""\n\r    z: [1,\r        2]\r'
    tree = parse_text(text)
    index = tree.index
    for line in lex(text).lines:
        for t in line.tokens:
            assert (t.line, t.column) == tuple(index.pos(t.start_pos))[1:], t
            assert (t.end_line, t.end_column) == tuple(index.pos(t.end_pos))[1:], t


# ------------------------------------------------------------ 3. huge integer literals


def test_an_integer_over_4300_digits_is_a_located_error(tmp_path):
    p = _write(tmp_path, HEAD + "    x is Int: " + "9" * 4301 + "\n    y is Int: " + "9" * 4300 + "\n")
    r = run_plx("lint", str(p))
    assert r.returncode == 1, r.stderr
    assert f"{p}:2:15: error S005 integer literal too long: 4301 digits" in r.stdout
    assert "internal error" not in r.stdout + r.stderr
    r = run_plx("fmt", str(p))
    assert r.returncode == 2 and "S005" in r.stderr and "internal error" not in r.stderr


# ------------------------------------------------------------ 5. indentation: the cause, once

TRUCK = (Path(__file__).parent / "data" / "truck.openplx").read_text(encoding="utf-8")


def _lint_lines(tmp_path: Path, text: str) -> list[str]:
    p = _write(tmp_path, text)
    r = run_plx("lint", str(p))
    return [line[len(str(p)):] for line in r.stdout.splitlines() if line.startswith(str(p))]


def test_truck_is_clean(tmp_path):
    assert _lint_lines(tmp_path, TRUCK) == []


def test_a_line_three_spaces_short_is_one_error(tmp_path):
    lines = _lint_lines(tmp_path, TRUCK.replace("        height: 0.3", "     height: 0.3"))
    assert lines == [":13:6: error S015 this line is indented 5 columns: between the block at column 4 and "
                     "the one at column 8"]


def test_a_tab_that_changes_the_block_is_one_error(tmp_path):
    lines = _lint_lines(tmp_path, TRUCK.replace("        height: 0.3", "\theight: 0.3"))
    assert len(lines) == 1 and lines[0].startswith(":13:2: error S003 a tab in this line's indentation"), lines
    assert "4 columns with 4-wide tabs, 8 with 8-wide tabs" in lines[0]


def test_a_consistent_tab_is_only_a_warning():
    text = "A is B:\n\tx: 1\n\tc is B:\n\t\ty: 2\n\tz: 3\n"
    tree = parse_text(text)
    assert [(d.code, d.severity.value) for d in tree.diagnostics] == [("S003", "warning")] * 4


def test_between_levels_keeps_the_following_lines_in_their_block():
    text = "A is B:\n    c is B:\n        a: 1\n      b: 2\n        d: 3\n    e: 4\n"
    tree = parse_text(text)
    assert [d.code for d in tree.diagnostics] == ["S015"]
    c = tree.statements[0].body[0]
    assert [s.path.text for s in c.body] == ["a", "b", "d"]
    assert [s.path.text for s in tree.statements[0].body] == ["c", "e"]
