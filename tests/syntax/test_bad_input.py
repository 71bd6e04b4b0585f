"""Hostile input: each gives a located diagnostic or is handled, never a traceback or a hang."""


from plxtools.syntax import parse_bytes, parse_text
from tests.conftest import run_plx


def codes(tree):
    return [(d.code, d.span.start.line + 1, d.span.start.column + 1) for d in tree.diagnostics]


def test_empty_file():
    tree = parse_bytes(b"")
    assert tree.statements == [] and tree.diagnostics == []


def test_binary_file():
    assert codes(parse_bytes(b"\x7fELF\x00\x01\x02garbage")) == [("S001", 1, 1)]


def test_invalid_utf8_located_and_rest_parsed():
    tree = parse_bytes(b'A is B:\n    name: "caf\xe9"\nC is D\n')
    assert codes(tree) == [("S002", 2, 15)]
    assert [s.path.text for s in tree.statements] == ["A", "C"]


def test_bom_is_accepted_and_remembered():
    tree = parse_bytes(b"\xef\xbb\xbfA is B\n")
    assert tree.diagnostics == [] and tree.had_bom and tree.statements[0].path.text == "A"


def test_crlf_positions():
    tree = parse_bytes(b"A is B:\r\n    x: 1 2\r\n")
    assert codes(tree) == [("S011", 2, 10)]
    assert tree.newline == "\r\n"


def test_tab_indentation_is_a_located_warning():
    tree = parse_bytes(b"A is B:\n\tx: 1\n")
    assert codes(tree) == [("S003", 2, 1)]
    assert tree.diagnostics[0].severity.value == "warning"
    assert len(tree.statements[0].body) == 1


def test_unterminated_triple_string():
    tree = parse_text('A is B:\n    .doc: """never\n    x: 1\n')
    assert codes(tree) == [("S009", 2, 11)]


def test_500_levels_of_blocks():
    src = "A:\n" + "".join(" " * (4 * i) + f"a{i}:\n" for i in range(1, 501)) + " " * 2004 + "x: 1\n"
    tree = parse_text(src)
    assert tree.diagnostics == []
    depth, node = 0, tree.statements[0]
    while node.body:
        node, depth = node.body[0], depth + 1
    assert depth == 501


def test_deep_brackets_are_refused_not_crashing():
    tree = parse_text("A is B:\n    x: " + "(" * 600 + "1" + ")" * 600 + "\n    y: 2\n")
    assert [c for c, _, _ in codes(tree)] == ["S007"]
    assert tree.statements[0].body[1].path.text == "y"


def test_a_large_file_parses_completely():
    """Size alone never costs a diagnostic or a statement (speed is measured in bench/)."""
    block = "M{i} is Physics3D.Bodies.RigidBody:\n    inertia.mass: {i}\n    geometry is Physics3D.Geometries.Box:\n        size: {{1, 2, 3}}\n\n"
    n = 5000
    tree = parse_text("".join(block.format(i=i) for i in range(n)))
    assert tree.diagnostics == [] and len(tree.statements) == n


def test_cli_on_binary_and_missing_files(tmp_path):
    b = tmp_path / "mesh.openplx"
    b.write_bytes(b"\x00\x01\x02")
    r = run_plx("lint", str(b))
    assert r.returncode == 1 and "S001" in r.stdout and "Traceback" not in r.stderr
    r = run_plx("lint", str(tmp_path / "nope.openplx"))
    assert r.returncode == 2 and "no such file" in r.stderr
