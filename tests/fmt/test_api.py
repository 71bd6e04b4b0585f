"""format_text / format_bytes: refusals, the safety net, and what the API imports."""

from __future__ import annotations

import subprocess
import sys

import pytest

from plxtools.fmt import FormatResult, format_bytes, format_text
from plxtools.fmt import api as fmt_api
from plxtools.fmt.document import Layout
from tests.fmt.helpers import REPO


def test_syntax_errors_refuse_the_file_with_located_diagnostics():
    result = format_text("A:\n    x: = 1\n    y:    2\n", "bad.openplx")
    assert isinstance(result, FormatResult)
    assert result.text is None and not result.ok
    assert [(d.code, d.span.start.line, d.span.start.column) for d in result.diagnostics] == [("S008", 1, 7)]
    assert result.internal_error is None


def test_warnings_do_not_refuse_tabs_are_fixed():
    result = format_text("A:\n\tx:  1\n")
    assert result.ok and result.text == "A:\n    x: 1\n"


def test_unchanged_text_is_reported_unchanged():
    result = format_text("A is B:\n    x: 1\n")
    assert result.ok and not result.changed


def test_empty_and_blank_files():
    assert format_text("").text == ""
    assert format_text("\n\n  \n").text == ""


@pytest.mark.parametrize(
    "wrong",
    [
        lambda text: text.replace("x: 1", "x: 2"),  # a changed value
        lambda text: text.replace("# keep", "# kept"),  # a changed comment
        lambda text: text.replace("    x: 1", "x: 1"),  # a changed block structure
        lambda text: text + "   junk is = \n",  # output that does not parse
    ],
)
def test_output_that_changes_the_meaning_is_never_returned(monkeypatch, wrong):
    real = fmt_api.layout_tree

    def broken(tree):
        good = real(tree)
        return Layout(wrong(good.text), good.pieces)

    monkeypatch.setattr(fmt_api, "layout_tree", broken)
    result = format_text("A:\n  x:   1  # keep\n")
    assert result.text is None
    assert result.internal_error


def test_unstable_output_is_never_returned(monkeypatch):
    real = fmt_api.layout_tree
    calls = []

    def flapping(tree):
        good = real(tree)
        calls.append(1)
        return Layout(good.text + "\n" * (len(calls) % 2), good.pieces)

    monkeypatch.setattr(fmt_api, "layout_tree", flapping)
    result = format_text("A:\n  x: 1\n")
    assert result.text is None and "unstable" in result.internal_error


def test_bom_is_kept_by_format_text_and_reported_by_format_bytes():
    assert format_text("\ufeffA:\n  x: 1\n").text == "\ufeffA:\n    x: 1\n"
    result = format_bytes(b"\xef\xbb\xbfA:\r\n  x: 1\r\n")
    assert result.had_bom and result.text == "A:\r\n    x: 1\r\n"


def test_binary_and_invalid_utf8_are_refused():
    assert format_bytes(b"A:\x00\x01").diagnostics[0].code == "S001"
    assert "S002" in {d.code for d in format_bytes(b"A:\n    x: 1 \xff\n").diagnostics}


HEAVY = ("mujoco", "numpy", "pygls", "lsprotocol", "rich")


def _imported_after(code: str) -> set[str]:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=REPO, check=True)
    return set(out.stdout.split())


def test_api_imports_nothing_heavy():
    mods = _imported_after(
        "import sys; from plxtools.fmt import format_text, format_range; "
        "format_text('A:\\n  x: 1\\n'); format_range('A:\\n  x: 1\\n', 0, 1); print(*sys.modules)"
    )
    assert not {m.split(".")[0] for m in mods} & set(HEAVY)


def test_fmt_check_on_one_file_imports_nothing_heavy(tmp_path):
    f = tmp_path / "one.openplx"
    f.write_text("A:\n    x: 1\n")
    proc = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "plxtools", "fmt", "--check", str(f)],
        capture_output=True,
        text=True,
        cwd=REPO,
    )
    assert proc.returncode == 0, proc.stderr
    imported = {line.split("|")[-1].strip().split(".")[0] for line in proc.stderr.splitlines() if "|" in line}
    # every line of the file is built by the parser's fast path: lark (the LALR fallback) stays unloaded
    assert "plxtools" in imported and "lark" not in imported
    assert not imported & set(HEAVY)
